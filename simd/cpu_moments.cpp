// CPU launches of the moment family: the encoded table build
// (kernels/encoded_table.h) and the lookups (kernels/msm.h, msm_soft.h, evsm.h).
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

// The join pass reads the same geometry as the moment table's.
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

template <class T, class Bands, class Join>
void build_in_bands(const Image& depth, T* origin, EncodedSatParams p, int* bad_rows, int lanes, Bands bands_kernel,
                    Join join_kernel)
{
    const int bands = (depth.height() + p.band_height - 1) / p.band_height;
    std::vector<T> columns(std::size_t(p.columns.plane_pitch) * std::size_t(p.channels), T(0));
    tbb::parallel_for(0, bands,
                      [&](int band) { bands_kernel(depth.plane(0), origin, columns.data(), bad_rows, p, band); });
    const SatParams s = join_params(p);
    for_each_strip(depth.width(), depth.height(), lanes,
                   [&](int x, int y) { join_kernel(origin, columns.data(), s, x, y); });
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
        build_in_bands(depth, table.float_origin(), p, bad_rows, k_.lanes, k_.encoded_bands_float,
                       k_.sat_join_bands_float);
    else
        build_in_bands(depth, table.exact_origin(), p, bad_rows, k_.lanes, k_.encoded_bands_exact,
                       k_.sat_join_bands_exact);
}

void CpuBackend::moment_lookup(MomentMethod method, const MomentTable& table, const Image& receivers,
                               const MomentParams& p, Image& out, int* bad_rows)
{
    const float* rx = receivers.plane(0);
    float* result = out.plane(0);
    if (table.precision() == Precision::Float) {
        auto* kernel = method == MomentMethod::Msm ? k_.msm_float
                       : method == MomentMethod::MsmSoft ? k_.msm_soft_float
                                                         : k_.evsm_float;
        for_each_strip(out.width(), out.height(), k_.lanes,
                       [&](int x, int y) { kernel(table.float_origin(), rx, result, bad_rows, p, x, y); });
    } else {
        auto* kernel = method == MomentMethod::Msm ? k_.msm_exact
                       : method == MomentMethod::MsmSoft ? k_.msm_soft_exact
                                                         : k_.evsm_exact;
        for_each_strip(out.width(), out.height(), k_.lanes,
                       [&](int x, int y) { kernel(table.exact_origin(), rx, result, bad_rows, p, x, y); });
    }
}

}  // namespace penumbra::cpu
