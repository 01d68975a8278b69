// OpenCL launches of the SDF soft shadows (kernels/sdf.h): one work-item per
// receiver; PoCL packs work-items into lanes and masks them as the SIMD
// backend does, so the same divergence applies (docs/sdf.md) and the generic
// per-pixel launch serves both kernels.
#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {

using detail::KernelId;

template <KernelId K>
void OpenClBackend::sdf(const float* data, std::size_t floats, const Image& positions, const Image& normals,
                        const SdfParams& p, Image& out, int* bad_rows)
{
    translate_cl_errors([&] {
        // An analytic scene may hold no primitives; OpenCL has no empty buffers.
        const Input<float> source = floats == 0 ? as_input(zeros<float>(context(), 4))
                                                : read_only(context(), data, floats);
        const Input<float> rx = image_input(context(), positions);
        // The same host block wrapped twice would alias two buffers; pass one.
        const Input<float> nx = &normals == &positions ? rx : image_input(context(), normals);
        const Output<float> result = image_output(context(), out);
        const Output<int> flags = row_flags(context(), bad_rows, positions.height());
        launch<K>(Pixels{out.width(), out.height()}, source, rx, nx, result, flags, p);
        sync_to_host(queue(), result);
        sync_to_host(queue(), flags);
    });
}

void OpenClBackend::sdf_grid(const float* data, std::size_t floats, const Image& positions, const Image& normals,
                             const SdfParams& p, Image& out, int* bad_rows)
{
    sdf<KernelId::sdf_grid>(data, floats, positions, normals, p, out, bad_rows);
}

void OpenClBackend::sdf_analytic(const float* data, std::size_t floats, const Image& positions,
                                 const Image& normals, const SdfParams& p, Image& out, int* bad_rows)
{
    sdf<KernelId::sdf_analytic>(data, floats, positions, normals, p, out, bad_rows);
}

}  // namespace penumbra::cl_backend
