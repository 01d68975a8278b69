// Independent references for the moment family (kernels/msm.h, msm_soft.h,
// moment_quantize.h, evsm.h), in double precision and by other means than the
// kernels: generic Gaussian elimination instead of the L D L^T factorisation,
// Vandermonde solves for the weights instead of closed forms, and a linear
// program over a grid as the judge of "the sharpest bound".
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/moments.h"

namespace penumbra::testing {

// (1, E[z], E[z^2], E[z^3], E[z^4]).
using Moments4 = std::array<double, 5>;

struct Atom {
    double x, w;  // depth and weight
};

Moments4 moments_of(const std::vector<Atom>& atoms);
// (1 - alpha) b + alpha (moments of half at 0, half at 1).
Moments4 biased(const Moments4& b, double alpha);

// The optimized quantization (Peters & Klein 2015), in double: o = T m + offset.
std::array<double, 4> optimized_encode(double z);
// o rounded into 16-bit steps, each clamped to [0, 65535].
std::array<std::uint32_t, 4> optimized_steps(double z);
// The moments of window means of o (the paper's inverse matrix).
Moments4 optimized_decode(const std::array<double, 4>& o);
// T and T^-1 as the paper prints them, row-major.
const std::array<std::array<double, 4>, 4>& optimized_matrix();
const std::array<std::array<double, 4>, 4>& optimized_inverse();

// The sharpest lower bound on P(Z < z) over distributions on [0, 1] with
// moments b: the Hamburger canonical
// representation through z when its points lie in [0, 1], else the
// Hausdorff one {0, z, r, 1}. A singular Hankel matrix (relative pivot below
// 1e-13) means one or two points, which the moments determine.
struct BoundReference {
    double intensity;            // the bound
    bool hausdorff;              // the fallback was taken
    std::vector<Atom> support;   // the representation (weights may be slightly negative from rounding)
};
BoundReference msm_bound(const Moments4& b, double z);

// min over w >= 0 on the points `grid` of sum_{x_i < z} w_i subject to the
// five moments: a dense two-phase simplex. Returns -1 when infeasible.
double lp_lower_bound(const Moments4& b, double z, const std::vector<double>& grid);

// The blockers of the Hamburger canonical representation through z (the
// support points in front of z): total weight and mean depth.
struct BlockerReference {
    double weight, depth;
};
BlockerReference msm_blockers(const Moments4& b, double z);

// Window moments of an MSM table over texels [x0, x1) x [y0, y1), decoded in
// double from the table's own sums (exact: its integers; float: its floats).
Moments4 table_moments(const MsmTable& table, int x0, int x1, int y0, int y1);

}  // namespace penumbra::testing
