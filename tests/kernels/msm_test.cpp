// MSM (kernels/msm.h) on every backend: against the exact sharpest bound
// (tests/support/moment_reference.h, itself checked against a linear program),
// on the windows where it is known to fail (one depth, two depths, depths 0
// and 1, receivers at a blocker's depth, the 16-bit limits, windows up to the
// whole map) and the overlap case against VSM (every backend against the
// scalar one: kernels/moments_cross_backend_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "penumbra/chebyshev.h"
#include "penumbra/moments.h"
#include "support/backends.h"
#include "support/maps.h"
#include "support/moment_reference.h"
#include "support/msm_windows.h"
#include "support/visibility.h"

namespace penumbra {
namespace {

using testing::expect_visibility;
using testing::Atom;
using testing::backend_names;
using testing::backend_test_name;
using testing::Moments4;
using testing::msm_excess;
using testing::msm_table_for;
using testing::window_atoms;

// ---- the reference itself -----------------------------------------------------

// The closed forms of the reference (Hamburger's three points, Hausdorff's
// four) are the optimum of the moment problem: a linear program over a grid
// that includes their support finds nothing lower, on random distributions
// that exercise both (no kernel involved).
TEST(MsmReference, IsTheSharpestBoundByLinearProgramming)
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0), weight(0.1, 1.0);
    double worst = 0.0;
    int hausdorff = 0;
    for (int trial = 0; trial < 120; ++trial) {
        std::vector<Atom> atoms;
        for (int i = 0, n = 1 + int(rng() % 5); i < n; ++i) atoms.push_back({unit(rng), weight(rng)});
        const Moments4 b = testing::biased(testing::moments_of(atoms), 0.01);
        const double z = 0.01 + 0.98 * unit(rng);
        const testing::BoundReference ref = testing::msm_bound(b, z);
        std::vector<double> grid;
        for (int i = 0; i <= 300; ++i) grid.push_back(i / 300.0);
        for (const Atom& a : ref.support) grid.push_back(std::clamp(a.x, 0.0, 1.0));
        grid.push_back(z);
        const double lp = testing::lp_lower_bound(b, z, grid);
        ASSERT_GE(lp, 0.0) << "infeasible linear program, trial " << trial;
        worst = std::max(worst, std::abs(lp - ref.intensity));
        hausdorff += ref.hausdorff;
        for (const Atom& a : ref.support) {
            EXPECT_GE(a.w, -1e-9) << "trial " << trial;
            EXPECT_TRUE(a.x >= -1e-9 && a.x <= 1.0 + 1e-9) << "trial " << trial << " support " << a.x;
        }
    }
    std::printf("[ msm reference ] 120 distributions, %d Hausdorff: max |LP - closed form| %.2g\n", hausdorff, worst);
    EXPECT_LT(worst, 1e-8);
    EXPECT_GT(hausdorff, 10);
    EXPECT_LT(hausdorff, 110);
}

// ---- against the reference, every backend --------------------------------------

class MsmTest : public ::testing::TestWithParam<std::string> {};

// Random windows (testing::few_depth_window) of 1 to 5 depths (multiples of 1/16, so that float sums of
// z^k stay exact and distinct depths are far apart), receivers anywhere and
// near texel depths, radii 0 to 4, both storages, two moment biases.
// Reference: the exact bound of the window's true (unquantized) moments,
// biased, and its truth. Tolerance 0.01 at a depth uncertainty of 1e-3 for 32-bit moments
// (exact here) and 1e-2 for 16-bit ones, whose rounding misplaces support
// points near small depths by up to that (docs/moments.md, "Accuracy").
PN_BACKEND_TEST(MsmTest, WithinTheExactBoundUpToDepthUncertainty)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (Quantization q : {Quantization::None, Quantization::Bits32})
        for (float alpha : {6e-5f, 1e-3f}) {
            std::mt19937 rng(7);
            const double delta = q == Quantization::Bits16 ? 1e-2 : 1e-3;
            double worst = 0.0;
            for (int trial = 0; trial < 80; ++trial) {
                const testing::FewDepthWindow c = testing::few_depth_window(rng, trial);
                const Image& rx = c.receivers;
                const Image out = msm(ctx, msm_table_for(ctx, c.depth, q), rx, MsmOptions{c.radius, alpha, 0.0f});
                expect_visibility(out, backend);
                for (int y = 0; y < rx.height(); ++y)
                    for (int x = 0; x < rx.width(); ++x) {
                        const std::vector<Atom> atoms = window_atoms(c.depth, x, y, c.radius);
                        const double e = msm_excess(atoms, alpha, rx.at(2, x, y), 1.0 - out.at(0, x, y), delta);
                        worst = std::max(worst, e);
                        ASSERT_LE(e, 0.01)
                            << backend << " " << to_string(q) << " storage, alpha " << alpha << " trial " << trial
                            << " receiver " << x << "," << y << " z " << rx.at(2, x, y);
                    }
            }
            std::printf("[ msm ] %s %s storage, alpha %g: worst excess over the exact bound (delta %g) %.4f\n",
                        backend.c_str(), to_string(q).c_str(), alpha, delta, worst);
        }
}

