#include "cl/opencl_runtime.h"

#include <CL/cl_ext.h>  // CL_PLATFORM_NOT_FOUND_KHR

#include <chrono>
#include <map>
#include <mutex>

namespace penumbra::cl_backend {

// ---- error names --------------------------------------------------------------

static std::string_view known_error_name(cl_int code)
{
#define PN_CL_ERROR(name) \
    case name: return #name;
    switch (code) {
        PN_CL_ERROR(CL_SUCCESS)
        PN_CL_ERROR(CL_DEVICE_NOT_FOUND)
        PN_CL_ERROR(CL_DEVICE_NOT_AVAILABLE)
        PN_CL_ERROR(CL_COMPILER_NOT_AVAILABLE)
        PN_CL_ERROR(CL_MEM_OBJECT_ALLOCATION_FAILURE)
        PN_CL_ERROR(CL_OUT_OF_RESOURCES)
        PN_CL_ERROR(CL_OUT_OF_HOST_MEMORY)
        PN_CL_ERROR(CL_PROFILING_INFO_NOT_AVAILABLE)
        PN_CL_ERROR(CL_MEM_COPY_OVERLAP)
        PN_CL_ERROR(CL_IMAGE_FORMAT_MISMATCH)
        PN_CL_ERROR(CL_IMAGE_FORMAT_NOT_SUPPORTED)
        PN_CL_ERROR(CL_BUILD_PROGRAM_FAILURE)
        PN_CL_ERROR(CL_MAP_FAILURE)
        PN_CL_ERROR(CL_MISALIGNED_SUB_BUFFER_OFFSET)
        PN_CL_ERROR(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
        PN_CL_ERROR(CL_COMPILE_PROGRAM_FAILURE)
        PN_CL_ERROR(CL_LINKER_NOT_AVAILABLE)
        PN_CL_ERROR(CL_LINK_PROGRAM_FAILURE)
        PN_CL_ERROR(CL_DEVICE_PARTITION_FAILED)
        PN_CL_ERROR(CL_KERNEL_ARG_INFO_NOT_AVAILABLE)
        PN_CL_ERROR(CL_INVALID_VALUE)
        PN_CL_ERROR(CL_INVALID_DEVICE_TYPE)
        PN_CL_ERROR(CL_INVALID_PLATFORM)
        PN_CL_ERROR(CL_INVALID_DEVICE)
        PN_CL_ERROR(CL_INVALID_CONTEXT)
        PN_CL_ERROR(CL_INVALID_QUEUE_PROPERTIES)
        PN_CL_ERROR(CL_INVALID_COMMAND_QUEUE)
        PN_CL_ERROR(CL_INVALID_HOST_PTR)
        PN_CL_ERROR(CL_INVALID_MEM_OBJECT)
        PN_CL_ERROR(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR)
        PN_CL_ERROR(CL_INVALID_IMAGE_SIZE)
        PN_CL_ERROR(CL_INVALID_SAMPLER)
        PN_CL_ERROR(CL_INVALID_BINARY)
        PN_CL_ERROR(CL_INVALID_BUILD_OPTIONS)
        PN_CL_ERROR(CL_INVALID_PROGRAM)
        PN_CL_ERROR(CL_INVALID_PROGRAM_EXECUTABLE)
        PN_CL_ERROR(CL_INVALID_KERNEL_NAME)
        PN_CL_ERROR(CL_INVALID_KERNEL_DEFINITION)
        PN_CL_ERROR(CL_INVALID_KERNEL)
        PN_CL_ERROR(CL_INVALID_ARG_INDEX)
        PN_CL_ERROR(CL_INVALID_ARG_VALUE)
        PN_CL_ERROR(CL_INVALID_ARG_SIZE)
        PN_CL_ERROR(CL_INVALID_KERNEL_ARGS)
        PN_CL_ERROR(CL_INVALID_WORK_DIMENSION)
        PN_CL_ERROR(CL_INVALID_WORK_GROUP_SIZE)
        PN_CL_ERROR(CL_INVALID_WORK_ITEM_SIZE)
        PN_CL_ERROR(CL_INVALID_GLOBAL_OFFSET)
        PN_CL_ERROR(CL_INVALID_EVENT_WAIT_LIST)
        PN_CL_ERROR(CL_INVALID_EVENT)
        PN_CL_ERROR(CL_INVALID_OPERATION)
        PN_CL_ERROR(CL_INVALID_GL_OBJECT)
        PN_CL_ERROR(CL_INVALID_BUFFER_SIZE)
        PN_CL_ERROR(CL_INVALID_MIP_LEVEL)
        PN_CL_ERROR(CL_INVALID_GLOBAL_WORK_SIZE)
        PN_CL_ERROR(CL_INVALID_PROPERTY)
        PN_CL_ERROR(CL_INVALID_IMAGE_DESCRIPTOR)
        PN_CL_ERROR(CL_INVALID_COMPILER_OPTIONS)
        PN_CL_ERROR(CL_INVALID_LINKER_OPTIONS)
        PN_CL_ERROR(CL_INVALID_DEVICE_PARTITION_COUNT)
        PN_CL_ERROR(CL_INVALID_GL_SHAREGROUP_REFERENCE_KHR)
        PN_CL_ERROR(CL_PLATFORM_NOT_FOUND_KHR)
    // OpenCL 2.0 to 3.0: numbers, since the 1.2 headers we compile against hide
    // the names. A 3.0 platform such as PoCL may still return them.
    case -69: return "CL_INVALID_PIPE_SIZE";
    case -70: return "CL_INVALID_DEVICE_QUEUE";
    case -71: return "CL_INVALID_SPEC_ID";
    case -72: return "CL_MAX_SIZE_RESTRICTION_EXCEEDED";
    }
#undef PN_CL_ERROR
    return {};
}

std::string_view opencl_error_name(cl_int code)
{
    if (std::string_view name = known_error_name(code); !name.empty()) return name;
    // Unknown codes (vendor extensions) are interned so the returned view stays
    // valid; there are only ever a handful of them.
    static std::mutex mutex;
    static std::map<cl_int, std::string> unknown_names;
    std::lock_guard lock(mutex);
    auto [entry, inserted] = unknown_names.try_emplace(code);
    if (inserted) entry->second = "unknown OpenCL error " + std::to_string(code);
    return entry->second;
}

static std::string describe_failure(std::string_view call, cl_int code)
{
    std::string text(call);
    text += " failed: ";
    text += opencl_error_name(code);
    text += " (" + std::to_string(code) + ")";
    return text;
}

Error backend_error(std::string_view call, cl_int code)
{
    return Error(ErrorCategory::Backend, "opencl", describe_failure(call, code));
}

Error backend_error(const cl::Error& error)
{
    return backend_error(error.what(), error.err());
}

// ---- discovery ----------------------------------------------------------------

namespace {

struct FoundDevice {
    cl::Device device;
    DeviceInfo info;
    cl_device_type type_bits = 0;
    bool usable = false;  // available and has a compiler, so it can build our sources
};

struct Discovery {
    std::vector<FoundDevice> found;
    std::string problem;
};

constexpr std::string_view no_platform_text =
    "no OpenCL platform found (is an ICD such as pocl-opencl-icd installed?)";

// Drivers pad some strings with spaces or a trailing NUL.
std::string trimmed(std::string text)
{
    while (!text.empty() && (text.back() == '\0' || text.back() == ' ' || text.back() == '\n'))
        text.pop_back();
    return text;
}

std::string device_type_name(cl_device_type type)
{
    std::string name;
    auto add = [&](cl_device_type bit, const char* label) {
        if (!(type & bit)) return;
        if (!name.empty()) name += '+';
        name += label;
    };
    add(CL_DEVICE_TYPE_CPU, "CPU");
    add(CL_DEVICE_TYPE_GPU, "GPU");
    add(CL_DEVICE_TYPE_ACCELERATOR, "accelerator");
    add(CL_DEVICE_TYPE_CUSTOM, "custom");
    return name.empty() ? "unknown" : name;
}

DeviceInfo describe(const cl::Platform& platform, const cl::Device& device)
{
    DeviceInfo info;
    info.platform_name = trimmed(platform.getInfo<CL_PLATFORM_NAME>());
    info.platform_vendor = trimmed(platform.getInfo<CL_PLATFORM_VENDOR>());
    info.platform_version = trimmed(platform.getInfo<CL_PLATFORM_VERSION>());
    info.device_name = trimmed(device.getInfo<CL_DEVICE_NAME>());
    info.device_version = trimmed(device.getInfo<CL_DEVICE_VERSION>());
    info.driver_version = trimmed(device.getInfo<CL_DRIVER_VERSION>());
    info.opencl_c_version = trimmed(device.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
    const cl_device_type type = device.getInfo<CL_DEVICE_TYPE>();
    info.is_cpu = (type & CL_DEVICE_TYPE_CPU) != 0;
    info.type = device_type_name(type);
    info.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
    info.max_work_group_size = device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
    info.global_memory_bytes = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
    return info;
}

void append_problem(std::string& problem, const std::string& text)
{
    if (!problem.empty()) problem += "; ";
    problem += text;
}

std::string platform_label(const cl::Platform& platform)
{
    try {
        return "platform '" + trimmed(platform.getInfo<CL_PLATFORM_NAME>()) + "'";
    } catch (const cl::Error&) {
        return "a platform";
    }
}

// One platform failing (a broken driver) must not hide the devices of the others.
void discover_platform(const cl::Platform& platform, Discovery& discovery)
{
    try {
        std::vector<cl::Device> devices;
        platform.getDevices(CL_DEVICE_TYPE_ALL, &devices);
        for (const cl::Device& device : devices) {
            const bool usable = device.getInfo<CL_DEVICE_AVAILABLE>() && device.getInfo<CL_DEVICE_COMPILER_AVAILABLE>();
            discovery.found.push_back({device, describe(platform, device), device.getInfo<CL_DEVICE_TYPE>(), usable});
        }
    } catch (const cl::Error& error) {
        append_problem(discovery.problem,
                       platform_label(platform) + ": " + describe_failure(error.what(), error.err()));
    }
}

Discovery discover() noexcept
{
    prepare_driver_cache_environment();  // before the first OpenCL call, see program_cache.h
    Discovery discovery;
    try {
        std::vector<cl::Platform> platforms;
        try {
            cl::Platform::get(&platforms);
        } catch (const cl::Error& error) {
            // ocl-icd reports "no vendor file" as CL_PLATFORM_NOT_FOUND_KHR.
            if (error.err() != CL_PLATFORM_NOT_FOUND_KHR) throw;
        }
        if (platforms.empty()) {
            discovery.problem = no_platform_text;
            return discovery;
        }
        for (const cl::Platform& platform : platforms) discover_platform(platform, discovery);
        if (discovery.found.empty() && discovery.problem.empty())
            discovery.problem = "the OpenCL platforms expose no device";
    } catch (const cl::Error& error) {
        append_problem(discovery.problem, describe_failure(error.what(), error.err()));
    } catch (const std::exception& error) {
        append_problem(discovery.problem, error.what());
    }
    return discovery;
}

bool is_gpu_or_accelerator(const FoundDevice& candidate)
{
    return (candidate.type_bits & (CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR)) != 0;
}

bool is_cpu(const FoundDevice& candidate) { return candidate.info.is_cpu; }

const FoundDevice* first_usable(const std::vector<FoundDevice>& found, bool (*wanted)(const FoundDevice&))
{
    for (const FoundDevice& candidate : found)
        if (candidate.usable && wanted(candidate)) return &candidate;
    return nullptr;
}

std::string names_of(const std::vector<FoundDevice>& found)
{
    std::string names;
    for (const FoundDevice& candidate : found) {
        names += (names.empty() ? "" : ", ") + candidate.info.device_name + " (" + candidate.info.type;
        names += candidate.usable ? ")" : ", unavailable or without a compiler)";
    }
    return names;
}

const FoundDevice& choose(const Discovery& discovery, DeviceChoice choice)
{
    // PoCL hides its device when its cache folder is unusable: name the folder.
    if (discovery.found.empty() && !driver_cache_problem().empty())
        throw Error(ErrorCategory::Unavailable, "opencl",
                    driver_cache_problem() + " (the OpenCL driver offers no device without it), or choose --backend simd");
    if (discovery.found.empty())
        throw Error(ErrorCategory::Unavailable, "opencl",
                    "no OpenCL device: " + discovery.problem +
                        "; install pocl-opencl-icd or a GPU driver, or choose --backend simd");
    if (const FoundDevice* fast = first_usable(discovery.found, is_gpu_or_accelerator)) return *fast;
    if (choice == DeviceChoice::NonCpuOnly)
        throw Error(ErrorCategory::Unavailable, "opencl",
                    "no usable GPU or accelerator OpenCL device among " + names_of(discovery.found) +
                        "; allow CPU devices or choose --backend simd");
    if (const FoundDevice* cpu = first_usable(discovery.found, is_cpu)) return *cpu;
    throw Error(ErrorCategory::Unavailable, "opencl",
                "no usable OpenCL device among " + names_of(discovery.found) + "; choose --backend simd");
}

}  // namespace

DeviceList list_devices()
{
    Discovery discovery = discover();
    DeviceList list;
    list.problem = std::move(discovery.problem);
    // PoCL hides its device when its cache folder is unusable: say that instead.
    if (discovery.found.empty() && !driver_cache_problem().empty()) list.problem = driver_cache_problem();
    for (FoundDevice& found : discovery.found) list.devices.push_back(std::move(found.info));
    return list;
}

// ---- runtime ------------------------------------------------------------------

// One cl::Context per device for the whole process, never released. PoCL frees
// its compiler state (the kernel library it links every program with) with
// the last context of the process: 0.23 s after a build from source, measured
// (docs/opencl_startup.md), which the process's exit does for nothing. A later
// Runtime on the device reuses the context and the library PoCL has loaded.
static cl::Context process_context(const cl::Device& device)
{
    static auto* mutex = new std::mutex;  // both never destroyed, on purpose
    static auto* contexts = new std::vector<std::pair<cl_device_id, cl::Context>>;
    std::lock_guard lock(*mutex);
    for (const auto& [id, context] : *contexts)
        if (id == device()) return context;
    contexts->emplace_back(device(), cl::Context(device));
    return contexts->back().second;
}

Runtime::Runtime(DeviceChoice choice, ProgramCache cache, ProgramCache seed)
    : cache_(std::move(cache)), seed_(std::move(seed))
{
    const Discovery discovery = discover();
    const FoundDevice& chosen = choose(discovery, choice);
    device_ = chosen.device;
    info_ = chosen.info;
    work_groups_ = work_groups_for(info_.max_work_group_size);
    require_double_precision();
    translate_cl_errors([&] {
        context_ = process_context(device_);
        queue_ = cl::CommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE);
    });
}

// The moment kernels form per-window moments in double (kernels/dialect.h):
// a device without fp64 would fail to build them, so refuse it here, by name.
void Runtime::require_double_precision() const
{
    const std::string extensions = translate_cl_errors([&] { return device_.getInfo<CL_DEVICE_EXTENSIONS>(); });
    if (extensions.find("cl_khr_fp64") == std::string::npos)
        throw Error(ErrorCategory::Backend, "opencl",
                    "device '" + info_.device_name + "' has no double precision (cl_khr_fp64), which the moment "
                    "kernels need; choose another device or --backend simd");
}

// The caller's objects, retained (cl::Context and cl::CommandQueue release
// them when the last copy goes); the device is the queue's.
Runtime::Runtime(cl_context context, cl_command_queue queue, ProgramCache cache, ProgramCache seed)
    : cache_(std::move(cache)), seed_(std::move(seed))
{
    const std::string op = "Context::from_opencl";
    require(context != nullptr, op, "context", "the cl_context is null");
    require(queue != nullptr, op, "queue", "the cl_command_queue is null");
    translate_cl_errors([&] {
        context_ = cl::Context(context, true);
        queue_ = cl::CommandQueue(queue, true);
        require(queue_.getInfo<CL_QUEUE_CONTEXT>()() == context, op, "queue",
                "the command queue belongs to another cl_context; pass the queue's own context");
        require((queue_.getInfo<CL_QUEUE_PROPERTIES>() & CL_QUEUE_OUT_OF_ORDER_EXEC_MODE_ENABLE) == 0, op, "queue",
                "the command queue is out of order; penumbra chains its kernels on an in-order queue");
        device_ = queue_.getInfo<CL_QUEUE_DEVICE>();
        info_ = describe(cl::Platform(device_.getInfo<CL_DEVICE_PLATFORM>(), true), device_);
    });
    work_groups_ = work_groups_for(info_.max_work_group_size);
    require_double_precision();
}

cl::Program Runtime::build(const std::string& source, const std::string& options, const BeforeStore& before_store)
{
    const auto start = std::chrono::steady_clock::now();
    const std::uint64_t key = cache_key(source, options);
    last_cache_note_.clear();

    const DriverCacheLock serialised;  // PoCL's cache is shared with other runs (program_cache.h)
    std::optional<cl::Program> program = build_from_stores(key, options);
    if (!program) {
        program = build_from_source(source, options);
        if (before_store) translate_cl_errors([&] { before_store(*program); });
        store_binary(*program, key);
        record_driver_cache();  // PoCL wrote this program's files: record them now
    }
    last_build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return *program;
}

std::uint64_t Runtime::cache_key(const std::string& source, const std::string& options) const
{
    const std::string groups = to_string(work_groups_);
    return program_key({source, options, info_.device_name, info_.device_version, info_.driver_version,
                        info_.platform_name, info_.platform_version, groups});
}

// The user's cache first, then the seed. The seed is not copied into the
// cache: reading it again costs what reading the copy would.
std::optional<cl::Program> Runtime::build_from_stores(std::uint64_t key, const std::string& options)
{
    std::optional<cl::Program> program;
    if (auto binary = cache_.load(key, &last_cache_note_)) program = build_from_binary(*binary, options, "cached");
    last_build_from_cache_ = program.has_value();
    last_build_from_seed_ = false;
    if (program || !seed_.enabled()) return program;
    std::string seed_note;
    if (auto binary = seed_.load(key, &seed_note)) program = build_from_binary(*binary, options, "seed");
    else append_problem(last_cache_note_, "seed: " + seed_note);
    last_build_from_seed_ = program.has_value();
    if (program) last_cache_note_.clear();
    return program;
}

// A binary that passed the checksum can still be refused by the driver
// (another driver build with the same version string, or a seed made for
// another CPU: CL_INVALID_BINARY): then build from source.
std::optional<cl::Program> Runtime::build_from_binary(const std::vector<unsigned char>& binary,
                                                      const std::string& options, std::string_view origin)
{
    try {
        cl::Program program(context_, {device_}, cl::Program::Binaries{binary});
        program.build(device_, options.c_str());
        return program;
    } catch (const cl::Error& error) {
        append_problem(last_cache_note_,
                       std::string(origin) + " binary refused: " + describe_failure(error.what(), error.err()));
        return std::nullopt;
    }
}

static std::string build_log_text(const cl::BuildError& error)
{
    std::string log;
    for (const auto& [device, text] : error.getBuildLog()) log += trimmed(text) + "\n";
    return log.empty() ? "(the driver gave no build log)\n" : log;
}

cl::Program Runtime::build_from_source(const std::string& source, const std::string& options) const
{
    cl::Program program = translate_cl_errors([&] { return cl::Program(context_, source); });
    try {
        program.build(device_, options.c_str());
    } catch (const cl::BuildError& error) {
        throw Error(ErrorCategory::Backend, "opencl",
                    describe_failure(error.what(), error.err()) + " on device '" + info_.device_name +
                        "' with options '" + options + "'; build log:\n" + build_log_text(error));
    } catch (const cl::Error& error) {
        throw backend_error(error);
    }
    return program;
}

// Best effort: a program that built is good even when its binary cannot be kept.
void Runtime::store_binary(const cl::Program& program, std::uint64_t key)
{
    if (!cache_.enabled()) return;
    try {
        const auto binaries = program.getInfo<CL_PROGRAM_BINARIES>();
        std::string why_not = "the driver returned " + std::to_string(binaries.size()) + " binaries for one device";
        if (binaries.size() != 1 || !cache_.store(key, binaries.front(), &why_not))
            append_problem(last_cache_note_, "binary not stored: " + why_not);
    } catch (const cl::Error& error) {
        append_problem(last_cache_note_, "binary not stored: " + describe_failure(error.what(), error.err()));
    }
}

}  // namespace penumbra::cl_backend
