// The variance family's float64 reference (kernels/vsm.h, vssm.h and the
// Chebyshev bound they share): a window's first two moments of the float32
// depths, and the one-tailed Chebyshev bound. Shared by
// tests/kernels/chebyshev_test.cpp and vssm_test.cpp.
#pragma once

#include <cstdint>

#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"

namespace penumbra::testing {

struct Moments {
    double mean, mean_sq;
};

// E[z], E[z^2] over [x0, x1) x [y0, y1) (fractional, inside the map), each
// texel weighted by the area of it the window covers: the integral of the
// piecewise-constant map, which the table's bilinear interpolation at
// fractional corners computes (kernels/moment_table.h); an integer window
// weighs every texel 1. Of the float32 depths themselves: an exact limb table
// rounds z and z^2 to 2^-33, a float table of dyadic depths is exact.
Moments covered_moments(const Image& depth, double x0, double x1, double y0, double y1);

// p_max = var / (var + d^2) for d = z - mean > 0, else 1, with var floored at
// `min_variance` (Cantelli's inequality; Donnelly & Lauritzen 2006).
double chebyshev_upper_bound(double raw_variance, double d, double min_variance);

// The set-up of the parameter checks of vsm() and vssm(): a scalar context,
// the exact and the float moment table of one random map, and a receiver over
// each of its texels at depth 0.5.
struct BothPrecisions {
    BothPrecisions(int width, int height, std::uint32_t seed);
    Context ctx;
    MomentTable exact, floats;
    Image rx;
};

}  // namespace penumbra::testing
