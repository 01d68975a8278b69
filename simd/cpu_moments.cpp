// CPU launch of the moment family's encoded table build
// (kernels/encoded_table.h); its lookups (kernels/msm.h, msm_soft.h, evsm.h)
// run through the generic receiver_lookup (simd/cpu_lookup.cpp).
//
// Table schedule: bands of rows scanned in parallel, one TBB task per band,
// then sat_join_bands_* adds the column totals of the bands above to every
// pixel. About four bands per thread: enough to balance the threads, few
// enough that the join adds only a handful of totals per pixel.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <vector>

#include "simd/cpu_backend.h"
#include "simd/cpu_schedule.h"

namespace penumbra::cpu {
namespace {

constexpr int kBandsPerThread = 4;

int band_height(int height)
{
    const int bands = std::clamp(kBandsPerThread * tbb::this_task_arena::max_concurrency(), 1, height);
    return (height + bands - 1) / bands;
}

// Pass 1 (entry Bands, a task per band) then pass 2 (entry Join, per pixel).
template <KernelId Bands, KernelId Join, class T>
void build_in_bands(const CpuKernels& kernels, const Image& depth, T* origin, EncodedSatParams p, int* bad_rows)
{
    const int bands = (depth.height() + p.band_height - 1) / p.band_height;
    std::vector<T> columns(std::size_t(p.columns.plane_pitch) * std::size_t(p.channels), T(0));
    T* column_sums = columns.data();
    launch_tasks<Bands>(kernels, bands, depth.plane(0), origin, column_sums, bad_rows, p);
    launch_pixels<Join>(kernels, depth.width(), depth.height(), origin, static_cast<const T*>(column_sums),
                        detail::join_params(p));
}

}  // namespace

void CpuBackend::build_encoded_table(const Image& depth, const EncodedSatParams& params, MomentTable& table,
                                     int* bad_rows)
{
    EncodedSatParams p = params;
    p.band_height = band_height(depth.height());
    const int bands = (depth.height() + p.band_height - 1) / p.band_height;
    const int pitch = padded_pitch(depth.width());
    p.columns = {depth.width(), bands, pitch, pitch * bands};
    if (table.precision() == Precision::Float)
        build_in_bands<KernelId::encoded_bands_float, KernelId::sat_join_bands_float>(kernels_, depth,
                                                                                      table.float_origin(), p, bad_rows);
    else
        build_in_bands<KernelId::encoded_bands_exact, KernelId::sat_join_bands_exact>(kernels_, depth,
                                                                                      table.exact_origin(), p, bad_rows);
}

}  // namespace penumbra::cpu