// The default storage (exact 3-limb tables) against MSM in double on the
// float32 depths themselves (the reference's msm_bound of the biased window
// moments): random, ramp and near-0/near-1 two-layer maps, odd sizes, radii
// 0 to 20, receivers on, in front of and behind the surface; the issue's
// tolerance 1e-3, plus twice the movement for ill-conditioned receivers (the
// worst deviation of the well-conditioned ones is printed).
// The body of the two tests below: `q`'s table against MSM in double on the
// window's moments, the float32 depths' own (None) or the dequantized
// 16-bit ones (Bits16: testing::table_moments decodes the table's exact
// sums in double), with the conditioning rule. Windows whose biased
// moments are no moment vector (possible only when dequantized) are checked
// for validity only.
void expect_msm_in_double(Context& ctx, const std::string& backend, Quantization q)
{
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    double worst = 0.0;
    int checked = 0, skipped = 0;
    for (int trial = 0; trial < 18; ++trial) {
        const int w = 1 + int(rng() % 33), h = 1 + int(rng() % 17);
        Image depth(w, h, 1);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                depth.at(0, x, y) = trial % 3 == 0   ? unit(rng)
                                    : trial % 3 == 1 ? float(x + 2 * y) / float(w + 2 * h)
                                                     : (rng() % 3 ? 0.05f : 0.97f) + 1e-4f * unit(rng);
        const MsmTable table = build_msm_table(ctx, depth, q);
        Image rx = testing::receivers_on_texels(w, h, w, h, 0.0f, 1.0f, rng());
        for (int i = 0; i < w * h; ++i) {
            const int x = i % w, y = i / w;
            if (i % 3 == 0) rx.at(2, x, y) = depth.at(0, x, y);
            if (i % 3 == 1) rx.at(2, x, y) = depth.at(0, x, y) + 0.05f * (unit(rng) - 0.5f);
        }
        const float alpha = default_moment_bias(q);
        const double bias = default_depth_bias(q);
        for (int radius : {0, 1, 3, 20}) {
            const Image out = msm(ctx, table, rx, MsmOptions{radius, {}, {}});
            expect_visibility(out, backend);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const int x0 = std::max(x - radius, 0), x1 = std::min(x + radius + 1, w);
                    const int y0 = std::max(y - radius, 0), y1 = std::min(y + radius + 1, h);
                    const Moments4 raw = q == Quantization::Bits16
                                             ? testing::table_moments(table, x0, x1, y0, y1)
                                             : testing::moments_of(window_atoms(depth, x, y, radius));
                    const Moments4 b = testing::biased(raw, alpha);
                    const double z = double(rx.at(2, x, y)) - bias;
                    auto answer = [&](Moments4 m) {
                        // kernels/msm.h's safety net, part of the method as it defines
                        // it: the intensity within Cantelli's two-sided bounds of (b1', b2')
                        // (a no-op on valid moments; dequantized ones can leave the moment
                        // space), then in [0, 1].
                        const double var = std::max(m[2] - m[1] * m[1], 0.0);
                        auto tail = [&](double d) { return d <= 0.0 ? 1.0 : var / std::max(var + d * d, 1e-300); };
                        const double lower = 1.0 - tail(z - m[1]), upper = tail(m[1] - z);
                        const double g = std::clamp(std::clamp(testing::msm_bound(m, z).intensity, lower, upper), 0.0, 1.0);
                        return z <= 0.0 ? 1.0 : z > 1.0 ? 0.0 : 1.0 - g;
                    };
                    const double want = answer(b);
                    // The conditioning probe: each moment moved by a relative
                    // 2^-20 either way; where the answer moves by more than the
                    // tolerance, the tolerance grows by twice that movement.
                    double movement = 0.0;
                    for (int k = 1; k <= 4; ++k)
                        for (double sign : {-1.0, 1.0}) {
                            Moments4 moved = b;
                            moved[k] *= 1.0 + sign * 0x1p-20;
                            movement = std::max(movement, std::abs(answer(moved) - want));
                        }
                    // Dequantized moments can leave the moment space (a Hankel matrix
                    // that is not positive definite even after the bias): there the
                    // kernel's fallbacks (kernels/msm.h: two-point fit, Cantelli) define
                    // the answer, which the reference's bound does not model.
                    const double d2 = b[2] - b[1] * b[1];
                    const double d3d2 = (b[4] - b[2] * b[2]) * d2 - std::pow(b[3] - b[1] * b[2], 2);
                    const bool ill = movement > 1e-3 || !(d2 > 0.0 && d3d2 > 1e-13 * b[4] * d2);
                    const double got = out.at(0, x, y);
                    if (ill) {
                        ++skipped;
                    } else {
                        ++checked;
                        worst = std::max(worst, std::abs(got - want));
                    }
                    if (ill && !(d2 > 0.0 && d3d2 > 1e-13 * b[4] * d2)) continue;  // validity only
                    ASSERT_NEAR(got, want, 1e-3 + (ill ? 2.0 * movement : 0.0))
                        << backend << " trial " << trial << " r=" << radius << " at " << x << "," << y << " z "
                        << rx.at(2, x, y) << " movement " << movement;
                }
        }
    }
    std::printf("[ msm ] %s %s: worst |kernel - double| %.2g over %d receivers (and %d ill-conditioned)\n",
                backend.c_str(), to_string(q).c_str(), worst, checked, skipped);
}

