// The fidelity reference of the moment family (issue 9): vsm, vssm, msm,
// msm-soft, evsm2 and evsm4 evaluated in long double (x87 extended, 64-bit
// mantissa) straight from the methods' formulas, by direct loops over the
// window of the float32 input depths. Nothing here reads the library's
// tables or kernels: the window contract, the formulas and the defaults are
// written again from the method docs (docs/moments.md, docs/fidelity.md and
// the kernel header comments).
//
// Window contract (as `penumbra shade`): box methods take the (2r+1)^2 block
// centred on the texel containing (u, v), u and v clamped into [0, 1] and the
// texel clamped into the map, clipped to the map, and so does VSSM's blocker
// search, with the radius floor(max(L W / 2, 1/2)) per axis. VSSM's filter
// window and both MSM-soft windows are fractional, centred at (u W, v H),
// their texels weighted by their overlap (the exact integral of the
// piecewise-constant map); their
// geometry (centre, half-widths, corners, the blocker depth the filter width
// is computed from) is float32 as in the library, their arithmetic long double.
//
// MSM follows the method as kernels/msm.h defines it: the moment bias, the
// Hamburger bound with the Hausdorff fallback, the window's own one or two
// depths (plus the bias atoms) where the biased Hankel matrix is singular or
// indefinite, and the clamp into Cantelli's bounds (a no-op for the moments
// of any distribution on [0, 1]).
//
// Moments are formed about the window's own mean (E[(Z - c)^k] summed
// directly), so that the float64 answer is not itself the victim of the
// cancellation the issue is about.
//
// The ill-conditioned rule (docs/fidelity.md). A receiver's movement is the
// largest change of the reference answer when each raw moment the method
// reads (VSM, VSSM: E[z], E[z^2]; MSM, MSM-soft: E[z] .. E[z^4]; EVSM:
// E[w], E[w^2] per warp) is scaled by (1 + s_k 2^-20), over every sign
// pattern s_k in {-1, +1} (VSM 4 patterns, EVSM2 4, EVSM4 16, MSM 16; VSSM
// and MSM-soft: the search window's and the filter window's moments
// perturbed by independent patterns, 16 and 256, the filter window following
// the perturbed blocker depth). A receiver whose movement exceeds the
// tolerance is ill-conditioned and is held to tolerance + 2 x movement, and
// to a finite value in [0, 1]; every other receiver is held to the
// tolerance. Tolerances: 2e-4 (vsm, vssm, evsm2, evsm4), 1e-3 (msm,
// msm-soft).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "penumbra/image.h"

