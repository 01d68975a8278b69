// The OpenCL runtime layer: error names, device discovery, program builds, the
// binary cache and its failure modes. Tests that need a device skip, saying so,
// on a machine without an OpenCL platform; they never pass vacuously.
#include "cl/opencl_runtime.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numeric>
#include <optional>

#include "support/cl_sources.h"

namespace penumbra::cl_backend {
namespace {

namespace fs = std::filesystem;

using testing::add1_source;
using testing::never_built_source;

// A scratch path that a threadsafe death test's child (which re-runs the test
// body in a new process) sees with the same name as the parent: passed by
// environment, which the child inherits.
fs::path path_shared_with_child(const std::string& name)
{
    const std::string variable = "PENUMBRA_TEST_PATH_" + name;
    if (const char* inherited = std::getenv(variable.c_str())) return inherited;
    const fs::path path = fs::temp_directory_path() / ("penumbra-" + name + "-" + std::to_string(::getpid()));
    ::setenv(variable.c_str(), path.c_str(), 1);
    return path;
}

template <class Call>
Error error_thrown_by(Call&& call)
{
    try {
        call();
    } catch (const Error& error) {
        return error;
    }
    ADD_FAILURE() << "expected penumbra::Error";
    return Error(ErrorCategory::InvalidArgument, "test", "nothing thrown");
}

// ---- without a device ---------------------------------------------------------

TEST(OpenClErrorName, NamesEveryKindOfCode)
{
    EXPECT_EQ(opencl_error_name(CL_SUCCESS), "CL_SUCCESS");
    EXPECT_EQ(opencl_error_name(-11), "CL_BUILD_PROGRAM_FAILURE");
    EXPECT_EQ(opencl_error_name(CL_INVALID_KERNEL_ARGS), "CL_INVALID_KERNEL_ARGS");
    EXPECT_EQ(opencl_error_name(CL_INVALID_DEVICE_PARTITION_COUNT), "CL_INVALID_DEVICE_PARTITION_COUNT");
    EXPECT_EQ(opencl_error_name(-1001), "CL_PLATFORM_NOT_FOUND_KHR");
    EXPECT_EQ(opencl_error_name(-72), "CL_MAX_SIZE_RESTRICTION_EXCEEDED");
}

TEST(OpenClErrorName, EveryOpenCl12CodeHasAName)
{
    for (cl_int code = 0; code >= -68; --code) {
        if (code < -19 && code > -30) continue;  // -20..-29 are unassigned
        EXPECT_TRUE(opencl_error_name(code).starts_with("CL_")) << code;
    }
}

TEST(OpenClErrorName, UnknownCodesStayValid)
{
    const std::string_view first = opencl_error_name(12345);
    EXPECT_EQ(first, "unknown OpenCL error 12345");
    EXPECT_EQ(opencl_error_name(-9999), "unknown OpenCL error -9999");
    EXPECT_EQ(first, "unknown OpenCL error 12345");  // not overwritten by the second call
}

TEST(OpenClBackendError, NamesCallAndError)
{
    const Error error = backend_error("clEnqueueNDRangeKernel", CL_INVALID_WORK_GROUP_SIZE);
    EXPECT_EQ(error.category(), ErrorCategory::Backend);
    EXPECT_STREQ(error.what(), "opencl: clEnqueueNDRangeKernel failed: CL_INVALID_WORK_GROUP_SIZE (-54)");
}

class ScopedEnvironment {
public:
    explicit ScopedEnvironment(const char* name) : name_(name)
    {
        if (const char* value = std::getenv(name)) saved_ = value;
    }
    ~ScopedEnvironment() { saved_ ? ::setenv(name_, saved_->c_str(), 1) : ::unsetenv(name_); }
    void set(const char* value) const { value ? ::setenv(name_, value, 1) : ::unsetenv(name_); }

private:
    const char* name_;
    std::optional<std::string> saved_;
};

// Runs sharing a cache folder take turns at PoCL's cache (program_cache.h,
// DriverCacheLock): while one holds the lock, another description of the lock
// file (as another process or thread opens it) cannot take it; after, it can.
// In a folder of its own: ctest -j2 runs other tests beside this one, and one
// that builds an OpenCL program in the shared cache holds the same lock (the
// "after" check failed so, once, in a fresh-root CI run).
TEST(DriverCacheLock, ExcludesOthersWhileHeldAndReleasesAfter)
{
    const fs::path folder = path_shared_with_child("driver-cache-lock");
    fs::create_directories(folder);
    const ScopedEnvironment cache("PENUMBRA_CACHE_DIR");
    cache.set(folder.c_str());
    const std::string lock_file = cache_directory() + "/pocl.lock";
    auto other_can_lock = [&] {
        const int fd = ::open(lock_file.c_str(), O_RDWR | O_CLOEXEC);
        if (fd < 0) return false;
        const bool locked = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
        ::close(fd);
        return locked;
    };
    {
        const DriverCacheLock held;
        ASSERT_TRUE(fs::exists(lock_file));
        EXPECT_FALSE(other_can_lock());
    }
    EXPECT_TRUE(other_can_lock());
    fs::remove_all(folder);
}

TEST(ProgramKey, ChangesWithEveryField)
{
    const ProgramIdentity base{"src", "-O", "dev", "dver", "drv", "plat", "pver", "512x8,64"};
    const std::uint64_t key = program_key(base);
    EXPECT_EQ(key, program_key(base));
    auto changed = [&](auto edit) {
        ProgramIdentity other = base;
        edit(other);
        return program_key(other);
    };
    EXPECT_NE(key, changed([](ProgramIdentity& id) { id.source = "src2"; }));
    EXPECT_NE(key, changed([](ProgramIdentity& id) { id.options = "-O2"; }));
    EXPECT_NE(key, changed([](ProgramIdentity& id) { id.device_name = "dev2"; }));
    EXPECT_NE(key, changed([](ProgramIdentity& id) { id.device_version = "dver2"; }));
    EXPECT_NE(key, changed([](ProgramIdentity& id) { id.driver_version = "drv2"; }));
    EXPECT_NE(key, changed([](ProgramIdentity& id) { id.platform_name = "plat2"; }));
    EXPECT_NE(key, changed([](ProgramIdentity& id) { id.platform_version = "pver2"; }));
    EXPECT_NE(key, changed([](ProgramIdentity& id) { id.work_groups = "64x4,64"; }));
    // Field boundaries count: moving a character from one field to the next is another key.
    EXPECT_NE(key, changed([](ProgramIdentity& id) { id.source = "sr", id.options = "c-O"; }));
}

TEST(CacheDirectory, FollowsTheDocumentedOrder)
{
    const ScopedEnvironment penumbra("PENUMBRA_CACHE_DIR"), xdg("XDG_CACHE_HOME"), home("HOME");
    penumbra.set("/p");
    xdg.set("/x");
    home.set("/h");
    EXPECT_EQ(cache_directory(), "/p");
    penumbra.set(nullptr);
    EXPECT_EQ(cache_directory(), "/x/penumbra");
    xdg.set("relative");  // invalid by the XDG spec, so ignored
    EXPECT_EQ(cache_directory(), "/h/.cache/penumbra");
    xdg.set(nullptr);
    home.set(nullptr);
    EXPECT_EQ(cache_directory(), "/tmp/penumbra-cache-" + std::to_string(::geteuid()));
}

class ProgramCacheFiles : public ::testing::Test {
protected:
    void SetUp() override { fs::remove_all(directory); }
    void TearDown() override { fs::remove_all(directory); }
    const fs::path directory = fs::temp_directory_path() / ("penumbra-cache-test-" + std::to_string(::getpid()));
    const ProgramCache cache{directory / "nested"};
    const std::vector<unsigned char> payload{1, 2, 3, 4, 5, 6, 7, 8, 9};
};

TEST_F(ProgramCacheFiles, RoundTripsAndLeavesNoTemporaryFile)
{
    ASSERT_TRUE(cache.store(42, payload));
    EXPECT_EQ(cache.load(42), payload);
    EXPECT_EQ(std::distance(fs::directory_iterator(cache.directory()), fs::directory_iterator()), 1);
    EXPECT_EQ(cache.file_for(42).filename(), "000000000000002a.bin");
}

TEST_F(ProgramCacheFiles, RejectsAFileStoredUnderAnotherKey)
{
    ASSERT_TRUE(cache.store(1, payload));
    fs::copy_file(cache.file_for(1), cache.file_for(2));
    std::string why_not;
    EXPECT_FALSE(cache.load(2, &why_not));
    EXPECT_NE(why_not.find("another key"), std::string::npos) << why_not;
}

TEST_F(ProgramCacheFiles, DisabledCacheDoesNothing)
{
    const ProgramCache disabled;
    EXPECT_FALSE(disabled.enabled());
    EXPECT_FALSE(disabled.store(1, payload));
    EXPECT_FALSE(disabled.load(1));
}

// Runs in a fresh process (threadsafe death-test style re-executes the binary), so
// the ICD loader reads OCL_ICD_VENDORS pointing at an empty directory: the machine
// then looks like one without any OpenCL driver.
TEST(NoOpenClPlatform, IsReportedNotThrownAndRuntimeSaysWhatToDo)
{
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const fs::path empty = path_shared_with_child("no-icd");
    fs::create_directories(empty);
    auto run_without_drivers = [&] {
        ::setenv("OCL_ICD_VENDORS", empty.c_str(), 1);
        const DeviceList list = list_devices();
        if (!list.devices.empty()) std::exit(2);
        std::fprintf(stderr, "problem: %s\n", list.problem.c_str());
        try {
            Runtime runtime(DeviceChoice::Any, ProgramCache());
        } catch (const Error& error) {
            std::fprintf(stderr, "runtime: %s\n", error.what());
            std::exit(error.category() == ErrorCategory::Unavailable ? 0 : 3);
        }
        std::exit(4);
    };
    EXPECT_EXIT(run_without_drivers(), ::testing::ExitedWithCode(0),
                "problem: no OpenCL platform found \\(is an ICD such as pocl-opencl-icd installed\\?\\)"
                "(.|\n)*runtime: opencl: no OpenCL device: no OpenCL platform found.*"
                "install pocl-opencl-icd or a GPU driver, or choose --backend simd");
    fs::remove_all(empty);
}

// ---- with a device --------------------------------------------------------------

TEST(ListDevices, FindsThePoclCpuDevice)
{
    if (std::string why = testing::why_no_opencl_device(); !why.empty()) GTEST_SKIP() << why;
    const DeviceList list = list_devices();
    const DeviceInfo* pocl = nullptr;
    for (const DeviceInfo& device : list.devices) {
        EXPECT_FALSE(device.device_name.empty());
        EXPECT_TRUE(device.opencl_c_version.starts_with("OpenCL C ")) << device.opencl_c_version;
        EXPECT_GT(device.compute_units, 0u);
        EXPECT_GT(device.global_memory_bytes, 0u);
        if (device.platform_name == "Portable Computing Language") pocl = &device;
    }
    if (!pocl) GTEST_SKIP() << "PoCL is not installed here; other devices were listed";
    EXPECT_TRUE(pocl->is_cpu);
    EXPECT_EQ(pocl->type, "CPU");
    EXPECT_EQ(pocl->platform_vendor, "The pocl project");
}

// In a fresh process without POCL_CACHE_DIR, our first OpenCL use points PoCL at
// $PENUMBRA_CACHE_DIR/pocl, and PoCL really writes its cache there. The child
// re-runs this test's body up to EXPECT_EXIT, so nothing before it may touch OpenCL.
TEST(ListDevices, PointsPoclAtTheKnownCacheDirectory)
{
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const fs::path root = path_shared_with_child("pocl-dir");
    auto build_in_fresh_process = [&] {
        fs::remove_all(root);
        ::unsetenv("POCL_CACHE_DIR");  // the parent's setting is inherited
        ::setenv("PENUMBRA_CACHE_DIR", root.c_str(), 1);
        if (!list_devices().devices.empty()) Runtime(DeviceChoice::Any, ProgramCache()).build(never_built_source(), "");
        std::fprintf(stderr, "POCL_CACHE_DIR=%s\n", pocl_cache_directory().c_str());
        std::exit(0);
    };
    EXPECT_EXIT(build_in_fresh_process(), ::testing::ExitedWithCode(0),
                "POCL_CACHE_DIR=" + (root / "pocl").string());
    EXPECT_TRUE(fs::is_directory(root / "pocl"));
    const auto devices = list_devices().devices;
    const bool pocl_only = !devices.empty() && std::all_of(devices.begin(), devices.end(), [](const DeviceInfo& d) {
        return d.platform_name == "Portable Computing Language";
    });
    if (pocl_only) {
        EXPECT_FALSE(fs::is_empty(root / "pocl")) << "PoCL did not write into its cache directory";
    }
    fs::remove_all(root);
}

TEST(DeviceChoice, NonCpuOnlyIsUnavailableOnACpuOnlyMachine)
{
    for (const DeviceInfo& device : list_devices().devices) {
        if (!device.is_cpu) GTEST_SKIP() << "this machine has a non-CPU device: " << device.device_name;
    }
    const Error error = error_thrown_by([] { Runtime runtime(DeviceChoice::NonCpuOnly, ProgramCache()); });
    EXPECT_EQ(error.category(), ErrorCategory::Unavailable);
    EXPECT_NE(std::string(error.what()).find("--backend simd"), std::string::npos) << error.what();
}

// One runtime for the suite: creating contexts is cheap, but the binary cache
// directory is the suite's own, so the user's cache is neither used nor touched.
class OpenClRuntime : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        if (!testing::why_no_opencl_device().empty()) return;
        fs::remove_all(cache_root());
        runtime = new Runtime(DeviceChoice::Any, ProgramCache(cache_root()));
    }
    static void TearDownTestSuite()
    {
        delete runtime;
        runtime = nullptr;
        fs::remove_all(cache_root());
    }
    void SetUp() override
    {
        if (std::string why = testing::why_no_opencl_device(); !why.empty()) GTEST_SKIP() << why;
    }
    static fs::path cache_root()
    {
        return fs::temp_directory_path() / ("penumbra-runtime-test-" + std::to_string(::getpid()));
    }