PN_BACKEND_TEST(MsmTest, DefaultStorageIsTheMethodInDouble)
{
    expect_msm_in_double(PN_CONTEXT_OR_SKIP(backend), backend, Quantization::None);
}

// The opt-in 16-bit quantization: faithful to its dequantized moments (its
// own error against the depths is bench/msm_quantization_error's).
PN_BACKEND_TEST(MsmTest, SixteenBitStorageIsTheMethodOnItsDequantizedMoments)
{
    expect_msm_in_double(PN_CONTEXT_OR_SKIP(backend), backend, Quantization::Bits16);
}

// ---- the windows where it fails, every backend -----------------------------------

// Every 16-bit depth as a one-texel window (and, on a constant map, windows of
// every size). The biased window is three atoms (alpha / 2 at 0 and 1): its
// Hankel matrix is definite, so the answer is the sharp bound of the biased
// moments (the reference's msm_bound, in double), which is 1 - alpha/2 in
// front of the depth and alpha/2 well behind it; just behind it the bound is
// lighter than the atoms' truth, as the method defines.
PN_BACKEND_TEST(MsmTest, EverySixteenBitDepthAsAOneDepthWindow)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image depth(256, 256, 1);
    for (int i = 0; i < 65536; ++i) depth.at(0, i % 256, i / 256) = float(i) / 65535.0f;
    const MsmTable table = msm_table_for(ctx, depth, Quantization::None);
    const float alpha = kMsmMomentBiasExact, step = 1.0f / 65535.0f;
    struct Case {
        float shift;   // receiver depth - texel depth
        float expect;  // visibility
    };
    // At the depth itself the default depth bias (2 steps) lights it; 3 steps behind is dark.
    for (Case c : {Case{-1.0f, 1.0f - alpha / 2}, Case{-0.01f, 1.0f - alpha / 2}, Case{0.0f, 1.0f - alpha / 2},
                   Case{3 * step, alpha / 2}, Case{0.01f, alpha / 2}, Case{1.0f, alpha / 2}}) {
        Image rx = testing::receivers_at_depth(256, 256, 0.0f);
        for (int i = 0; i < 65536; ++i) rx.at(2, i % 256, i / 256) = float(i) / 65535.0f + c.shift;
        const Image out = msm(ctx, table, rx, MsmOptions{0, {}, {}});
        expect_visibility(out, backend);
        for (int i = 0; i < 65536; ++i) {
            const double z = double(rx.at(2, i % 256, i / 256)) - double(kMsmDepthBiasExact);
            const Moments4 b = testing::biased(testing::moments_of({{double(depth.at(0, i % 256, i / 256)), 1}}), alpha);
            // The near plane and beyond the far plane are exact by definition.
            const double want = z <= 0.0 ? 1.0 : (z > 1.0 ? 0.0 : 1.0 - testing::msm_bound(b, z).intensity);
            // Within 2^-8 of 0 or 1 the biased Hankel matrix is nearly singular
            // (det ~ alpha^2 z^2 / 4, down to 1e-18): the float64 answer itself moves
            // by more than the tolerance when the moments move by a relative 2^-20
            // (an ill-conditioned receiver, issue 9); there only validity is checked.
            // So is a receiver a few 1e-5 behind the depth: the bound's support
            // point sits within 1e-7 of 1, where Hamburger hands over to Hausdorff.
            const float depth_i = depth.at(0, i % 256, i / 256);
            if (depth_i < 1.0f / 256.0f || depth_i > 255.0f / 256.0f || c.shift == 3 * step) continue;
            ASSERT_NEAR(out.at(0, i % 256, i / 256), want, 1e-3) << backend << " depth " << i << "/65535 shift "
                                                                 << c.shift;
            if (std::abs(c.shift) >= 0.01f && z > 0.0 && z < 1.0) {
                ASSERT_NEAR(out.at(0, i % 256, i / 256), c.expect, 1e-4) << backend << " depth " << i;
            }
        }
    }
}

