// The CPU schedule of the entries that read a shadow map through a DirectMap
// (kernels/params.h) stored in another convention than normalised depth: the
// direct window sums (vsm_direct, msm_direct, evsm_direct; kernels/box_window.h)
// and the soft discs (pcss, burley; kernels/hammersley.h). Each tap converts
// the texel it reads, so a texel is converted once per tap that reads it
// ((2r + 1)^2 times for windows of receivers one per texel, up to 40 times
// for the discs), and a rational convention divides each time
// (docs/integration.md, "Depth conventions"). Here a band of receiver rows
// first converts the map rows its taps reach, once, into a buffer of its
// thread, and its strips read that buffer as normalised depth: the same
// conversion of the same texels, so the same values, bit for bit. A band
// whose taps spread over more map texels than they number (receivers
// scattered over the map, discs wider than the map) keeps the per-tap
// conversion; a strip whose discs outgrow the band (a filter disc wider than
// tap_reach guessed) is run again over the stored map (PN_BAND_RERUN).
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
// evsm_direct's, and their table twins', which share them; pcss's and burley's).
template <class Params>
concept ReadsDirectMap = requires(const Params& p) { p.direct; };

// Whether the band conversion saves anything: the host sets rows.height for
// the direct entries only, and normalised depth is not converted at all.
template <ReadsDirectMap Params>
bool converts_per_band(const Params& p)
{
    return p.direct.rows.height > 0 && p.direct.convention.kind != PN_DEPTH_NORMALIZED;
}

// How far a receiver's taps reach from its own row of the map, and how many
// it reads: the rows of v H - radius H .. v H + radius H, then `rows` more.
struct TapReach {
    pn_dims map;       // the whole map
    float radius = 0;  // texture units: a disc's; 0 for a box window
    int rows = 0;      // a box window's radius in texels; a disc's margin
    int taps = 1;      // per receiver
};

// A box window of radius r texels: (2r + 1)^2 taps.
template <class Params>
    requires requires(const Params& p) { p.table; p.radius; }
TapReach tap_reach(const Params& p)
{
    return TapReach{p.table, 0.0f, p.radius, (2 * p.radius + 1) * (2 * p.radius + 1)};
}

// The soft discs' blocker and filter taps (simd/cpu_direct_sums.cpp says
// which radius).
TapReach tap_reach(const SoftPcfParams& p);

// The map rows [first, last) that the taps of receiver rows [y0, y1) reach,
// if converting them costs fewer conversions than the taps.
struct MapRows {
    int first = 0, last = 0;
};
inline constexpr int kMaxLanes = 64;  // above any strip receiver_v_bounds writes (AVX-512: 16 floats)
bool band_map_rows(const CpuKernels& kernels, const Image& receivers, const TapReach& reach, int y0, int y1,
                   MapRows& rows);

// Map rows `rows` converted into `buffer`: the DirectMap that reads them as
// normalised depth.
DirectMap convert_map_rows(const CpuKernels& kernels, const float* map, const DirectMap& stored, MapRows rows,
                           std::vector<float>& buffer);

// Entry K (Params reading a DirectMap) over the receivers, in bands of
// kDirectBandRows rows; a strip left to the schedule (PN_BAND_RERUN in its
// first lane, which always lies inside the row) runs again over the stored map.
template <KernelId K, class Params>
void launch_in_bands(const CpuKernels& kernels, const float* map, const Image& receivers, Image& out, int* bad_rows,
                     const Params& p)
{
    const CpuEntry<K> kernel = entry<K>(kernels);
    const TapReach reach = tap_reach(p);
    tbb::enumerable_thread_specific<std::vector<float>> buffers;
    const int bands = (out.height() + kDirectBandRows - 1) / kDirectBandRows;
    tbb::parallel_for(0, bands, [&](int band) {
        const int y0 = band * kDirectBandRows, y1 = std::min(out.height(), y0 + kDirectBandRows);
        Params q = p;
        const float* source = map;
        MapRows rows;
        if (band_map_rows(kernels, receivers, reach, y0, y1, rows)) {
            std::vector<float>& buffer = buffers.local();
            q.direct = convert_map_rows(kernels, map, p.direct, rows, buffer);
            source = buffer.data();
        }
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < out.width(); x += kernels.lanes) {
                kernel(source, receivers.plane(0), out.plane(0), bad_rows, q, x, y);
                if (source != map && out.at(0, x, y) == PN_BAND_RERUN)
                    kernel(map, receivers.plane(0), out.plane(0), bad_rows, p, x, y);
            }
    });
}

}  // namespace penumbra::cpu