    // Runs add1 over 0, 1, ..., n-1 and returns the result.
    static std::vector<float> run_add1(const cl::Program& program, std::size_t n)
    {
        return translate_cl_errors([&] {
            std::vector<float> values(n);
            std::iota(values.begin(), values.end(), 0.0f);
            cl::Buffer buffer(runtime->context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                              n * sizeof(float), values.data());
            cl::Kernel kernel(program, "add1");
            kernel.setArg(0, buffer);
            runtime->queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(n));
            runtime->queue().enqueueReadBuffer(buffer, CL_TRUE, 0, n * sizeof(float), values.data());
            return values;
        });
    }
    static void expect_add1_works(const cl::Program& program)
    {
        const std::vector<float> values = run_add1(program, 1000);
        for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(values[i], float(i) + 1.0f) << i;
    }

    static inline Runtime* runtime = nullptr;
};

TEST_F(OpenClRuntime, BuildsAndRunsATinyKernel)
{
    EXPECT_FALSE(runtime->device_info().device_name.empty());
    expect_add1_works(runtime->build(add1_source, ""));
    EXPECT_GT(runtime->last_build_seconds(), 0.0);
}

TEST_F(OpenClRuntime, SyntaxErrorGivesTheWholeBuildLog)
{
    const std::string broken = "kernel void broken(global float* a){ a[0] = undeclared_thing; }\n";
    const Error error = error_thrown_by([&] { runtime->build(broken, "-cl-std=CL1.2"); });
    const std::string what = error.what();
    EXPECT_EQ(error.category(), ErrorCategory::Backend);
    EXPECT_NE(what.find("clBuildProgram failed: CL_BUILD_PROGRAM_FAILURE"), std::string::npos) << what;
    EXPECT_NE(what.find("-cl-std=CL1.2"), std::string::npos) << what;
    // A line of the compiler's log, with the offending name.
    EXPECT_NE(what.find("use of undeclared identifier 'undeclared_thing'"), std::string::npos) << what;
}

