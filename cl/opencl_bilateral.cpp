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
        const Input<float> mask_buf = image_input(context(), mask);
        const Input<float> guide_buf = image_input(context(), guide);
        // Without normals the kernels never read this argument; the guide stands in.
        const Input<float> normals_buf = normals ? image_input(context(), *normals) : guide_buf;
        const Input<int> taps_buf = copy_of(context(), taps);
        const Input<float> weights_buf = copy_of(context(), weights);
        const Output<float> out_buf = image_output(context(), out);
        const Output<int> flags = row_flags(context(), bad_rows, mask.height());
        const Pixels pixels{out.width(), out.height()};

        if (!separable) {
            launch<KernelId::bilateral_full>(pixels, mask_buf, guide_buf, normals_buf, taps_buf, weights_buf, out_buf,
                                             flags, params);
        } else {
            BilateralParams p = params;
            p.pass = detail::dims_of(out);  // a whole-image intermediate of the output's geometry
            p.pass_first_row = 0;
            const Output<float> pass = scratch<float>(context(), image_floats(out));
            launch<KernelId::bilateral_horizontal>(pixels, mask_buf, guide_buf, normals_buf, taps_buf, weights_buf,
                                                   pass, flags, p);
            launch<KernelId::bilateral_vertical>(pixels, as_input(pass), guide_buf, normals_buf, taps_buf,
                                                 weights_buf, out_buf, p);
        }
        sync_to_host(queue(), out_buf);
        sync_to_host(queue(), flags);
    });
}

}  // namespace penumbra::cl_backend
