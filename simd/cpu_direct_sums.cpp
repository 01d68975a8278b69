// The band conversion of the CPU's direct window sums (simd/cpu_direct_sums.h).
#include "simd/cpu_direct_sums.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace penumbra::cpu {
namespace {

// The bits of a float as an int: for floats in [0, 1] the same order, so
// that the band's lowest and highest v are integer minima and maxima, which
// the compiler vectorises. A negative v (-0 included) reads as 0 and any
// larger one (NaN, infinity) as 1, as the kernels clamp v into [0, 1] (a NaN
// receiver is flagged and its output unspecified; its lane reads inside the
// band anyway, kernels/box_window.h).
constexpr std::int32_t kOneBits = 0x3f800000;

std::int32_t clamped_bits(float v)
{
    std::int32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return std::min(std::max(bits, std::int32_t(0)), kOneBits);
}

float from_bits(std::int32_t bits)
{
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

// The texel row of a clamped v, as kernels/box_window.h's texel_window_xy
// computes it (the float32 product, floored, clamped into the map).
int texel_row(float v, int height)
{
    return int(std::clamp(std::floor(v * float(height)), 0.0f, float(height - 1)));
}

}  // namespace

bool band_map_rows(const Image& receivers, pn_dims map, int radius, int y0, int y1, MapRows& rows)
{
    std::int32_t low = kOneBits, high = 0;
    for (int y = y0; y < y1; ++y) {
        const float* v = receivers.row(1, y);
        for (int x = 0; x < receivers.width(); ++x) {
            const std::int32_t bits = clamped_bits(v[x]);
            low = std::min(low, bits);
            high = std::max(high, bits);
        }
    }
    rows.first = std::max(texel_row(from_bits(low), map.height) - radius, 0);
    rows.last = std::min(texel_row(from_bits(high), map.height) + radius + 1, map.height);
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
