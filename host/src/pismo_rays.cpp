// The ray pattern of Pismo's shadow-ray test (pismo_rays.h states the formula).
#include "pismo_rays.h"

#include <algorithm>
#include <cmath>

#include "kernels/params.h"

namespace penumbra::detail {
namespace {

// C. Wellons' lowbias32: a 32-bit integer hash whose output bits each flip
// with probability near 1/2 when one input bit does.
std::uint32_t lowbias32(std::uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// At most 64 x 64 strata per triangle (kPismoMaxRays), so a stratum's index fits below 4096.
constexpr std::uint32_t kStrataPerTriangle = 4096;

}  // namespace

double pismo_jitter(std::uint32_t key) { return double(lowbias32(key) >> 8) * 0x1p-24; }

double pismo_triangle_area(const std::vector<std::array<double, 3>>& v, const std::array<int, 3>& t)
{
    const auto& a = v[std::size_t(t[0])];
    const auto& b = v[std::size_t(t[1])];
    const auto& c = v[std::size_t(t[2])];
    const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, f[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double x = e[1] * f[2] - e[2] * f[1], y = e[2] * f[0] - e[0] * f[2], z = e[0] * f[1] - e[1] * f[0];
    return 0.5 * std::sqrt(x * x + y * y + z * z);
}

PismoRayTable pismo_ray_table(const std::vector<std::array<double, 3>>& vertices,
                              const std::vector<std::array<int, 3>>& triangles, int rays)
{
    double total = 0;
    for (const auto& t : triangles) total += pismo_triangle_area(vertices, t);
    PismoRayTable table;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const double share = pismo_triangle_area(vertices, triangles[t]) / total;
        const int n = std::max(1, int(std::lround(std::sqrt(rays * share))));
        const std::uint32_t first = std::uint32_t(table.rays.size() / PN_PISMO_RAY_FLOATS);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const std::uint32_t key = 2 * (kStrataPerTriangle * std::uint32_t(t) + std::uint32_t(j * n + i));
                const double a = (i + pismo_jitter(key)) / n, b = (j + pismo_jitter(key + 1)) / n;
                const double r = std::sqrt(a);
                table.rays.insert(table.rays.end(),
                                  {float(1 - r), float(r * (1 - b)), float(r * b), float(share / (n * n))});
            }
        const std::uint32_t end = std::uint32_t(table.rays.size() / PN_PISMO_RAY_FLOATS);
        table.triangles.insert(table.triangles.end(), {std::uint32_t(triangles[t][0]), std::uint32_t(triangles[t][1]),
                                                       std::uint32_t(triangles[t][2]), first, end});
    }
    return table;
}

}  // namespace penumbra::detail
