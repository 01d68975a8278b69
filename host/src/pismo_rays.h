// The ray pattern of Pismo's shadow-ray test (kernels/pismo.h): the same for
// every receiver, so the kernel reads it as a table and the float64
// reference (tests/support/pismo_reference.cpp) computes the same formula on
// its own.
//
// Per triangle t of area share s (its area over the mesh's):
//   n = max(1, round(sqrt(rays s))), n x n strata of the unit square;
//   stratum (i, j), index q = j n + i, jittered by h(k) = (lowbias32(k) >> 8) / 2^24,
//     a = (i + h(2 (4096 t + q))) / n,  b = (j + h(2 (4096 t + q) + 1)) / n
//   (keys modulo 2^32; lowbias32 is C. Wellons' 32-bit integer hash);
//   weights (1 - sqrt(a), sqrt(a) (1 - b), sqrt(a) b), the area-preserving
//   map of the square onto the triangle; each ray weighs s / n^2.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "penumbra/pismo.h"

namespace penumbra::detail {

// h(k) above: a jitter in [0, 1) with 24 bits, exact in float and double.
double pismo_jitter(std::uint32_t key);

// The kernel's triangle and ray records (PN_PISMO_TRIANGLE_UINTS,
// PN_PISMO_RAY_FLOATS, kernels/params.h).
struct PismoRayTable {
    std::vector<std::uint32_t> triangles;
    std::vector<float> rays;
};

PismoRayTable pismo_ray_table(const std::vector<std::array<double, 3>>& vertices,
                              const std::vector<std::array<int, 3>>& triangles, int rays);

// Half the norm of the cross product of its edges.
double pismo_triangle_area(const std::vector<std::array<double, 3>>& vertices, const std::array<int, 3>& triangle);

// The first pass keeps one float per receiver and map; chunks of receiver
// rows bound it (1089 maps of a 1024-wide image: 15 rows a chunk).
inline constexpr std::size_t kPismoEstimateBytes = std::size_t(64) << 20;

// pismo_shade over a given ray pattern (tests give one ray at a vertex, and a
// small estimate budget to run many chunks): the maps and images checked as
// there, the options' values taken as valid.
void pismo_shade_rays(Context& context, const PismoMaps& maps, PismoRayTable rays, float bias_texels,
                      const Image& receivers, Image& out, std::size_t estimate_bytes = kPismoEstimateBytes);

}  // namespace penumbra::detail
