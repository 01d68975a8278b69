// penumbra::Context — owns the backend every operation runs on.
//
// Backends: Simd (xsimd, the best ISA of this CPU, TBB across cores), OpenCL
// (any OpenCL 1.2 device; PoCL on a CPU-only machine), Scalar (one lane, the
// readable debug path). The rule for Auto, which users can rely on:
//   1. PENUMBRA_BACKEND (auto | simd | opencl | scalar) overrides Auto.
//   2. Auto takes a non-CPU OpenCL device (a GPU or accelerator) when one
//      exists, because it is then faster than the CPU; otherwise Simd (an
//      OpenCL CPU driver such as PoCL runs the same cores slower than Simd).
//   3. If that OpenCL device fails to start, Auto falls back to Simd with one
//      warning (see warnings()); an explicit OpenCL request that cannot be met
//      throws Error(Unavailable).
// A context is not thread-safe; use one per thread. The OpenCL program is built
// once per context (PoCL compiles at run time: seconds, cached on disk).
#pragma once

#include <functional>
#include <future>
#include <memory>
#include <string>
#include <vector>

struct _cl_context;        // cl_context, as CL/cl.h declares it
struct _cl_command_queue;  // cl_command_queue

namespace penumbra {

enum class Backend { Auto, Simd, OpenCL, Scalar };

std::string to_string(Backend backend);
// Parses auto|simd|opencl|scalar; throws Error(InvalidArgument) otherwise.
Backend parse_backend(const std::string& name);

struct ContextOptions {
    Backend backend = Backend::Auto;
    // SIMD only: force an ISA (sse4.2, avx2, avx512); empty = PENUMBRA_SIMD_ISA or the best.
    std::string simd_isa;
};

namespace detail {
class BackendImpl;
}

class Context {
public:
    explicit Context(ContextOptions options = {});
    ~Context();
    Context(Context&&) noexcept;
    Context& operator=(Context&&) noexcept;

    Backend backend() const;          // resolved: never Auto
    std::string description() const; // e.g. "simd (avx512, 16 lanes)", "opencl (Portable Computing Language: cpu)"
    std::string reason() const;       // why this backend was chosen
    const std::vector<std::string>& warnings() const;
    std::string isa() const;          // SIMD/Scalar: the ISA in use; OpenCL: empty
    double program_build_seconds() const;  // OpenCL: time to build the program; else 0

    detail::BackendImpl& impl();

    // An OpenCL context over the caller's cl_context and in-order
    // cl_command_queue (interop: penumbra/device_image.h); the device is the
    // queue's. penumbra retains both and releases them when the Context goes.
    // Error(InvalidArgument) for a null or mismatched pair or an out-of-order
    // queue, Error(Unavailable) in a build without OpenCL.
    static Context from_opencl(_cl_context* context, _cl_command_queue* queue);

private:
    Context(std::unique_ptr<detail::BackendImpl> impl, Backend backend, std::string reason);

    std::unique_ptr<detail::BackendImpl> impl_;
    Backend backend_ = Backend::Simd;
    std::string reason_;
    std::vector<std::string> warnings_;
};

// Makes a Context on another thread and returns at once, so that the caller
// can read its inputs meanwhile: an OpenCL driver takes tens of milliseconds
// to start (PoCL loads LLVM and probes the CPU: about half of a warm
// `penumbra shade`, docs/opencl_startup.md). `prepare`, when given, runs on
// that thread on the new context before get() returns it: `shade` passes its
// method's warm_up (penumbra/methods.h), so that the programs the method
// launches are loaded while the inputs are still being read. The context's
// errors come from get(); an Error that `prepare` throws is dropped (the real
// run meets it again and reports it). What the driver needs of the process
// environment is set before this returns, so that no other thread reads the
// environment while it changes.
std::future<Context> start_context(ContextOptions options = {}, std::function<void(Context&)> prepare = {});

}  // namespace penumbra