TEST_F(OpenClRuntime, CLErrorsFromLaunchCodeBecomePenumbraErrors)
{
    const Error error = error_thrown_by([] {
        translate_cl_errors([] { cl::Buffer empty(runtime->context(), CL_MEM_READ_WRITE, 0); });
    });
    EXPECT_EQ(error.category(), ErrorCategory::Backend);
    EXPECT_NE(std::string(error.what()).find("clCreateBuffer failed: CL_INVALID_BUFFER_SIZE"), std::string::npos)
        << error.what();
}

// The speed of the cached build is printed, not asserted: a test that times
// itself fails on a loaded machine (bench/opencl_startup.sh measures it).
TEST_F(OpenClRuntime, SecondBuildComesFromTheCache)
{
    const std::string source = never_built_source();
    runtime->build(source, "");
    EXPECT_FALSE(runtime->last_build_from_cache());
    const double cold = runtime->last_build_seconds();
    const fs::path file = runtime->program_cache().file_for(runtime->cache_key(source, ""));
    EXPECT_TRUE(fs::exists(file)) << runtime->last_cache_note();

    const cl::Program cached = runtime->build(source, "");
    EXPECT_TRUE(runtime->last_build_from_cache()) << runtime->last_cache_note();
    std::printf("[ timing   ] build of a new program %.4f s, from the binary cache %.4f s\n", cold,
                runtime->last_build_seconds());
    expect_add1_works(cached);

    runtime->build(source, "-cl-fast-relaxed-math");  // other options, other entry
    EXPECT_FALSE(runtime->last_build_from_cache());
}

