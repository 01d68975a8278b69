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

constexpr int kBandHeight = 32;

SatParams table_params(const Image& depth, const MomentTable& table, int bands)
{
    return detail::sat_params(depth, table, bands, kBandHeight);
}

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
        if (table.precision() == Precision::Exact)
            build_table_as<KernelId::sat_bands_exact, std::uint32_t>(depth, table, bad_rows);
        else
            build_table_as<KernelId::sat_bands_float, float>(depth, table, bad_rows);
    });
}

template <KernelId K, class T>
void OpenClBackend::build_table_as(const Image& depth, MomentTable& table, int* bad_rows)
{
    const int bands = (depth.height() + kBandHeight - 1) / kBandHeight;
    const SatParams p = table_params(depth, table, bands);
    const auto target = table_output<T>(context(), table);
    const Output<T> carry = zeros<T>(context(), std::size_t(depth.height()) * table.planes());
    const Output<T> columns = zeros<T>(context(), std::size_t(p.columns.plane_pitch) * table.planes());
    const Output<int> flags = row_flags(context(), bad_rows, depth.height());
    launch<K>(Tasks{bands}, image_input(context(), depth), target.origin, carry, columns, flags, p);
    join_bands(target.origin, columns, p, Pixels{depth.width(), depth.height()});
    sync_to_host(queue(), target.storage, table.storage_elements() * 4);
    sync_to_host(queue(), flags);
}

}  // namespace penumbra::cl_backend
