#include "support/msm_windows.h"

#include <algorithm>
#include <cmath>

#include "support/maps.h"

namespace penumbra::testing {

std::vector<Atom> window_atoms(const Image& depth, int x, int y, int radius)
{
    std::vector<Atom> atoms;
    const int w = depth.width(), h = depth.height();
    for (int j = std::max(y - radius, 0); j < std::min(y + radius + 1, h); ++j)
        for (int i = std::max(x - radius, 0); i < std::min(x + radius + 1, w); ++i)
            atoms.push_back({double(depth.at(0, i, j)), 1.0});
    return atoms;
}

MsmTable msm_table_for(Context& ctx, const Image& depth, Quantization q)
{
    return build_msm_table(ctx, depth, q, q == Quantization::Bits32 ? Precision::Float : Precision::Exact);
}

namespace {

// The share of the biased window in front of z: (1 - alpha) of the atoms,
// plus alpha's half at depth 0 and half at depth 1 (biased()'s distribution).
double window_truth(const std::vector<Atom>& atoms, double alpha, double z)
{
    double in_front = 0.0, total = 0.0;
    for (const Atom& a : atoms) {
        total += a.w;
        in_front += a.x < z ? a.w : 0.0;
    }
    return (1.0 - alpha) * in_front / total + 0.5 * alpha * ((z > 0.0) + (z > 1.0));
}

}  // namespace

double msm_excess(const std::vector<Atom>& atoms, double alpha, double z, double shadow, double delta)
{
    const Moments4 b = biased(moments_of(atoms), alpha);
    const double lo = msm_bound(b, z - delta).intensity;
    const double hi = std::max(window_truth(atoms, alpha, z + delta), msm_bound(b, z + delta).intensity);
    return std::max({lo - shadow, shadow - hi, 0.0});
}

FewDepthWindow few_depth_window(std::mt19937& rng, int trial)
{
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), near(-0.05f, 0.05f);
    const int w = 9, h = 7, levels = 1 + int(rng() % 5);
    float level[5];
    for (float& l : level) l = std::floor(unit(rng) * 16.0f) / 16.0f;
    FewDepthWindow c{Image(w, h, 1), receivers_on_texels(w, h, w, h, 0.0f, 1.0f, 11u * trial), 0};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) c.depth.at(0, x, y) = level[rng() % levels];
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (rng() % 2) c.receivers.at(2, x, y) = level[rng() % levels] + near(rng);
    c.radius = int(rng() % 5);
    return c;
}

}  // namespace penumbra::testing