// A constant map, every window size up to the whole map (exact: up to the
// 255 x 255 limit; float: beyond the map), both storages.
PN_BACKEND_TEST(MsmTest, ConstantMapsAnyWindow)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (Quantization q : {Quantization::None, Quantization::Bits32})
        for (float level : {0.0f, 0.0625f, 0.5f, 0.9375f, 1.0f}) {
            Image depth(37, 23, 1);
            depth.fill(0, level);
            const MsmTable table = msm_table_for(ctx, depth, q);
            const float alpha = default_moment_bias(q);
            for (int radius : {0, 3, 40, 127})
                for (float shift : {-0.2f, -0.001f, 0.001f, 0.2f}) {
                    const float z = level + shift;
                    const Image rx = testing::receivers_at_depth(37, 23, z);
                    const Image out = msm(ctx, table, rx, MsmOptions{radius, {}, {}});
                    expect_visibility(out, backend);
                    const float zf = z - default_depth_bias(q);
                    // Exact storage: the bound of the biased moments (see above); float
                    // storage sees a one-depth window through its noise floor: exact atoms.
                    const Moments4 b = testing::biased(testing::moments_of({{double(level), 1}}), alpha);
                    const double bound = 1.0 - testing::msm_bound(b, double(z) - default_depth_bias(q)).intensity;
                    const double atoms = shift < 0 ? 1.0f - alpha / 2 : alpha / 2;
                    const double inside = q == Quantization::None ? bound : atoms;
                    const double want = zf <= 0.0f ? 1.0 : zf > 1.0f ? 0.0 : inside;
                    for (int i = 0; i < 37 * 23; ++i)
                        ASSERT_NEAR(out.at(0, i % 37, i / 37), want, 1e-5)
                            << backend << " " << to_string(q) << "-bit level " << level << " r=" << radius << " z "
                            << z;
                }
        }
}

