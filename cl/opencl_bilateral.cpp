// OpenCL launches of the cross-bilateral filter (kernels/bilateral.h): one
// work-item per pixel; the separable schedule is two launches through a
// device buffer of the output's geometry (the in-order queue orders them).
#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {

void OpenClBackend::cross_bilateral(const Image& mask, const Image& guide, const Image* normals,
                                    const std::vector<int>& taps, const std::vector<float>& weights, bool separable,
                                    const BilateralParams& params, Image& out, int* bad_rows)
{
    translate_cl_errors([&] {
        const cl::Context& ctx = runtime_.context();
        const cl::CommandQueue& queue = runtime_.queue();
        cl::Buffer mask_buf = wrap(ctx, mask.plane(0), image_bytes(mask), CL_MEM_READ_ONLY);
        cl::Buffer guide_buf = wrap(ctx, guide.plane(0), image_bytes(guide), CL_MEM_READ_ONLY);
        // Without normals the kernels never read this argument; the guide stands in.
        cl::Buffer normals_buf = normals ? wrap(ctx, normals->plane(0), image_bytes(*normals), CL_MEM_READ_ONLY)
                                         : guide_buf;
        cl::Buffer taps_buf(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, taps.size() * sizeof(int),
                            const_cast<int*>(taps.data()));
        cl::Buffer weights_buf(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, weights.size() * sizeof(float),
                               const_cast<float*>(weights.data()));
        cl::Buffer out_buf = wrap(ctx, out.plane(0), image_bytes(out), CL_MEM_WRITE_ONLY);
        const std::size_t flag_bytes = std::size_t(mask.height()) * sizeof(int);
        cl::Buffer flags = wrap(ctx, bad_rows, flag_bytes, CL_MEM_READ_WRITE);

        if (!separable) {
            cl::Kernel& k = kernel("bilateral_full");
            k.setArg(0, mask_buf);
            k.setArg(1, guide_buf);
            k.setArg(2, normals_buf);
            k.setArg(3, taps_buf);
            k.setArg(4, weights_buf);
            k.setArg(5, out_buf);
            k.setArg(6, flags);
            k.setArg(7, sizeof(BilateralParams), &params);
            k.setArg(8, 0);
            launch_pixels(queue, k, out.width(), out.height());
        } else {
            BilateralParams p = params;
            p.pass = detail::dims_of(out);  // a whole-image intermediate of the output's geometry
            p.pass_first_row = 0;
            cl::Buffer pass(ctx, CL_MEM_READ_WRITE, image_bytes(out));
            cl::Kernel& h = kernel("bilateral_horizontal");
            h.setArg(0, mask_buf);
            h.setArg(1, guide_buf);
            h.setArg(2, normals_buf);
            h.setArg(3, taps_buf);
            h.setArg(4, weights_buf);
            h.setArg(5, pass);
            h.setArg(6, flags);
            h.setArg(7, sizeof(BilateralParams), &p);
            h.setArg(8, 0);
            launch_pixels(queue, h, out.width(), out.height());
            cl::Kernel& v = kernel("bilateral_vertical");
            v.setArg(0, pass);
            v.setArg(1, guide_buf);
            v.setArg(2, normals_buf);
            v.setArg(3, taps_buf);
            v.setArg(4, weights_buf);
            v.setArg(5, out_buf);
            v.setArg(6, sizeof(BilateralParams), &p);
            v.setArg(7, 0);
            launch_pixels(queue, v, out.width(), out.height());
        }
        sync_to_host(queue, out_buf, image_bytes(out));
        sync_to_host(queue, flags, flag_bytes);
    });
}

}  // namespace penumbra::cl_backend
