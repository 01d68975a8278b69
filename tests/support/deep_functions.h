// Visibility functions for the deep shadow map tests: random valid ones from a
// seed, and a brute-force evaluation independent of the library's
// (deep_visibility's binary search): a linear scan in long double, with both
// one-sided limits, so that a step is checked on both of its sides.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

namespace penumbra::testing {

struct Function {
    std::vector<float> z, t;
};

// V(d-) (side < 0: the value just before depth d) or V(d+) (side > 0).
inline long double brute_visibility(const Function& f, double d, int side)
{
    const std::size_t n = f.z.size();
    if (n == 0) return 1.0L;
    // The last vertex strictly before d (left limit) or at or before d (right).
    std::size_t last = n;
    for (std::size_t i = 0; i < n; ++i)
        if (side < 0 ? double(f.z[i]) < d : double(f.z[i]) <= d) last = i;
    if (last == n) return 1.0L;
    if (last == n - 1) return f.t[n - 1];
    const long double z0 = f.z[last], z1 = f.z[last + 1], t0 = f.t[last], t1 = f.t[last + 1];
    if (z1 == z0) return side < 0 ? t0 : t1;
    return t0 + (t1 - t0) * ((long double)d - z0) / (z1 - z0);
}

// A function as a generator would make one: surfaces (steps of random
// opacity, some at one depth), stretches of fog (linear declines) and empty
// stretches, over depths in [start, start + span). `opaque` in [0, 1] is the
// chance that a surface is fully opaque.
inline Function random_function(std::uint32_t seed, int events, float start = 1.0f, float span = 10.0f,
                                float opaque = 0.05f)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Function f;
    float z = start + span * 0.1f * unit(rng);
    double t = 1.0;
    f.z.push_back(z), f.t.push_back(1.0f);
    for (int e = 0; e < events; ++e) {
        const float kind = unit(rng);
        if (kind < 0.7f) z += span / float(events) * 2.0f * unit(rng);  // 30%: at the previous depth
        if (kind < 0.4f) {                                               // fog: a linear decline
            t *= 1.0 - 0.3 * unit(rng);
        } else if (kind < 0.55f) {  // empty space: flat
        } else {                    // a surface: a step
            f.z.push_back(z), f.t.push_back(float(t));
            t *= unit(rng) < opaque ? 0.0 : 1.0 - 0.5 * unit(rng);
        }
        f.z.push_back(z), f.t.push_back(std::min(float(t), f.t.back()));
    }
    return f;
}

}  // namespace penumbra::testing