// Depths 0 and 1 only: the biased Hankel matrix is singular (the bias lives
// there too). The two-point answer is exact: between 0 and 1 the lit share is
// the share of ones, (1 - alpha) f + alpha / 2.
PN_BACKEND_TEST(MsmTest, DepthsZeroAndOneOnly)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image depth = testing::binary_depth(23, 11, 3, 3);
    for (Quantization q : {Quantization::None, Quantization::Bits32}) {
        const MsmTable table = msm_table_for(ctx, depth, q);
        const float alpha = default_moment_bias(q);
        for (int radius : {0, 1, 4, 127})
            for (float z : {0.0f, 0.3f, 0.5f, 0.99f, 1.0f}) {
                const Image rx = testing::receivers_at_depth(23, 11, z);
                const Image out = msm(ctx, table, rx, MsmOptions{radius, {}, {}});
                expect_visibility(out, backend);
                for (int y = 0; y < 11; ++y)
                    for (int x = 0; x < 23; ++x) {
                        const double ones = testing::window_mean(depth, 1, x, y, radius);
                        const double want = z == 0.0f ? 1.0 : (1.0 - alpha) * ones + alpha / 2;
                        ASSERT_NEAR(out.at(0, x, y), want, 2e-4)
                            << backend << " " << to_string(q) << "-bit r=" << radius << " z " << z << " at " << x
                            << "," << y;
                    }
            }
    }
}

// Two exact depths: a receiver on the nearer one (a blocker's own depth) is
// lit, one between them sees the far share, one behind both is dark but for
// the looseness the bias gives the bound right behind the far depth (the
// reference says how much: 0.072 at 0.01 behind, 1.7e-3 at 0.05).
PN_BACKEND_TEST(MsmTest, TwoDepthsAndAReceiverAtTheBlocker)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (Quantization q : {Quantization::None, Quantization::Bits32}) {
        Image depth(16, 16, 1);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) depth.at(0, x, y) = x < 6 ? 0.25f : 0.75f;  // 6 / 16 blockers
        const MsmTable table = msm_table_for(ctx, depth, q);
        const float alpha = default_moment_bias(q);
        const Moments4 b = testing::biased(testing::moments_of({{0.25, 6}, {0.75, 10}}), alpha);
        // Whole-map windows: 37.5% at 0.25, 62.5% at 0.75.
        struct Case {
            float z, expect, tolerance;
        };
        for (Case c : {Case{0.25f, 1.0f, 1e-3f}, Case{0.5f, 0.625f, 2e-3f}, Case{0.7499f, 0.625f, 2e-3f},
                       Case{0.76f, 0.072f, 2e-3f}, Case{0.8f, 0.0017f, 2e-3f}, Case{0.95f, 0.0f, 1e-3f}}) {
            const Image out = msm(ctx, table, testing::receivers_at_depth(16, 16, c.z), MsmOptions{20, {}, {}});
            expect_visibility(out, backend);
            const double ref = 1.0 - testing::msm_bound(b, c.z - default_depth_bias(q)).intensity;
            for (int i = 0; i < 256; ++i) {
                ASSERT_NEAR(out.at(0, i % 16, i / 16), ref, c.tolerance)
                    << backend << " " << to_string(q) << "-bit z " << c.z;
                ASSERT_NEAR(out.at(0, i % 16, i / 16), c.expect, c.tolerance + 1e-3)
                    << backend << " " << to_string(q) << "-bit z " << c.z;
            }
        }
    }
}

