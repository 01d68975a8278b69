// The CPU schedule of the direct window sums (vsm_direct, msm_direct,
// evsm_direct; kernels/box_window.h) over a map stored in another convention
// than normalised depth. Each window converts its taps as it reads them, so a
// texel is converted once per window that covers it ((2r + 1)^2 times for
// receivers one per texel), and a rational convention divides each time
// (docs/integration.md, "Depth conventions"). Here a band of receiver rows
// first converts the map rows its windows read, once, into a buffer of its
// thread, and its strips sum from that buffer as normalised depth: the same
// conversion of the same texels, so the same values, bit for bit. A band
// whose windows spread over more map texels than they have taps (receivers
// scattered over the map) keeps the per-tap conversion.
#pragma once

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "penumbra/image.h"
#include "simd/cpu_kernels.h"

namespace penumbra::cpu {

inline constexpr int kDirectBandRows = 32;  // receiver rows per band (docs/integration.md, "Depth conventions")

// Params that read the map through a DirectMap (vsm_direct's, msm_direct's,
// evsm_direct's, and their table twins', which share them).
template <class Params>
concept ReadsDirectMap = requires(const Params& p) { p.direct; };

// Whether the band conversion saves anything: the host sets rows.height for
// the direct entries only, and normalised depth is not converted at all.
template <ReadsDirectMap Params>
bool converts_per_band(const Params& p)
{
    return p.direct.rows.height > 0 && p.direct.convention.kind != PN_DEPTH_NORMALIZED;
}

// The map rows [first, last) that the windows of receiver rows [y0, y1)
// read, if converting them costs fewer conversions than the windows' taps.
struct MapRows {
    int first = 0, last = 0;
};
inline constexpr int kMaxLanes = 64;  // above any strip receiver_v_bounds writes (AVX-512: 16 floats)
bool band_map_rows(const CpuKernels& kernels, const Image& receivers, pn_dims map, int radius, int y0, int y1,
                   MapRows& rows);

// Map rows `rows` converted into `buffer`: the DirectMap that reads them as
// normalised depth.
DirectMap convert_map_rows(const CpuKernels& kernels, const float* map, const DirectMap& stored, MapRows rows,
                           std::vector<float>& buffer);

// Direct-sum entry K over the receivers, in bands of kDirectBandRows rows.
template <KernelId K, class Params>
void launch_direct_sums(const CpuKernels& kernels, const float* map, const Image& receivers, Image& out,
                        int* bad_rows, const Params& p)
{
    const CpuEntry<K> kernel = entry<K>(kernels);
    tbb::enumerable_thread_specific<std::vector<float>> buffers;
    const int bands = (out.height() + kDirectBandRows - 1) / kDirectBandRows;
    tbb::parallel_for(0, bands, [&](int band) {
        const int y0 = band * kDirectBandRows, y1 = std::min(out.height(), y0 + kDirectBandRows);
        Params q = p;
        const float* source = map;
        MapRows rows;
        if (band_map_rows(kernels, receivers, p.table, p.radius, y0, y1, rows)) {
            std::vector<float>& buffer = buffers.local();
            q.direct = convert_map_rows(kernels, map, p.direct, rows, buffer);
            source = buffer.data();
        }
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < out.width(); x += kernels.lanes)
                kernel(source, receivers.plane(0), out.plane(0), bad_rows, q, x, y);
    });
}

}  // namespace penumbra::cpu
