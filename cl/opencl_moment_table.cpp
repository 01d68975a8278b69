// OpenCL launch of the summed-area table build (kernels/moment_table.h):
// bands of rows scanned in parallel (one work-item scans a band), then the
// bands' column totals added to the bands below.
#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {
namespace {
constexpr int kBandHeight = 32;
}

void OpenClBackend::build_moment_table(const Image& depth, MomentTable& table, int* bad_rows)
{
    translate_cl_errors([&] {
        const cl::Context& ctx = runtime_.context();
        const cl::CommandQueue& queue = runtime_.queue();
        const bool exact = table.precision() == Precision::Exact;
        const int bands = (depth.height() + kBandHeight - 1) / kBandHeight;
        SatParams p{};
        p.depth = detail::dims_of(depth);
        p.table = detail::dims_of(table);
        p.moments = table.moments();
        p.limbs = table.limbs();
        p.encoding = table.values().kind;
        p.exponent_positive = table.values().positive;
        p.exponent_negative = table.values().negative;
        p.band_height = kBandHeight;
        p.columns = {depth.width(), bands, padded_pitch(depth.width()), padded_pitch(depth.width()) * bands};

        const std::size_t table_bytes = table.storage_elements() * 4;
        cl::Buffer depth_buf = wrap(ctx, depth.plane(0), image_bytes(depth), CL_MEM_READ_ONLY);
        cl::Buffer storage = wrap(ctx, table.storage(), table_bytes, CL_MEM_READ_WRITE);
        cl::Buffer origin = table_origin(storage, table, CL_MEM_READ_WRITE);
        cl::Buffer carry = zeros(ctx, std::size_t(depth.height()) * table.planes() * 4);
        cl::Buffer columns = zeros(ctx, std::size_t(p.columns.plane_pitch) * table.planes() * 4);
        const std::size_t flag_bytes = std::size_t(depth.height()) * sizeof(int);
        cl::Buffer flags = wrap(ctx, bad_rows, flag_bytes, CL_MEM_READ_WRITE);

        cl::Kernel& scan = kernel(exact ? "sat_bands_exact" : "sat_bands_float");
        scan.setArg(0, depth_buf);
        scan.setArg(1, origin);
        scan.setArg(2, carry);
        scan.setArg(3, columns);
        scan.setArg(4, flags);
        scan.setArg(5, sizeof(SatParams), &p);
        scan.setArg(6, bands);
        queue.enqueueNDRangeKernel(scan, cl::NullRange, cl::NDRange(std::size_t(bands)));

        cl::Kernel& join = kernel(exact ? "sat_join_bands_exact" : "sat_join_bands_float");
        join.setArg(0, origin);
        join.setArg(1, columns);
        join.setArg(2, sizeof(SatParams), &p);
        join.setArg(3, 0);
        launch_pixels(queue, join, depth.width(), depth.height());
        sync_to_host(queue, storage, table_bytes);
        sync_to_host(queue, flags, flag_bytes);
    });
}

}  // namespace penumbra::cl_backend
