// The seed (cl/program_seed.h): binaries made at build time, read when the
// user's cache misses. Used on a miss, never written; a seed file of another
// key (another device's, or renamed), a binary the driver refuses (another
// device's PoCL header) and a damaged file all fall back to the source build,
// with a working program. A program built from source is launched once before
// its binary is stored (cl/opencl_prime.h), so the binary holds PoCL's
// work-group function of the fixed local size. Skips, saying so, without an
// OpenCL device.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <string>
#include <unistd.h>

#include "penumbra/config.h"
#if PENUMBRA_OPENCL
#include "cl/opencl_prime.h"
#include "cl/opencl_programs.h"
#include "cl/opencl_runtime.h"
#include "cl/program_seed.h"
#include "support/cl_sources.h"
#endif

namespace penumbra::cl_backend {
namespace {

#if PENUMBRA_OPENCL
namespace fs = std::filesystem;

using testing::never_built_source;

std::map<std::string, std::uintmax_t> listing(const fs::path& dir)
{
    std::map<std::string, std::uintmax_t> files;
    for (const auto& entry : fs::directory_iterator(dir)) files[entry.path().filename()] = entry.file_size();
    return files;
}

std::string bytes_of(const fs::path& file)
{
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class OpenClSeed : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (std::string why = testing::why_no_opencl_device(); !why.empty()) GTEST_SKIP() << why;
        root_ = fs::temp_directory_path() / ("penumbra-seed-test-" + std::to_string(::getpid()));
        fs::remove_all(root_);
        fs::create_directories(seed_dir());
    }
    void TearDown() override { fs::remove_all(root_); }

    fs::path seed_dir() const { return root_ / "seed"; }
    // A runtime whose own cache is new and empty, reading the test's seed.
    Runtime user() const { return Runtime(DeviceChoice::Any, ProgramCache(root_ / "cache"), ProgramCache::seed(seed_dir())); }
    // Builds `source` into the seed folder, as the build step does.
    void seed(const std::string& source) const
    {
        Runtime(DeviceChoice::Any, ProgramCache(seed_dir()), ProgramCache()).build(source, "");
    }

    static void expect_add1_works(Runtime& runtime, const cl::Program& program)
    {
        std::vector<float> values(100);
        std::iota(values.begin(), values.end(), 0.0f);
        translate_cl_errors([&] {
            cl::Buffer buffer(runtime.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, values.size() * 4,
                              values.data());
            cl::Kernel kernel(program, "add1");
            kernel.setArg(0, buffer);
            runtime.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(values.size()));
            runtime.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, values.size() * 4, values.data());
        });
        for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(values[i], float(i) + 1.0f) << i;
    }

    fs::path root_;
};

TEST_F(OpenClSeed, IsUsedWhenTheCacheMissesAndNeverWritten)
{
    const std::string source = never_built_source();
    seed(source);
    const auto seeded = listing(seed_dir());
    ASSERT_EQ(seeded.size(), 1u);

    Runtime runtime = user();
    const cl::Program program = runtime.build(source, "");
    EXPECT_TRUE(runtime.last_build_from_seed()) << runtime.last_cache_note();
    EXPECT_FALSE(runtime.last_build_from_cache());
    expect_add1_works(runtime, program);
    EXPECT_EQ(listing(seed_dir()), seeded);

    const std::string other = never_built_source();  // not in the seed: from source, stored in the cache only
    runtime.build(other, "");
    EXPECT_FALSE(runtime.last_build_from_seed());
    EXPECT_NE(runtime.last_cache_note().find("seed: no cached binary"), std::string::npos) << runtime.last_cache_note();
    EXPECT_TRUE(fs::exists(runtime.program_cache().file_for(runtime.cache_key(other, ""))));
    EXPECT_EQ(listing(seed_dir()), seeded);
}

// The key hashes the device, driver and platform (program_cache.h): a seed
// made on another device is filed under another name, and a file renamed into
// this device's name carries the other key in its header.
TEST_F(OpenClSeed, AFileOfAnotherDeviceKeyIsRefused)
{
    const std::string source = never_built_source();
    seed(source);
    Runtime runtime = user();
    const DeviceInfo& device = runtime.device_info();
    const std::string other_device = device.device_name + " (another CPU)";
    const std::string groups = to_string(runtime.work_groups());
    const std::uint64_t their_key = program_key({source, "", other_device, device.device_version, device.driver_version,
                                                 device.platform_name, device.platform_version, groups});
    const ProgramCache seed_files = ProgramCache::seed(seed_dir());
    const fs::path ours = seed_files.file_for(runtime.cache_key(source, ""));
    fs::rename(ours, seed_files.file_for(their_key));

    expect_add1_works(runtime, runtime.build(source, ""));
    EXPECT_FALSE(runtime.last_build_from_seed()) << "found under another device's key";

    // Copied under this device's name of another program: the header says otherwise.
    const std::string renamed = never_built_source();
    fs::copy_file(seed_files.file_for(their_key), seed_files.file_for(runtime.cache_key(renamed, "")));
    expect_add1_works(runtime, runtime.build(renamed, ""));
    EXPECT_FALSE(runtime.last_build_from_seed());
    EXPECT_NE(runtime.last_cache_note().find("written for another key"), std::string::npos) << runtime.last_cache_note();
}