namespace penumbra::testing::fidelity {

using real = long double;

enum class Method { Vsm, Vssm, Msm, MsmSoft, Evsm2, Evsm4 };
std::string method_name(Method m);
double tolerance(Method m);

// Per-texel raw moments E[z^k], k = 1..4, for a storage whose texels are not
// the powers of one depth: the opt-in 16-bit MSM table's dequantized
// moments. Its decoding is affine, so a window's dequantized moments are the
// window mean of its texels' (overlap-weighted for fractional windows).
struct StoredMoments {
    int width = 0, height = 0;
    std::vector<std::array<real, 4>> texel;  // row-major
};

using Transform = long double (*)(long double z, const struct Params& p);

// EVSM's warps of every texel of a map, row-major (an exp each: computed
// once per map rather than once per window texel).
struct WarpedMap {
    std::vector<real> positive, negative;
    const std::vector<real>* of(Transform f) const;
};

// Every parameter a method reads, with the library's defaults of the mode
// `penumbra shade` uses when no precision or quantization option is given.
struct Params {
    int radius = 2;                 // box methods
    float light_size = 0.02f;       // vssm, msm-soft
    int max_radius = 126;           // vssm, msm-soft: filter half-width clamp (texels) is max_radius + 0.5
    float min_variance = 2e-5f;     // vsm, vssm, evsm (depth^2)
    float bleed = 0.0f;             // vsm, vssm, evsm
    float moment_bias = 6e-5f;      // msm, msm-soft: alpha
    float msm_depth_bias = 2.0f / 65535.0f;  // msm, msm-soft
    float evsm_depth_bias = 0.0f;   // evsm
    float positive = 5.545177f;     // evsm: c+
    float negative = 5.545177f;     // evsm4: c-
    // msm-soft's plane bias (kernels/msm_soft.h) and the receivers' plane,
    // dz/du and dz/dv, the same at every receiver: the tests that set it
    // shade a planar receiver grid, whose plane is known in closed form.
    float plane_bias = 0.0f, plane_bias_max = 0.02f;
    real plane_dzdu = 0, plane_dzdv = 0;
    // msm, msm-soft: windows from these moments instead of the depths' powers.
    const StoredMoments* stored = nullptr;
    // evsm: the map's warps, when precomputed (warp_map); else warped per texel.
    const WarpedMap* warped = nullptr;
};

// A rectangle of texels [x0, x1) x [y0, y1).
struct Box {
    int x0, x1, y0, y1;
};
Box texel_window(int width, int height, float u, float v, int radius);
// The same grown by rx columns and ry rows (VSSM's search box).
Box texel_box(int width, int height, float u, float v, int rx, int ry);

// A fractional window in texel coordinates (exclusive corners), clipped.
struct Span {
    real x0, x1, y0, y1;
};
Span clip_span(int width, int height, real cx, real cy, real half_x, real half_y);

// A weighted depth distribution's moments about its mean c: central[k] =
// E[(Z - c)^k], k = 0 .. 4 (central[0] = 1, central[1] ~ 0).
struct Moments {
    real centre = 0;
    std::array<real, 5> central{1, 0, 0, 0, 0};
    real raw(int k) const;          // E[Z^k] by the binomial expansion
};
// From raw moments E[Z^k], k = 1..4 (used for the perturbed ones).
Moments from_raw(const std::array<real, 5>& raw);
// Raw moments scaled by (1 + s_k eps), s_k = +1 where bit k-1 of `signs` is set.
Moments perturbed(const Moments& m, int count, unsigned signs, real eps);

// The map as read (float32 depths, one channel) and a per-texel transform.
Moments box_moments(const Image& depth, Box b, Transform f, const Params& p);
Moments span_moments(const Image& depth, Span s, Transform f, const Params& p);
real identity(real z, const Params& p);
real positive_warp(real z, const Params& p);  // EVSM: e^{c+ (z - 1)}
real negative_warp(real z, const Params& p);  // EVSM: -e^{-c- z}
WarpedMap warp_map(const Image& depth, const Params& p);

// The methods' arithmetic on given moments.
real chebyshev_upper(const Moments& m, real z, real min_variance);
real linstep(real lo, real hi, real x);
// MSM: the lower bound on P(Z < z_f) of the biased moments, with the exact
// answers where the biased distribution has at most two support points.
real msm_intensity(const Moments& raw, real z_f, real alpha);
struct Blockers {
    real weight, depth;
};
Blockers msm_blockers(const Moments& raw, real z_f, real alpha);

// One receiver's reference answer and (on request) its movement.
struct Answer {
    real visibility;
    real movement = -1;  // < 0: not computed
};
struct Receiver {
    float u, v, z;
};
Answer evaluate(Method m, const Image& depth, Receiver r, const Params& p, bool with_movement);

// The rule: |library - reference| within the bound, and finite in [0, 1].
struct Verdict {
    bool pass;
    bool ill_conditioned;
    double deviation, bound, reference, movement;
};
// `reference`: the answer when already known (evaluate(...).visibility).
Verdict judge(Method m, const Image& depth, Receiver r, const Params& p, float library,
              const double* reference = nullptr);

}  // namespace penumbra::testing::fidelity