// Anything: random depths (continuous, clustered, 0/1-heavy), receivers at
// any depth including outside [0, 1], odd sizes, every lane tail: never NaN
// or infinity, always in [0, 1].
PN_BACKEND_TEST(MsmTest, NeverNaNOnAnything)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    // This backend's strip shapes: widths 1, N - 1, N, N + 1 and 3N + 1 for its lane count N.
    std::vector<std::pair<int, int>> sizes{{1, 1}, {7, 3}, {33, 17}};
    const int lanes = testing::backend_lanes(backend);
    for (int w : {lanes - 1, lanes, lanes + 1, 3 * lanes + 1})
        if (w > 1) sizes.push_back({w, 3});
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), wide(-0.5f, 1.5f);
    for (auto [w, h] : sizes)
        for (int kind = 0; kind < 4; ++kind) {
            Image depth(w, h, 1);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const float u = unit(rng);
                    depth.at(0, x, y) = kind == 0 ? u : kind == 1 ? std::round(u * 3) / 3 : kind == 2 ? float(u > 0.5f)
                                                                                                   : 0.4f + 1e-4f * u;
                }
            Image rx = testing::receivers_on_texels(w, h, w, h, 0.0f, 1.0f, rng());
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) rx.at(2, x, y) = rng() % 3 ? depth.at(0, x, y) : wide(rng);
            for (Quantization q : {Quantization::None, Quantization::Bits16, Quantization::Bits32}) {
                const MsmTable table = msm_table_for(ctx, depth, q);
                for (int radius : {0, 5})
                    for (float alpha : {0.0f, 6e-5f, 0.5f})
                        expect_visibility(msm(ctx, table, rx, MsmOptions{radius, alpha, 0.0f}),
                                          backend + " " + std::to_string(w) + "x" + std::to_string(h));
            }
        }
}

// ---- the overlap case ------------------------------------------------------------

// Two occluders, half the window each at depths 0.3 and 0.5, the receiver
// behind both (truth: 0). VSM's bound leaks var / (var + d^2); MSM's far less
// (what it does leak right behind 0.5 is the moment bias's looseness).
PN_BACKEND_TEST(MsmTest, LeaksLessThanVsmBehindTwoOccluders)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image depth(16, 16, 1);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) depth.at(0, x, y) = (x + y) % 2 ? 0.3f : 0.5f;
    const MsmTable msm_table = build_msm_table(ctx, depth);
    const MomentTable vsm_table = build_moment_table(ctx, depth);
    for (float z : {0.55f, 0.6f, 0.8f}) {
        const Image rx = testing::receivers_at_depth(16, 16, z);
        const Image m = msm(ctx, msm_table, rx, MsmOptions{3, {}, {}});
        const Image v = vsm(ctx, vsm_table, rx, VsmOptions{3});
        const float mv = m.at(0, 8, 8), vv = v.at(0, 8, 8);
        std::printf("[ overlap ] %s receiver %.2f behind occluders at 0.3 and 0.5: leak VSM %.4f, MSM %.6f\n",
                    backend.c_str(), z, vv, mv);
        EXPECT_GT(vv, 0.05f);
        EXPECT_LT(mv, 0.1f * vv);
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, MsmTest, ::testing::ValuesIn(backend_names()), backend_test_name);

// ---- the bias, measured ------------------------------------------------------------

// The smallest alpha that keeps the variance of every one-depth window of the
// 16-bit quantization positive (decoded from its exact table, in double), and
// what the default leaves of it.
TEST(MsmBias, SixteenBitDefaultCoversTheWorstOneDepthWindow)
{
    Context ctx(ContextOptions{Backend::Scalar, {}});
    Image depth(256, 256, 1);
    for (int i = 0; i < 65536; ++i) depth.at(0, i % 256, i / 256) = float(i) / 65535.0f;
    const MsmTable table = build_msm_table(ctx, depth, Quantization::Bits16);
    double needed = 0.0, worst_variance = 0.0;
    for (int i = 0; i < 65536; ++i) {
        const Moments4 b = testing::table_moments(table, i % 256, i % 256 + 1, i / 256, i / 256 + 1);
        const double variance = b[2] - b[1] * b[1];
        worst_variance = std::max(worst_variance, std::abs(variance));
        // The biased variance (1 - a) var + a (1/2 - b1^2 ...) is linear in a: solve for > 0.
        for (double alpha = needed; alpha < 1e-3; alpha += 1e-6) {
            const Moments4 c = testing::biased(b, alpha);
            if (c[2] - c[1] * c[1] > 0.0) break;
            needed = alpha + 1e-6;
        }
    }
    std::printf("[ msm bias ] 16-bit one-depth windows: worst |variance| %.3g, alpha needed %.2g, default %.2g\n",
                worst_variance, needed, double(kMsmMomentBias16));
    EXPECT_LT(needed, kMsmMomentBias16 / 2.0);
}

}  // namespace
}  // namespace penumbra
