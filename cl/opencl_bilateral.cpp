// OpenCL launches of the cross-bilateral filter (kernels/bilateral.h): one
// work-item per pixel; the separable schedule is two launches through a
// device buffer of the output's geometry (the in-order queue orders them).
#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {

using detail::KernelId;

void OpenClBackend::cross_bilateral(const Image& mask, const Image& guide, const Image* normals,
                                    const std::vector<int>& taps, const std::vector<float>& weights, bool separable,
                                    const BilateralParams& params, Image& out, int* bad_rows)
{
    translate_cl_errors([&] {
        const Input<float> guide_buf = image_input(context(), guide);
        // Without normals the kernels never read this argument; the guide stands in.
        const BilateralBuffers buffers{image_input(context(), mask),
                                       guide_buf,
                                       normals ? image_input(context(), *normals) : guide_buf,
                                       copy_of(context(), taps),
                                       copy_of(context(), weights),
                                       image_output(context(), out),
                                       row_flags(context(), bad_rows, mask.height())};
        enqueue_bilateral(buffers, separable, params);
        sync_to_host(queue(), buffers.out);
        sync_to_host(queue(), buffers.flags);
    });
}

void OpenClBackend::enqueue_bilateral(const BilateralBuffers& b, bool separable, const BilateralParams& params)
{
    const Pixels pixels{params.out.width, params.out.height};
    if (!separable) {
        launch<KernelId::bilateral_full>(pixels, b.mask, b.guide, b.normals, b.taps, b.weights, b.out, b.flags,
                                         params);
        return;
    }
    BilateralParams p = params;
    p.pass = params.out;  // a whole-image intermediate of the output's geometry
    p.pass_first_row = 0;
    const Output<float> pass = scratch<float>(context(), extent_of(p.out, p.channels));
    launch<KernelId::bilateral_horizontal>(pixels, b.mask, b.guide, b.normals, b.taps, b.weights, pass, b.flags, p);
    launch<KernelId::bilateral_vertical>(pixels, as_input(pass), b.guide, b.normals, b.taps, b.weights, b.out, p);
}

}  // namespace penumbra::cl_backend
