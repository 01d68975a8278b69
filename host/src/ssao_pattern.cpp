// The volumetric-obscurance sample pattern (penumbra/ssao.h, ssao_pattern):
// equal-volume rings, golden-angle turns, brute-force Voronoi volumes.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "penumbra/ssao.h"

namespace penumbra {
namespace {

// Raster side of the notes' "image" of the disc: 1024^2 pixels put each
// cell's volume within about 1e-3 of its share (docs/ssao.md).
constexpr int kRaster = 1024;

// The disc radius inside which a unit sphere holds the share v of its
// volume: v = 1 - (1 - rho^2)^(3/2).
double radius_of_volume(double v) { return std::sqrt(1.0 - std::pow(1.0 - v, 2.0 / 3.0)); }

struct Point {
    double x, y;
};

// The nearest of the points to (x, y).
std::size_t nearest(const std::vector<Point>& points, double x, double y)
{
    std::size_t best = 0;
    double best_d = INFINITY;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double dx = points[i].x - x, dy = points[i].y - y, d = dx * dx + dy * dy;
        if (d < best_d) best_d = d, best = i;
    }
    return best;
}

// Each point's share of the sphere: the sum of the line lengths
// 2 sqrt(1 - x^2 - y^2) over the raster pixels nearest to it, normalised.
std::vector<double> voronoi_volumes(const std::vector<Point>& points)
{
    std::vector<double> volume(points.size(), 0.0);
    double total = 0;
    for (int j = 0; j < kRaster; ++j)
        for (int i = 0; i < kRaster; ++i) {
            const double x = 2.0 * (i + 0.5) / kRaster - 1.0, y = 2.0 * (j + 0.5) / kRaster - 1.0;
            const double r2 = x * x + y * y;
            if (r2 >= 1.0) continue;
            const double length = 2.0 * std::sqrt(1.0 - r2);
            volume[nearest(points, x, y)] += length;
            total += length;
        }
    for (double& v : volume) v /= total;
    return volume;
}

}  // namespace

SsaoPattern ssao_pattern(int pairs)
{
    check(kSsaoPairsRange, pairs, "ssao");
    // Point 0 is the centre, owning the innermost 1/K of the volume; pair j
    // sits in the middle of the next 2/K (K = 2 pairs + 1), at the golden
    // angle's j-th turn, so that rings and directions both spread.
    const double samples = 2.0 * pairs + 1.0;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    std::vector<Point> points{{0, 0}};
    for (int j = 0; j < pairs; ++j) {
        const double rho = radius_of_volume((2.0 + 2.0 * j) / samples);
        const double angle = golden * j;
        points.push_back({rho * std::cos(angle), rho * std::sin(angle)});
        points.push_back({-rho * std::cos(angle), -rho * std::sin(angle)});
    }
    const std::vector<double> volume = voronoi_volumes(points);
    SsaoPattern pattern;
    pattern.centre_weight = volume[0];
    for (int j = 0; j < pairs; ++j) {
        // The mirror's cell mirrors the point's; their mean cancels raster noise.
        const double w = 0.5 * (volume[1 + 2 * std::size_t(j)] + volume[2 + 2 * std::size_t(j)]);
        pattern.pairs.push_back({points[1 + 2 * std::size_t(j)].x, points[1 + 2 * std::size_t(j)].y, w});
    }
    return pattern;
}

double ssao_tile_angle(int x, int y)
{
    // The notes' "randomized rotations" table: which of the 16 sequential
    // angles each pixel of the 4x4 tile takes.
    static constexpr int kOffsets[16] = {4, 1, 3, 7, 8, 11, 15, 6, 10, 2, 14, 5, 0, 13, 12, 9};
    return kOffsets[(y & 3) * 4 + (x & 3)] * std::numbers::pi / 16.0;
}

}  // namespace penumbra
