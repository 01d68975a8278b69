// OpenCL launches of the SDF soft shadows (kernels/sdf.h): one work-item per
// receiver; PoCL packs work-items into lanes and masks them as the SIMD
// backend does, so the same divergence applies (docs/sdf.md).
#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {
namespace {

// An analytic scene may hold no primitives; OpenCL has no empty buffers.
cl::Buffer source_buffer(const cl::Context& ctx, const float* data, std::size_t floats)
{
    if (floats == 0) return zeros(ctx, 4 * sizeof(float));
    return wrap(ctx, data, floats * sizeof(float), CL_MEM_READ_ONLY);
}

}  // namespace

static void launch_sdf(Runtime& runtime, cl::Kernel& k, const float* data, std::size_t floats,
                       const Image& positions, const Image& normals, const SdfParams& p, Image& out, int* bad_rows)
{
    translate_cl_errors([&] {
        const cl::Context& ctx = runtime.context();
        cl::Buffer source = source_buffer(ctx, data, floats);
        cl::Buffer rx = wrap(ctx, positions.plane(0), image_bytes(positions), CL_MEM_READ_ONLY);
        // The same host block wrapped twice would alias two buffers; pass one.
        cl::Buffer nx = &normals == &positions ? rx : wrap(ctx, normals.plane(0), image_bytes(normals), CL_MEM_READ_ONLY);
        cl::Buffer result = wrap(ctx, out.plane(0), image_bytes(out), CL_MEM_WRITE_ONLY);
        const std::size_t flag_bytes = std::size_t(positions.height()) * sizeof(int);
        cl::Buffer flags = wrap(ctx, bad_rows, flag_bytes, CL_MEM_READ_WRITE);

        k.setArg(0, source);
        k.setArg(1, rx);
        k.setArg(2, nx);
        k.setArg(3, result);
        k.setArg(4, flags);
        k.setArg(5, sizeof(SdfParams), &p);
        k.setArg(6, 0);
        launch_pixels(runtime.queue(), k, out.width(), out.height());
        sync_to_host(runtime.queue(), result, image_bytes(out));
        sync_to_host(runtime.queue(), flags, flag_bytes);
    });
}

void OpenClBackend::sdf_grid(const float* data, std::size_t floats, const Image& positions, const Image& normals,
                             const SdfParams& p, Image& out, int* bad_rows)
{
    launch_sdf(runtime_, kernel("sdf_grid"), data, floats, positions, normals, p, out, bad_rows);
}

void OpenClBackend::sdf_analytic(const float* data, std::size_t floats, const Image& positions,
                                 const Image& normals, const SdfParams& p, Image& out, int* bad_rows)
{
    launch_sdf(runtime_, kernel("sdf_analytic"), data, floats, positions, normals, p, out, bad_rows);
}

}  // namespace penumbra::cl_backend
