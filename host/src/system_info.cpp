#include "penumbra/system_info.h"

#include <cstdlib>
#include <filesystem>

#include "penumbra/config.h"
#include "penumbra/context.h"
#include "penumbra/error.h"
#include "simd/cpu_kernels.h"
#if PENUMBRA_OPENCL
#include "cl/opencl_backend.h"
#include "cl/opencl_runtime.h"
#include "cl/program_cache.h"
#include "cl/program_seed.h"
#endif

namespace penumbra {
namespace {

#if PENUMBRA_OPENCL
// The program files of the seed (cl/program_seed.h); 0 when it is missing.
int count_seed_programs(const std::string& directory)
{
    std::error_code error;
    int count = 0;
    if (directory.empty()) return 0;
    for (std::filesystem::directory_iterator it(directory, error), end; !error && it != end; it.increment(error))
        count += it->path().extension() == ".bin" ? 1 : 0;
    return count;
}
#endif

// A context builds a kernel's program on first use; `info --verbose` times
// the builds of all of them, as a run that uses every method would.
void time_opencl_builds(SystemInfo& info)
{
#if PENUMBRA_OPENCL
    try {
        cl_backend::OpenClBackend opencl(false);
        opencl.programs().build_all();
        info.opencl_build_seconds = opencl.program_build_seconds();
    } catch (const Error& e) {
        info.opencl_build_error = e.what();
    }
#else
    (void)info;
#endif
}

void describe_opencl(SystemInfo& info)
{
#if PENUMBRA_OPENCL
    info.opencl_built = true;
    const cl_backend::DeviceList list = cl_backend::list_devices();
    info.opencl_problem = list.problem;
    for (const cl_backend::DeviceInfo& d : list.devices)
        info.opencl_devices.push_back(
            {d.platform_name, d.platform_version, d.device_name, d.device_version, d.driver_version, d.type, d.compute_units});
    info.cache_directory = cl_backend::cache_directory();
    info.seed_directory = cl_backend::seed_directory();
    info.seed_programs = count_seed_programs(info.seed_directory);
    if (info.opencl_devices.empty() && info.opencl_problem.empty()) info.opencl_problem = "no OpenCL device found";
#else
    info.opencl_problem = "this build has no OpenCL backend (PENUMBRA_OPENCL=OFF)";
#endif
}

}  // namespace

SystemInfo describe_system(bool measure_opencl_build)
{
    SystemInfo info;
    info.version = PENUMBRA_VERSION;
    for (std::string_view isa : cpu::supported_isas()) info.cpu_isas.emplace_back(isa);
    info.chosen_isa = cpu::chosen_isa();
    const char* forced = std::getenv("PENUMBRA_SIMD_ISA");
    info.isa_reason = forced && *forced ? "forced by PENUMBRA_SIMD_ISA" : "the widest ISA this CPU runs";
    describe_opencl(info);
    info.backends = {"scalar", "simd"};
    if (!info.opencl_devices.empty()) info.backends.push_back("opencl");

    Context automatic;
    info.auto_backend = to_string(automatic.backend());
    info.auto_description = automatic.description();
    info.auto_reason = automatic.reason();
    info.auto_warnings = automatic.warnings();

    if (measure_opencl_build && !info.opencl_devices.empty()) time_opencl_builds(info);
    return info;
}

}  // namespace penumbra
