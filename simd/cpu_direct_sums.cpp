// The band conversion of the CPU's direct window sums (simd/cpu_direct_sums.h).
#include "simd/cpu_direct_sums.h"

#include <array>
#include <cmath>

#include "host/backend/backend.h"

namespace penumbra::cpu {
namespace {

// The texel row of a clamped v, as kernels/box_window.h's texel_window_xy
// computes it (the float32 product, floored, clamped into the map).
int texel_row(float v, int height)
{
    return int(std::clamp(std::floor(v * float(height)), 0.0f, float(height - 1)));
}

}  // namespace

bool band_map_rows(const CpuKernels& kernels, const Image& receivers, pn_dims map, int radius, int y0, int y1,
                   MapRows& rows)
{
    std::array<float, kMaxLanes> low{}, high{};
    const pn_dims strip{kernels.lanes, 1, kernels.lanes, kernels.lanes};
    kernels.receiver_v_bounds(receivers.plane(0), detail::dims_of(receivers), y0, y1, low.data(), high.data(), strip);
    const float lowest = *std::min_element(low.begin(), low.begin() + kernels.lanes);
    const float highest = *std::max_element(high.begin(), high.begin() + kernels.lanes);
    rows.first = std::max(texel_row(lowest, map.height) - radius, 0);
    rows.last = std::min(texel_row(highest, map.height) + radius + 1, map.height);
    const double converted = double(rows.last - rows.first) * map.width;
    const double taps = double(y1 - y0) * receivers.width() * (2.0 * radius + 1) * (2.0 * radius + 1);
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
