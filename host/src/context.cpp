#include "penumbra/context.h"

#include <tbb/cache_aligned_allocator.h>
#include <tbb/parallel_for.h>

#include <cstdlib>
#include <string>

#include "host/backend/backend.h"
#include "penumbra/config.h"
#include "penumbra/error.h"
#include "simd/cpu_backend.h"
#if PENUMBRA_OPENCL
#include "cl/opencl_backend.h"
#include "cl/program_cache.h"
#endif

namespace penumbra {

std::string to_string(Backend backend)
{
    switch (backend) {
    case Backend::Auto: return "auto";
    case Backend::Simd: return "simd";
    case Backend::OpenCL: return "opencl";
    case Backend::Scalar: return "scalar";
    }
    return "unknown";
}

Backend parse_backend(const std::string& name)
{
    if (name == "auto") return Backend::Auto;
    if (name == "simd") return Backend::Simd;
    if (name == "opencl") return Backend::OpenCL;
    if (name == "scalar") return Backend::Scalar;
    throw Error(ErrorCategory::InvalidArgument, "backend",
                "'" + name + "' is not a backend; valid: auto, simd, opencl, scalar");
}

namespace {

std::unique_ptr<detail::BackendImpl> make_simd(const ContextOptions& options)
{
    const std::string_view isa = options.simd_isa.empty() ? cpu::chosen_isa() : std::string_view(options.simd_isa);
    return cpu::make_cpu_backend(cpu::kernels_for(isa));
}

std::unique_ptr<detail::BackendImpl> make_opencl(bool non_cpu_only)
{
#if PENUMBRA_OPENCL
    return cl_backend::make_opencl_backend(non_cpu_only);
#else
    (void)non_cpu_only;
    throw Error(ErrorCategory::Unavailable, "opencl",
                "this build of penumbra has no OpenCL backend (configure with -DPENUMBRA_OPENCL=ON)");
#endif
}

// A damaged PoCL cache that was cleared at start-up (cl/pocl_cache_guard.h).
void add_driver_cache_warning(std::vector<std::string>& warnings)
{
#if PENUMBRA_OPENCL
    if (std::string warning = cl_backend::driver_cache_warning(); !warning.empty()) warnings.push_back(warning);
#else
    (void)warnings;
#endif
}

bool has_non_cpu_opencl_device()
{
#if PENUMBRA_OPENCL
    return cl_backend::has_non_cpu_device();
#else
    return false;
#endif
}

}  // namespace

Context::Context(ContextOptions options)
{
    Backend requested = options.backend;
    std::string source = "requested by the caller";
    if (requested == Backend::Auto) {
        if (const char* env = std::getenv("PENUMBRA_BACKEND"); env && *env) {
            requested = parse_backend(env);
            source = "PENUMBRA_BACKEND=" + std::string(env);
        }
    }
    switch (requested) {
    case Backend::Simd:
        impl_ = make_simd(options);
        backend_ = Backend::Simd;
        reason_ = source;
        break;
    case Backend::Scalar:
        impl_ = cpu::make_cpu_backend(cpu::kernels_scalar);
        backend_ = Backend::Scalar;
        reason_ = source;
        break;
    case Backend::OpenCL:
        impl_ = make_opencl(false);
        backend_ = Backend::OpenCL;
        reason_ = source;
        add_driver_cache_warning(warnings_);
        break;
    case Backend::Auto:
        if (has_non_cpu_opencl_device()) {
            try {
                impl_ = make_opencl(true);
                backend_ = Backend::OpenCL;
                reason_ = "auto: a non-CPU OpenCL device is present";
                add_driver_cache_warning(warnings_);
                break;
            } catch (const Error& e) {
                warnings_.push_back(std::string("OpenCL device failed to start, using SIMD instead: ") + e.what());
            }
        }
        impl_ = make_simd(options);
        backend_ = Backend::Simd;
        // Only the OpenCL start above can have left a warning by now.
        reason_ = warnings_.empty() ? "auto: no non-CPU OpenCL device, so the SIMD backend (faster than an "
                                      "OpenCL CPU driver on the same cores)"
                                    : "auto: fell back to SIMD after the OpenCL device failed";
        break;
    }
}

namespace {

// TBB loads libtbbmalloc and libirml with dlopen on its first allocation and
// its first parallel loop, and glibc runs one dlopen at a time. Started
// after PoCL's own dlopen (libLLVM and libclang-cpp relocated: 20 ms idle,
// 50 to 90 ms under load), those waited for it: a warm `shade` had its input
// reading blocked in read_exr -> Image -> tbb::detail::r1::allocate ->
// dlopen until PoCL's had finished (perf record -e sched:sched_switch,
// docs/opencl_startup.md). Taking them first keeps the reads beside it.
void load_tbb_runtime()
{
    tbb::cache_aligned_allocator<char> allocator;
    allocator.deallocate(allocator.allocate(1), 1);
    tbb::parallel_for(0, 2, [](int) {});
}

}  // namespace

std::future<Context> start_context(ContextOptions options, std::function<void(Context&)> prepare)
{
#if PENUMBRA_OPENCL
    cl_backend::prepare_driver_cache_environment();  // sets POCL_CACHE_DIR: before the thread starts
#endif
    load_tbb_runtime();
    return std::async(std::launch::async, [options = std::move(options), prepare = std::move(prepare)] {
        Context context(options);
        try {
            if (prepare) prepare(context);
        } catch (const Error&) {
            // Only a head start: the real run reports its own errors.
        }
        return context;
    });
}

Context::Context(std::unique_ptr<detail::BackendImpl> impl, Backend backend, std::string reason)
    : impl_(std::move(impl)), backend_(backend), reason_(std::move(reason))
{
}

Context Context::from_opencl(_cl_context* context, _cl_command_queue* queue)
{
#if PENUMBRA_OPENCL
    return Context(cl_backend::make_opencl_backend(context, queue), Backend::OpenCL,
                   "the caller's cl_context and cl_command_queue (Context::from_opencl)");
#else
    (void)context;
    (void)queue;
    throw Error(ErrorCategory::Unavailable, "Context::from_opencl",
                "this build of penumbra has no OpenCL backend (configure with -DPENUMBRA_OPENCL=ON)");
#endif
}

Context::~Context() = default;
Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;

Backend Context::backend() const { return backend_; }
std::string Context::description() const { return impl_->description(); }
std::string Context::reason() const { return reason_; }
const std::vector<std::string>& Context::warnings() const { return warnings_; }
std::string Context::isa() const { return impl_->isa(); }
double Context::program_build_seconds() const { return impl_->program_build_seconds(); }
detail::BackendImpl& Context::impl() { return *impl_; }

}  // namespace penumbra
