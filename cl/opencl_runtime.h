// The OpenCL runtime layer: device discovery, one context/device/queue, program
// builds through a binary cache, and the translation of every OpenCL failure into
// penumbra::Error. Launch code (opencl_backend.*) sits on top of it.
//
// Needs the definitions the library target sets for <CL/opencl.hpp>:
// CL_HPP_TARGET_OPENCL_VERSION=120, CL_HPP_MINIMUM_OPENCL_VERSION=120 (Debian's
// header does not compile with 300 against a minimum of 120) and
// CL_HPP_ENABLE_EXCEPTIONS. Device code is OpenCL C 1.2: PoCL 3.1 rejects CLC++.
//
// No cl::Error leaves this layer: code here catches it and throws
// Error(Backend) naming the API call and the error name; launch code does the
// same with translate_cl_errors().
#pragma once

#include <CL/opencl.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cl/opencl_work_groups.h"
#include "cl/program_cache.h"
#include "penumbra/error.h"

namespace penumbra::cl_backend {

// "CL_BUILD_PROGRAM_FAILURE" for -11; every code of OpenCL 1.2, the later core
// codes and the KHR ICD codes; "unknown OpenCL error <n>" otherwise. The view stays
// valid for the life of the process.
std::string_view opencl_error_name(cl_int code);

// Error(Backend, "opencl", "<call> failed: <NAME> (<code>)"), for codes returned
// by the C API and for cl::Error caught from the C++ wrapper.
Error backend_error(std::string_view call, cl_int code);
Error backend_error(const cl::Error& error);

// Runs `call` (a lambda around cl:: calls) and rethrows a cl::Error as
// backend_error(), so that callers of the library see only penumbra::Error.
template <class Call>
decltype(auto) translate_cl_errors(Call&& call)
{
    try {
        return std::forward<Call>(call)();
    } catch (const cl::Error& error) {
        throw backend_error(error);
    }
}

struct DeviceInfo {
    std::string platform_name, platform_vendor, platform_version;
    std::string device_name, device_version, driver_version, opencl_c_version;
    bool is_cpu = false;
    std::string type;  // "CPU", "GPU", "accelerator", "custom", joined by '+'
    unsigned compute_units = 0;
    std::size_t max_work_group_size = 0;
    std::uint64_t global_memory_bytes = 0;
};

struct DeviceList {
    std::vector<DeviceInfo> devices;  // every device of every platform, in driver order
    std::string problem;              // empty when enumeration went through; else what failed
};

// Never throws. With no ICD loader configuration or platform, `devices` is empty
// and `problem` says so and what to install.
DeviceList list_devices();

// Only devices that are available and have a compiler are chosen (we build from
// source); among those, driver order decides.
enum class DeviceChoice {
    NonCpuOnly,  // the first GPU or accelerator; Error(Unavailable) if there is none
    Any,         // a GPU or accelerator if there is one, else a CPU device (PoCL)
};

// One device with its context and in-order queue. The context is the device's
// one context of the process, kept until the process exits (opencl_runtime.cpp
// says why); the queue is this runtime's own. Profiling is enabled on the
// queue so launches can be timed by their events; it costs nothing measurable on
// PoCL. Copies share the underlying OpenCL objects (they are reference counted).
// Not safe to build from two threads at once (build() records its timing).
class Runtime {
public:
    // Throws Error(Unavailable) when no device fits `choice`, Error(Backend) when
    // the context or queue cannot be created. `cache` holds program binaries
    // between runs; `seed` is read, never written, when `cache` misses (the
    // binaries made at build time, cl/program_seed.h). Pass ProgramCache() to
    // disable either.
    explicit Runtime(DeviceChoice choice = DeviceChoice::Any,
                     ProgramCache cache = ProgramCache::in_default_directory(),
                     ProgramCache seed = ProgramCache::installed_seed());

    // Over a caller's context and in-order queue, retained and released by
    // this runtime (interop: penumbra/device_image.h); the device is the
    // queue's. Error(InvalidArgument) for a null or mismatched pair or an
    // out-of-order queue.
    Runtime(cl_context context, cl_command_queue queue, ProgramCache cache = ProgramCache::in_default_directory(),
            ProgramCache seed = ProgramCache::installed_seed());

    const cl::Context& context() const { return context_; }
    const cl::Device& device() const { return device_; }
    const cl::CommandQueue& queue() const { return queue_; }
    const DeviceInfo& device_info() const { return info_; }
    const ProgramCache& program_cache() const { return cache_; }
    const WorkGroups& work_groups() const { return work_groups_; }

    // Runs on a program built from source before its binary is stored
    // (KernelPrograms launches its kernel once: cl/opencl_prime.h).
    using BeforeStore = std::function<void(const cl::Program&)>;

    // Builds `source` with `options` for the device, from the binary cache when it
    // holds a valid entry, else from the seed, else from source (then runs
    // `before_store` and stores the binary). A compile error throws
    // Error(Backend) naming clBuildProgram, the error name, the options and the
    // whole build log.
    cl::Program build(const std::string& source, const std::string& options, const BeforeStore& before_store = {});

    // Wall time of the last build() call, cache lookup and store included.
    double last_build_seconds() const { return last_build_seconds_; }
    bool last_build_from_cache() const { return last_build_from_cache_; }
    bool last_build_from_seed() const { return last_build_from_seed_; }
    // Why the last build did not come from the cache (empty after a hit), nor
    // from the seed, or why its binary could not be stored: for `penumbra info`
    // and debugging.
    const std::string& last_cache_note() const { return last_cache_note_; }

    // The key build() files this program under in program_cache().
    std::uint64_t cache_key(const std::string& source, const std::string& options) const;

private:
    std::optional<cl::Program> build_from_binary(const std::vector<unsigned char>& binary,
                                                 const std::string& options, std::string_view origin);
    std::optional<cl::Program> build_from_stores(std::uint64_t key, const std::string& options);
    cl::Program build_from_source(const std::string& source, const std::string& options) const;
    void require_double_precision() const;
    void store_binary(const cl::Program& program, std::uint64_t key);

    cl::Context context_;
    cl::Device device_;
    cl::CommandQueue queue_;
    DeviceInfo info_;
    WorkGroups work_groups_{};
    ProgramCache cache_;
    ProgramCache seed_;
    double last_build_seconds_ = 0.0;
    bool last_build_from_cache_ = false;
    bool last_build_from_seed_ = false;
    std::string last_cache_note_;
};

}  // namespace penumbra::cl_backend
