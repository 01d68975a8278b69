// OpenCL launch of the summed-area table build (kernels/moment_table.h):
// bands of rows scanned in parallel (one work-item scans a band: a per-task
// launch), then the bands' column totals added to the bands below (per pixel).
// The two launches stay a schedule of their own: the scan is sequential along
// a band, so one work-item per pixel cannot express it.
#include <cstdint>
#include <type_traits>

#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {

using detail::KernelId;

namespace {

SatParams table_params(const Image& depth, const MomentTable& table, int bands)
{
    return detail::sat_params(depth, table, bands, kTableBandHeight);
}

}  // namespace

// The band height and column rows of this schedule, for a device table's build.
SatParams device_table_params(pn_dims depth, pn_dims table, int limbs)
{
    const int bands = (depth.height + kTableBandHeight - 1) / kTableBandHeight;
    return detail::sat_params(depth, table, 2, limbs, bands, kTableBandHeight);
}

namespace {

}  // namespace

template <class T>
void OpenClBackend::join_bands(const Output<T>& origin, const Output<T>& columns, const SatParams& params,
                               Pixels pixels)
{
    constexpr KernelId join = std::is_same_v<T, float> ? KernelId::sat_join_bands_float : KernelId::sat_join_bands_exact;
    launch<join>(pixels, origin, as_input(columns), params);
}
template void OpenClBackend::join_bands(const Output<float>&, const Output<float>&, const SatParams&, Pixels);
template void OpenClBackend::join_bands(const Output<std::uint32_t>&, const Output<std::uint32_t>&, const SatParams&,
                                        Pixels);

void OpenClBackend::build_moment_table(const Image& depth, MomentTable& table, int* bad_rows)
{
    translate_cl_errors([&] {
        const int bands = (depth.height() + kTableBandHeight - 1) / kTableBandHeight;
        const cl_mem_flags access = CL_MEM_READ_WRITE;
        cl::Buffer storage = table_storage(context(), table, access);
        const cl::Buffer origin = table_origin(storage, table, access);
        const Output<int> flags = row_flags(context(), bad_rows, depth.height());
        enqueue_table_build(image_input(context(), depth), origin,
                            table.storage_elements() * 4 - table.origin_offset_bytes(), table.precision(),
                            table_params(depth, table, bands), table.planes(), flags);
        sync_to_host(queue(), storage, table.storage_elements() * 4);
        sync_to_host(queue(), flags);
    });
}

void OpenClBackend::enqueue_table_build(const Input<float>& depth, const cl::Buffer& origin,
                                        std::size_t origin_bytes, Precision precision, const SatParams& params,
                                        int planes, const Output<int>& flags)
{
    if (precision == Precision::Exact)
        enqueue_table_build_as<KernelId::sat_bands_exact>(depth, Output<std::uint32_t>{origin, origin_bytes}, params,
                                                          planes, flags);
    else
        enqueue_table_build_as<KernelId::sat_bands_float>(depth, Output<float>{origin, origin_bytes}, params, planes,
                                                          flags);
}

template <KernelId K, class T>
void OpenClBackend::enqueue_table_build_as(const Input<float>& depth, const Output<T>& origin, const SatParams& p,
                                           int planes, const Output<int>& flags)
{
    const int bands = (p.depth.height + kTableBandHeight - 1) / kTableBandHeight;
    const Output<T> carry = device_zeros<T>(std::size_t(p.depth.height) * std::size_t(planes));
    const Output<T> columns = device_zeros<T>(std::size_t(p.columns.plane_pitch) * std::size_t(planes));
    launch<K>(Tasks{bands}, depth, origin, carry, columns, flags, p);
    join_bands(origin, columns, p, Pixels{p.depth.width, p.depth.height});
}

}  // namespace penumbra::cl_backend