// PoCL crashes when handed a damaged binary, so the cache must catch every kind
// of damage before the driver sees it, and then rebuild and repair the entry.
TEST_F(OpenClRuntime, CorruptCacheFileFallsBackToASourceBuild)
{
    const std::string source = never_built_source();
    runtime->build(source, "");
    const fs::path entry = runtime->program_cache().file_for(runtime->cache_key(source, ""));
    ASSERT_TRUE(fs::exists(entry));
    const auto intact_size = fs::file_size(entry);

    const std::vector<std::pair<std::string, std::function<void()>>> damages = {
        {"truncated", [&] { fs::resize_file(entry, intact_size / 2); }},
        {"empty", [&] { fs::resize_file(entry, 0); }},
        {"one byte flipped in the payload", [&] {
             std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
             f.seekg(static_cast<std::streamoff>(intact_size - 100));
             const char byte = static_cast<char>(f.get() ^ 0x40);
             f.seekp(static_cast<std::streamoff>(intact_size - 100));
             f.put(byte);
         }},
        {"garbage", [&] { std::ofstream(entry, std::ios::binary | std::ios::trunc) << "not a binary at all"; }},
    };
    for (const auto& [damage, apply] : damages) {
        SCOPED_TRACE(damage);
        apply();
        const cl::Program program = runtime->build(source, "");
        EXPECT_FALSE(runtime->last_build_from_cache());
        EXPECT_FALSE(runtime->last_cache_note().empty());
        expect_add1_works(program);
        // Repaired by the source build. Not byte-for-byte: PoCL's binary of a
        // program differs between its first compile (cold driver cache) and
        // later ones, so the repaired entry need not have the first one's size.
        EXPECT_GT(fs::file_size(entry), 32u);
        runtime->build(source, "");
        EXPECT_TRUE(runtime->last_build_from_cache()) << runtime->last_cache_note();
    }
}

}  // namespace
}  // namespace penumbra::cl_backend
