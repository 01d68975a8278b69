#include "support/vsm_reference.h"

#include <algorithm>
#include <cmath>

#include "support/maps.h"

namespace penumbra::testing {

Moments covered_moments(const Image& depth, double x0, double x1, double y0, double y1)
{
    double s1 = 0.0, s2 = 0.0;
    for (int y = int(std::floor(y0)); y < int(std::ceil(y1)); ++y)
        for (int x = int(std::floor(x0)); x < int(std::ceil(x1)); ++x) {
            const double weight = (std::min(x1, x + 1.0) - std::max(x0, double(x))) *
                                  (std::min(y1, y + 1.0) - std::max(y0, double(y)));
            const float z = depth.at(0, x, y);
            s1 += weight * double(z);
            s2 += weight * (double(z) * z);
        }
    const double area = (x1 - x0) * (y1 - y0);
    return {s1 / area, s2 / area};
}

double chebyshev_upper_bound(double raw_variance, double d, double min_variance)
{
    if (d <= 0.0) return 1.0;
    const double var = std::max(raw_variance, min_variance);
    return var / (var + d * d);
}

BothPrecisions::BothPrecisions(int width, int height, std::uint32_t seed)
    : ctx(ContextOptions{Backend::Scalar, {}}),
      exact(build_moment_table(ctx, random_depth(width, height, seed), 2, Precision::Exact)),
      floats(build_moment_table(ctx, random_depth(width, height, seed), 2, Precision::Float)),
      rx(receivers_at_depth(width, height, 0.5f))
{
}

}  // namespace penumbra::testing
