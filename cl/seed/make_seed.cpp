// Makes the seed (cl/program_seed.h): every kernel entry's program built from
// source on this machine's OpenCL device, launched once (cl/opencl_prime.h),
// and stored as program cache files in OUT_DIR. CMake runs it after the
// library is built (cmake/penumbra_cl_seed.cmake) and installs OUT_DIR beside
// the library.
//
//   penumbra_cl_seed OUT_DIR
//
// A machine with no usable OpenCL device (or a driver that fails) gets no
// seed, a note saying so, and exit status 0: the seed only saves the first
// run's compile, and the build must not fail for want of it.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include "cl/opencl_programs.h"
#include "cl/opencl_runtime.h"
#include "host/backend/kernel_id.h"

namespace fs = std::filesystem;
using namespace penumbra;
using namespace penumbra::cl_backend;

namespace {

// PoCL's cache and ours go to a folder of their own beside OUT_DIR, so that
// the user's caches are neither read nor written; set before any OpenCL call.
fs::path use_private_caches(const fs::path& out)
{
    fs::path work = out;
    work += "-work";
    std::error_code ignored;
    fs::remove_all(work, ignored);
    ::setenv("PENUMBRA_CACHE_DIR", work.c_str(), 1);
    ::unsetenv("POCL_CACHE_DIR");
    return work;
}

int make_seed(const fs::path& out)
{
    Runtime runtime(DeviceChoice::Any, ProgramCache(out), ProgramCache());
    KernelPrograms programs(runtime);
    programs.build_all();
    std::printf("penumbra_cl_seed: %d programs for %s (%s) in %.1f s into %s\n", programs.programs_built(),
                runtime.device_info().device_name.c_str(), runtime.device_info().driver_version.c_str(),
                programs.build_seconds(), out.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: penumbra_cl_seed OUT_DIR\n");
        return 2;
    }
    const fs::path out = argv[1];
    std::error_code error;
    fs::remove_all(out, error);  // a seed of an older build must not survive
    fs::create_directories(out, error);
    if (error) {
        std::fprintf(stderr, "penumbra_cl_seed: cannot create %s: %s\n", out.c_str(), error.message().c_str());
        return 1;
    }
    const fs::path work = use_private_caches(out);
    int status = 0;
    try {
        status = make_seed(out);
    } catch (const std::exception& failure) {
        fs::remove_all(out, error);
        fs::create_directories(out, error);  // empty: installed as such, read as a miss
        std::printf("penumbra_cl_seed: no seed made (%s); OpenCL programs build from source on first use\n",
                    failure.what());
    }
    fs::remove_all(work, error);
    return status;
}
