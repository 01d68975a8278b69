// OpenCL launches of the Chebyshev lookups (kernels/vsm.h, kernels/vssm.h).
#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {

void OpenClBackend::chebyshev(detail::ChebyshevMethod method, const MomentTable& table, const Image& receivers,
                              const ChebyshevParams& p, Image& out, int* bad_rows)
{
    const bool exact = table.precision() == Precision::Exact;
    const bool vsm = method == detail::ChebyshevMethod::Vsm;
    const char* name = vsm ? (exact ? "vsm_exact" : "vsm_float") : (exact ? "vssm_exact" : "vssm_float");
    table_lookup(name, table, receivers, &p, sizeof p, out, bad_rows);
}

void OpenClBackend::table_lookup(const char* name, const MomentTable& table, const Image& receivers,
                                 const void* params, std::size_t params_bytes, Image& out, int* bad_rows)
{
    translate_cl_errors([&] {
        const cl::Context& ctx = runtime_.context();
        cl::Buffer storage = wrap(ctx, table.storage(), table.storage_elements() * 4, CL_MEM_READ_ONLY);
        cl::Buffer origin = table_origin(storage, table, CL_MEM_READ_ONLY);
        cl::Buffer rx = wrap(ctx, receivers.plane(0), image_bytes(receivers), CL_MEM_READ_ONLY);
        cl::Buffer result = wrap(ctx, out.plane(0), image_bytes(out), CL_MEM_WRITE_ONLY);
        const std::size_t flag_bytes = std::size_t(receivers.height()) * sizeof(int);
        cl::Buffer flags = wrap(ctx, bad_rows, flag_bytes, CL_MEM_READ_WRITE);

        cl::Kernel& k = kernel(name);
        k.setArg(0, origin);
        k.setArg(1, rx);
        k.setArg(2, result);
        k.setArg(3, flags);
        k.setArg(4, params_bytes, params);
        k.setArg(5, 0);
        launch_pixels(runtime_.queue(), k, out.width(), out.height());
        sync_to_host(runtime_.queue(), result, image_bytes(out));
        sync_to_host(runtime_.queue(), flags, flag_bytes);
    });
}

}  // namespace penumbra::cl_backend
