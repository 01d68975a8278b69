// The band conversion of the CPU's direct window sums and soft discs (simd/cpu_direct_sums.h).
#include "simd/cpu_direct_sums.h"

#include <array>
#include <cmath>

#include "host/backend/backend.h"

namespace penumbra::cpu {
namespace {

// The texel row of a position t (texels) on the map, as kernels/box_window.h's
// texel_window_xy and kernels/hammersley.h's hammersley_texel take it
// (floored, clamped into the map).
int texel_row(float t, int height)
{
    return int(std::clamp(std::floor(t), 0.0f, float(height - 1)));
}

}  // namespace

TapReach tap_reach(const SoftPcfParams& p)
{
    // burley (light_size 0): max_radius, its blocker disc and, for z_b <= z,
    // its widest filter disc. pcss: L, twice its blocker disc, which holds
    // its filter disc L (z - z_b) / (2 z_b) wherever z_b >= z / 3; a wider
    // one reruns its strip. One margin row for the host's own rounding.
    return TapReach{p.depth, std::max(p.light_size, p.max_radius), 1, p.blocker_samples + p.filter_samples};
}

bool band_map_rows(const CpuKernels& kernels, const Image& receivers, const TapReach& reach, int y0, int y1,
                   MapRows& rows)
{
    std::array<float, kMaxLanes> low{}, high{};
    const pn_dims strip{kernels.lanes, 1, kernels.lanes, kernels.lanes};
    kernels.receiver_v_bounds(receivers.plane(0), detail::dims_of(receivers), y0, y1, low.data(), high.data(), strip);
    const float lowest = *std::min_element(low.begin(), low.begin() + kernels.lanes);
    const float highest = *std::max_element(high.begin(), high.begin() + kernels.lanes);
    const float h = float(reach.map.height), spread = reach.radius * h;
    rows.first = std::max(texel_row(lowest * h - spread, reach.map.height) - reach.rows, 0);
    rows.last = std::min(texel_row(highest * h + spread, reach.map.height) + reach.rows + 1, reach.map.height);
    const double converted = double(rows.last - rows.first) * reach.map.width;
    const double taps = double(y1 - y0) * receivers.width() * reach.taps;
    return converted < taps;
}

DirectMap convert_map_rows(const CpuKernels& kernels, const float* map, const DirectMap& stored, MapRows rows,
                           std::vector<float>& buffer)
{
    const int width = stored.rows.width, height = rows.last - rows.first;
    buffer.resize(std::size_t(width) * std::size_t(height));
    DirectMap band{};
    band.rows = pn_dims{width, height, width, width * height};
    band.first_row = rows.first;  // band.convention zeroed: normalised
    kernels.depth_convert_rows(map, stored.rows, buffer.data(), band.rows, stored.convention, rows.first, rows.last);
    return band;
}

}  // namespace penumbra::cpu
