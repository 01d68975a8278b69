// Random few-depth windows for MSM (kernels/msm.h) and the interval its answer
// must lie in, judged by the exact bound of support/moment_reference.h. Shared
// by tests/kernels/msm_test.cpp (the check) and bench/msm_bias_excess.cpp (the
// table of docs/moments.md, "Biases"): both draw the same windows.
#pragma once

#include <random>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/moments.h"
#include "support/moment_reference.h"

namespace penumbra::testing {

// The depths of VSM's box window around texel (x, y), one atom each.
std::vector<Atom> window_atoms(const Image& depth, int x, int y, int radius);

// MSM's table for `q` as its tests read it: float for 32-bit, exact limbs otherwise.
MsmTable msm_table_for(Context& ctx, const Image& depth, Quantization q);

// What the kernel may answer for a window of known depths: at least the
// sharpest bound its (biased) moments allow, and at most the truth, the share
// of the biased window in front of z (the two coincide where the moments
// determine the window: one or two depths, which the kernel answers exactly).
// Both jump where z crosses a depth, and float moments place the depths only
// to within a depth uncertainty: [bound(z - delta), truth(z + delta)]. The
// excess is how far `shadow` (1 - visibility) lies outside that interval.
double msm_excess(const std::vector<Atom>& atoms, double alpha, double z, double shadow, double delta);

// A 9 x 7 map of 1 to 5 depths (multiples of 1/16, so that float sums of z^k
// stay exact and distinct depths are far apart), receivers on every texel,
// half of them near a texel depth (+-0.05), and a box radius 0 to 4.
struct FewDepthWindow {
    Image depth, receivers;
    int radius;
};
FewDepthWindow few_depth_window(std::mt19937& rng, int trial);

}  // namespace penumbra::testing
