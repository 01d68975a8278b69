// The float64 reference of the deep shadow map lookup (penumbra/deep_lookup.h,
// kernels/dsm_lookup.h): each pixel's function evaluated in double by its own
// search (the first vertex at or beyond z, as deep_visibility states the step
// convention), the box or tent weights summed in double over every pixel of
// the footprint, brute force. Written from the contract, not from the kernel.
// Also random deep maps with the pixels a lookup must survive.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "penumbra/deep_lookup.h"
#include "penumbra/deep_shadow_map.h"
#include "penumbra/image.h"

namespace penumbra::testing {

inline double reference_pixel_visibility(const DeepShadowMap& map, int x, int y, double z)
{
    const auto zs = map.depths(x, y);
    const auto ts = map.transmittances(x, y);
    std::size_t i = 0;
    while (i < zs.size() && double(zs[i]) < z) ++i;
    if (i == 0) return 1.0;
    if (i == zs.size()) return ts.back();
    const double z0 = zs[i - 1], z1 = zs[i], t0 = ts[i - 1], t1 = ts[i];
    return t0 + (t1 - t0) * (z - z0) / (z1 - z0);
}

// One receiver (u, v, z as read, float32) under `o`.
inline double reference_deep_lookup(const DeepShadowMap& map, const DeepLookupOptions& o, float u_in, float v_in,
                                    float z_in)
{
    const double u = std::clamp(double(u_in), 0.0, 1.0), v = std::clamp(double(v_in), 0.0, 1.0);
    // The contract evaluates each pixel at the float32 depth z - bias (as
    // the kernel receives it); on a steep segment one rounding of that depth
    // moves V by the segment's slope times half an ulp of z.
    const double z = double(z_in - o.bias);
    const int w = map.width(), h = map.height(), r = o.radius;
    double sum = 0, total = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double weight = 0;
            if (o.filter == DeepFilter::Box) {
                const int cx = std::clamp(int(std::floor(u * w)), 0, w - 1);
                const int cy = std::clamp(int(std::floor(v * h)), 0, h - 1);
                weight = std::abs(x - cx) <= r && std::abs(y - cy) <= r ? 1.0 : 0.0;
            } else {
                const double half = r + 1;
                const double wx = half - std::abs(x - (u * w - 0.5)), wy = half - std::abs(y - (v * h - 0.5));
                weight = wx > 0 && wy > 0 ? wx * wy : 0.0;
            }
            if (weight == 0) continue;
            sum += weight * reference_pixel_visibility(map, x, y, z);
            total += weight;
        }
    return sum / total;
}

// A random map: empty pixels, single steps, several steps, slopes, steps at
// one depth twice, all valid (t non-increasing from 1, depths sorted).
inline DeepShadowMap random_deep_map(int width, int height, std::uint32_t seed, int max_vertices = 12)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    DeepShadowMapBuilder builder(width, height);
    for (int p = 0; p < width * height; ++p) {
        std::vector<float> z, t;
        const int kind = int(rng() % 4);
        if (kind == 1) {  // one step
            const float d = unit(rng);
            z = {d, d};
            t = {1.0f, unit(rng)};
        } else if (kind >= 2) {  // a step (same depth, lower t) or a segment, at random
            const int n = 2 + int(rng() % unsigned(max_vertices - 1));
            float d = 0.05f * unit(rng), tv = 1.0f;
            z = {d};
            t = {tv};
            for (int i = 1; i < n; ++i) {
                if (rng() % 3 == 0) {
                    tv *= 0.3f + 0.6f * unit(rng);
                } else {
                    d += 0.9f / float(n) * unit(rng);
                    if (rng() % 2 == 0) tv *= 0.7f + 0.3f * unit(rng);
                }
                z.push_back(d);
                t.push_back(tv);
            }
        }
        builder.add_pixel(z, t);
    }
    return builder.build();
}

}  // namespace penumbra::testing
