// OpenCL launches of the moment family: the encoded table build
// (kernels/encoded_table.h; bands of 32 rows, one work-item each, then the
// join of kernels/moment_table.h, as the moment table's build) and the
// lookups (kernels/msm.h, msm_soft.h, evsm.h; one work-item per receiver).
#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {
namespace {

constexpr int kBandHeight = 32;

SatParams join_params(const EncodedSatParams& p)
{
    SatParams s{};
    s.depth = p.depth;
    s.table = p.table;
    s.columns = p.columns;
    s.moments = p.channels;
    s.limbs = 1;
    s.band_height = p.band_height;
    return s;
}

const char* lookup_name(detail::BackendImpl::MomentMethod method, bool exact)
{
    using M = detail::BackendImpl::MomentMethod;
    if (method == M::Msm) return exact ? "msm_exact" : "msm_float";
    if (method == M::MsmSoft) return exact ? "msm_soft_exact" : "msm_soft_float";
    return exact ? "evsm_exact" : "evsm_float";
}

}  // namespace

void OpenClBackend::build_encoded_table(const Image& depth, const EncodedSatParams& params, MomentTable& table,
                                        int* bad_rows)
{
    translate_cl_errors([&] {
        const cl::Context& ctx = runtime_.context();
        const cl::CommandQueue& queue = runtime_.queue();
        const bool exact = table.precision() == Precision::Exact;
        const int bands = (depth.height() + kBandHeight - 1) / kBandHeight;
        const int pitch = padded_pitch(depth.width());
        EncodedSatParams p = params;
        p.band_height = kBandHeight;
        p.columns = {depth.width(), bands, pitch, pitch * bands};
        const SatParams s = join_params(p);

        const std::size_t table_bytes = table.storage_elements() * 4;
        cl::Buffer depth_buf = wrap(ctx, depth.plane(0), image_bytes(depth), CL_MEM_READ_ONLY);
        cl::Buffer storage = wrap(ctx, table.storage(), table_bytes, CL_MEM_READ_WRITE);
        cl::Buffer origin = table_origin(storage, table, CL_MEM_READ_WRITE);
        cl::Buffer columns = zeros(ctx, std::size_t(p.columns.plane_pitch) * std::size_t(p.channels) * 4);
        const std::size_t flag_bytes = std::size_t(depth.height()) * sizeof(int);
        cl::Buffer flags = wrap(ctx, bad_rows, flag_bytes, CL_MEM_READ_WRITE);

        cl::Kernel& scan = kernel(exact ? "encoded_bands_exact" : "encoded_bands_float");
        scan.setArg(0, depth_buf);
        scan.setArg(1, origin);
        scan.setArg(2, columns);
        scan.setArg(3, flags);
        scan.setArg(4, sizeof(EncodedSatParams), &p);
        scan.setArg(5, bands);
        queue.enqueueNDRangeKernel(scan, cl::NullRange, cl::NDRange(std::size_t(bands)));

        cl::Kernel& join = kernel(exact ? "sat_join_bands_exact" : "sat_join_bands_float");
        join.setArg(0, origin);
        join.setArg(1, columns);
        join.setArg(2, sizeof(SatParams), &s);
        join.setArg(3, 0);
        launch_pixels(queue, join, depth.width(), depth.height());
        sync_to_host(queue, storage, table_bytes);
        sync_to_host(queue, flags, flag_bytes);
    });
}

void OpenClBackend::moment_lookup(MomentMethod method, const MomentTable& table, const Image& receivers,
                                  const MomentParams& p, Image& out, int* bad_rows)
{
    table_lookup(lookup_name(method, table.precision() == Precision::Exact), table, receivers, &p, sizeof p, out,
                 bad_rows);
}

}  // namespace penumbra::cl_backend