// A binary of another device that passes our checks (the same key, a valid
// header) is refused by the driver: PoCL's header hashes the device's triple
// and CPU (the 8 bytes after its magic "poclbin"), and clBuildProgram or
// clCreateProgramWithBinary says CL_INVALID_BINARY.
TEST_F(OpenClSeed, ABinaryTheDriverRefusesFallsBackToTheSourceBuild)
{
    const std::string source = never_built_source();
    seed(source);
    Runtime runtime = user();
    const std::uint64_t key = runtime.cache_key(source, "");
    const ProgramCache seed_files = ProgramCache::seed(seed_dir());
    auto binary = seed_files.load(key);
    ASSERT_TRUE(binary);
    if (std::string(binary->begin(), binary->begin() + 7) != "poclbin") GTEST_SKIP() << "not a PoCL binary";
    for (int i = 8; i < 16; ++i) (*binary)[i] ^= 0x5a;  // another device's id
    ASSERT_TRUE(seed_files.store(key, *binary));

    expect_add1_works(runtime, runtime.build(source, ""));
    EXPECT_FALSE(runtime.last_build_from_seed());
    EXPECT_NE(runtime.last_cache_note().find("seed binary refused"), std::string::npos) << runtime.last_cache_note();
}

// PoCL crashes on a damaged binary: the seed's header and checksum catch every
// kind of damage first, and the seed is left as it is (it is the installer's).
TEST_F(OpenClSeed, ADamagedSeedFallsBackToTheSourceBuild)
{
    const std::vector<std::pair<std::string, std::function<void(std::string&)>>> damages = {
        {"truncated", [](std::string& b) { b.resize(b.size() / 2); }},
        {"empty", [](std::string& b) { b.clear(); }},
        {"a byte flipped", [](std::string& b) { b[b.size() - 100] = char(b[b.size() - 100] ^ 0x40); }},
        {"garbage", [](std::string& b) { b = "not a binary at all"; }},
    };
    for (const auto& [damage, apply] : damages) {
        SCOPED_TRACE(damage);
        const std::string source = never_built_source();
        seed(source);
        Runtime runtime = user();
        const fs::path file = ProgramCache::seed(seed_dir()).file_for(runtime.cache_key(source, ""));
        std::string bytes = bytes_of(file);
        apply(bytes);
        std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;

        expect_add1_works(runtime, runtime.build(source, ""));
        EXPECT_FALSE(runtime.last_build_from_seed());
        EXPECT_NE(runtime.last_cache_note().find("seed: "), std::string::npos) << runtime.last_cache_note();
        EXPECT_EQ(bytes_of(file), bytes) << "the seed was rewritten";
    }
}

// What makes the seed worth having: the stored binary of an entry built from
// source and launched once (KernelPrograms passes prime_kernel) holds PoCL's
// work-group function of the fixed local size (cl/opencl_work_groups.h),
// which PoCL files under "<lx>-<ly>-<lz>-goffs0-smallgrid"; stored before any
// launch, it does not. Each source is new to PoCL's cache too, so PoCL compiles it.
TEST_F(OpenClSeed, AStoredBinaryHoldsTheWorkGroupFunctionOfTheFixedLocalSize)
{
    Runtime runtime(DeviceChoice::Any, ProgramCache(seed_dir()), ProgramCache());
    const WorkGroups& g = runtime.work_groups();
    const std::vector<std::pair<detail::KernelId, std::string>> entries = {
        {detail::KernelId::vsm_exact,  // per pixel
         "/" + std::to_string(g.pixel_width) + "-" + std::to_string(g.pixel_height) + "-1-goffs0-smallgrid/"},
        {detail::KernelId::sat_bands_exact, "/" + std::to_string(g.task) + "-1-1-goffs0-smallgrid/"},  // per task
    };
    for (const auto& [id, folder] : entries) {
        for (const bool primed : {true, false}) {
            SCOPED_TRACE(std::string(detail::kernel_name(id)) + (primed ? ", launched once" : ", never launched"));
            const std::string source = testing::unique_line() + program_source(id);
            Runtime::BeforeStore prime;
            if (primed) prime = [&](const cl::Program& p) { prime_kernel(runtime.context(), runtime.queue(), p, id, g); };
            runtime.build(source, kProgramOptions, prime);
            const auto binary = runtime.program_cache().load(runtime.cache_key(source, kProgramOptions));
            ASSERT_TRUE(binary) << runtime.last_cache_note();
            const std::string payload(binary->begin(), binary->end());
            EXPECT_EQ(payload.find(folder) != std::string::npos, primed) << folder;
        }
    }
}

TEST(OpenClSeedDirectory, IsBesideTheLibraryUnlessChosen)
{
    const std::string saved = std::getenv("PENUMBRA_CL_SEED_DIR") ? std::getenv("PENUMBRA_CL_SEED_DIR") : "";
    const bool was_set = std::getenv("PENUMBRA_CL_SEED_DIR") != nullptr;
    ::unsetenv("PENUMBRA_CL_SEED_DIR");
    const fs::path beside = seed_directory();
    EXPECT_EQ(beside.filename(), kSeedFolderName);
    EXPECT_TRUE(fs::exists(beside.parent_path() / "libpenumbra.so")) << beside;
    ::setenv("PENUMBRA_CL_SEED_DIR", "", 1);
    EXPECT_FALSE(ProgramCache::installed_seed().enabled()) << "an empty PENUMBRA_CL_SEED_DIR turns the seed off";
    if (was_set) ::setenv("PENUMBRA_CL_SEED_DIR", saved.c_str(), 1);
    else ::unsetenv("PENUMBRA_CL_SEED_DIR");
}
#else
TEST(OpenClSeed, SkippedWithoutOpenCl) { GTEST_SKIP() << "this build has no OpenCL backend (PENUMBRA_OPENCL=OFF)"; }
#endif

}  // namespace
}  // namespace penumbra::cl_backend
