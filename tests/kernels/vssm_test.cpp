// VSSM (kernels/vssm.h) against a hand-computed two-depth case and against a
// brute-force reference in double (the search box's texels; area-weighted
// texel sums for the fractional filter window), on every backend; its failure
// modes; its light-size checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <string>

#include "penumbra/chebyshev.h"
#include "penumbra/error.h"
#include "support/backends.h"
#include "support/errors.h"
#include "support/maps.h"
#include "support/visibility.h"
#include "support/vsm_reference.h"

namespace penumbra {
namespace {

using namespace testing;  // the references and checks of tests/support

// ---- the brute-force reference ------------------------------------------------

// Window moments over integer and fractional windows and the Chebyshev bound,
// in double, come from support/vsm_reference.h (covered_moments,
// chebyshev_upper_bound).

// Offsets added to the reference's intermediates, to measure how sensitive the
// answer is to the kernel's float rounding of them (see vssm_expected).
struct Slack {
    double search_mean = 0, search_var = 0, filter_mean = 0, filter_var = 0, half = 0, shift = 0;
};

struct VssmTrace {
    double value;
    double z_occ;       // the blocker estimate (before its floor)
    bool lit;           // no blocker found
    double filter_half; // in texels, x axis
};

// vssm() step by step (the header comment of kernels/vssm.h), in double.
VssmTrace vssm_reference(const Image& depth, Precision precision, const VssmOptions& o, double u, double v, double z,
                         const Slack& s = {})
{
    const double w = depth.width(), h = depth.height();
    const double max_radius = precision == Precision::Exact ? kExactMaxRadius - 1 : std::max(w, h);
    const double cx = std::clamp(u, 0.0, 1.0) * w + s.shift, cy = std::clamp(v, 0.0, 1.0) * h + s.shift;
    auto window = [&](double hx, double hy) {
        return covered_moments(depth, std::clamp(cx - hx, 0.0, w), std::clamp(cx + hx, 0.0, w),
                               std::clamp(cy - hy, 0.0, h), std::clamp(cy + hy, 0.0, h));
    };
    const double L = o.light_size;
    // The search box: the receiver's texel grown by floor(max(L W / 2, 1/2))
    // texels per axis (the half-width in float, as the kernel's geometry), clipped.
    const auto radius = [&](int texels) { return std::floor(std::max(o.light_size * 0.5f * float(texels), 0.5f)); };
    const double tx = std::clamp(std::floor(std::clamp(u, 0.0, 1.0) * w), 0.0, w - 1);
    const double ty = std::clamp(std::floor(std::clamp(v, 0.0, 1.0) * h), 0.0, h - 1);
    const double rx = radius(depth.width()), ry = radius(depth.height());
    Moments search = covered_moments(depth, std::max(tx - rx, 0.0), std::min(tx + rx + 1, w), std::max(ty - ry, 0.0),
                                     std::min(ty + ry + 1, h));
    search.mean += s.search_mean;
    const double p = chebyshev_upper_bound(search.mean_sq - search.mean * search.mean + s.search_var, z - search.mean,
                                 o.min_variance);
    const double blocked = 1.0 - p;
    const double z_occ = (search.mean - p * z) / std::max(blocked, 1e-4);
    const double occluder = std::max(z_occ, z * 1e-4);
    const double penumbra = L * (z - occluder) / occluder;
    const double hx = std::clamp(penumbra * 0.5 * w, 0.5, max_radius + 0.5) + s.half;
    const double hy = std::clamp(penumbra * 0.5 * h, 0.5, max_radius + 0.5) + s.half;
    Moments filter = window(hx, hy);
    filter.mean += s.filter_mean;
    const double pf = chebyshev_upper_bound(filter.mean_sq - filter.mean * filter.mean + s.filter_var, z - filter.mean,
                                  o.min_variance);
    const double visibility = std::clamp((pf - o.bleed) / (1.0 - o.bleed), 0.0, 1.0);
    return {blocked < 1e-4 ? 1.0 : visibility, z_occ, blocked < 1e-4, hx};
}

// The reference and a tolerance from its sensitivity. The kernel forms the
// window means from float sums (the nine weighted rectangles of a fractional
// window: |dE| <= ~1e-6 relative to depths <= 1, |dvar| <= 2e-6) and the
// filter window's edges in float (texel coordinates below 2^7: <= 1e-5;
// the search box's edges are integers). The tolerance
// is 1e-5 plus, for each of those six intermediates, the largest change of the
// reference when that one is moved by its bound either way (first order in
// each). The chain is steep where z_occ is small (d half / d z_occ =
// -L z W / 2 / z_occ^2) and discontinuous at the no-blocker threshold; there
// the tolerance grows by exactly as much as the answer is ill-determined.
struct Expected {
    VssmTrace ref;
    double tolerance;
};

Expected vssm_expected(const Image& depth, Precision precision, const VssmOptions& o, double u, double v, double z)
{
    const VssmTrace ref = vssm_reference(depth, precision, o, u, v, z);
    double tolerance = 1e-5;
    for (int i = 0; i < 6; ++i) {
        double worst = 0.0;
        for (double sign : {-1.0, 1.0}) {
            Slack s;
            double* field[] = {&s.search_mean, &s.search_var, &s.filter_mean, &s.filter_var, &s.half, &s.shift};
            const double bound[] = {1e-6, 2e-6, 1e-6, 2e-6, 1e-5, 1e-5};
            *field[i] = sign * bound[i];
            worst = std::max(worst, std::abs(vssm_reference(depth, precision, o, u, v, z, s).value - ref.value));
        }
        tolerance += worst;
    }
    return {ref, tolerance};
}

// One receiver (u, v, z) repeated over a strip-shaped image (every lane of every
// ISA computes it, tails included).
Image repeated_receiver(float u, float v, float z, int width = 37)
{
    Image rx(width, 2, 3);
    rx.fill(0, u);
    rx.fill(1, v);
    rx.fill(2, z);
    return rx;
}

// Every receiver of `rx` against the reference; returns the largest error.
double check_against_reference(Context& ctx, const Image& depth, Precision precision, const Image& rx,
                               const VssmOptions& o, const std::string& what)
{
    const MomentTable table = build_moment_table(ctx, depth, 2, precision);
    const Image out = vssm(ctx, table, rx, o);
    expect_visibility(out);
    double worst = 0.0;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            const Expected e = vssm_expected(depth, precision, o, rx.at(0, x, y), rx.at(1, x, y), rx.at(2, x, y));
            const double got = out.at(0, x, y);
            EXPECT_NEAR(got, e.ref.value, e.tolerance)
                << what << " " << to_string(precision) << " L=" << o.light_size << " min_variance=" << o.min_variance
                << " bleed=" << o.bleed << " receiver (" << x << "," << y << ") u=" << rx.at(0, x, y)
                << " v=" << rx.at(1, x, y) << " z=" << rx.at(2, x, y) << " z_occ=" << e.ref.z_occ
                << " filter half-width=" << e.ref.filter_half;
            if (std::abs(got - e.ref.value) > e.tolerance) return INFINITY;
            worst = std::max(worst, std::abs(got - e.ref.value));
        }
    return worst;
}

class VssmTest : public ::testing::TestWithParam<std::string> {};

// ---- the hand-computed case -----------------------------------------------------

// A 64x64 map at depth 0.75 with a 17x17 checkerboard of blockers at 0.25 over
// texels [24, 41)^2 (145 blockers, the corners included); receiver at the
// centre, u = v = 0.5 (texel 32, continuous position 32, 32), z = 0.75;
// light_size L = 0.25.
//  Search: radius floor(L W / 2) = floor(0.25 * 64 / 2) = 8 texels around
//    texel 32: the box [24, 41)^2, exactly the checkerboard; blockers q =
//    145/289. A two-point distribution (0.25 with weight q, 0.75) seen from
//    its upper point attains the bound: mean = 0.75 - q/2, var = q (1 - q)/4,
//    d = q/2, p = var / (var + d^2) = 1 - q, and z_occ = (mean - p z) / (1 - p)
//    = (q/4) / q = 0.25, the blockers' depth, for any q (in double: to ~1e-16).
//  Penumbra: w = L (z - z_occ) / z_occ = 0.25 * 0.5 / 0.25 = 0.5 texture units;
//    half-width w W / 2 = 16 texels: window [16, 48)^2 = 1024 texels, 145 blockers.
//  Filter: the same two-point argument, p = 879/1024, the fraction of lit texels.
// The filter's sums are dyadic (exact in a float table); the search's mean is
// not (289 texels), which moves z_occ by about 1e-7 and the filter's
// half-width by about 1e-5 texels: 1e-4 is slack. An exact table's sums are
// exact; its values' rounding (2^-33) is far below that.
constexpr double kCheckerboardVisibility = 879.0 / 1024.0;
Image checkerboard_map()
{
    Image depth(64, 64, 1);
    depth.fill(0, 0.75f);
    for (int y = 24; y < 41; ++y)
        for (int x = 24; x < 41; ++x)
            if ((x + y) % 2 == 0) depth.at(0, x, y) = 0.25f;
    return depth;
}

PN_BACKEND_TEST(VssmTest, HandComputedCheckerboard)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image depth = checkerboard_map();
    const Image rx = repeated_receiver(0.5f, 0.5f, 0.75f);
    const VssmOptions o{0.25f, kDefaultMinVariance, 0.0f};
    // The reference agrees with the hand arithmetic.
    const VssmTrace by_hand = vssm_reference(depth, Precision::Float, o, 0.5, 0.5, 0.75);
    ASSERT_NEAR(by_hand.z_occ, 0.25, 1e-14);
    ASSERT_NEAR(by_hand.filter_half, 16.0, 1e-12);
    ASSERT_NEAR(by_hand.value, kCheckerboardVisibility, 1e-12);

    for (Precision precision : {Precision::Float, Precision::Exact}) {
        const MomentTable table = build_moment_table(ctx, depth, 2, precision);
        const Image out = vssm(ctx, table, rx, o);
        for (int y = 0; y < rx.height(); ++y)
            for (int x = 0; x < rx.width(); ++x)
                ASSERT_NEAR(out.at(0, x, y), kCheckerboardVisibility, 1e-4) << to_string(precision);
        const Expected e = vssm_expected(depth, precision, o, 0.5, 0.5, 0.75);
        EXPECT_NEAR(out.at(0, 0, 0), e.ref.value, e.tolerance) << to_string(precision);
        std::cout << "[ vssm ] " << backend << " checkerboard " << to_string(precision) << ": " << out.at(0, 0, 0)
                  << " (879/1024 - got = " << kCheckerboardVisibility - out.at(0, 0, 0) << ", reference "
                  << e.ref.value << ")\n";
    }
}

// ---- fractional windows against brute-force weighted sums ------------------------

PN_BACKEND_TEST(VssmTest, FractionalWindowsMatchWeightedBruteForce)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image rx = scattered_receivers(31, 17, -0.05f, 1.05f, 0.0f, 1.0f, 17);
    double worst = 0.0;
    for (Precision precision : {Precision::Float, Precision::Exact}) {
        const Image depth = testing::random_depth(29, 23, 5, precision == Precision::Float);
        // Search radii 0, 1, 5 texels in x (0, 1, 4 in y); filter windows fractional.
        for (float light : {0.05f, 0.11f, 0.37f})
            for (VssmOptions o : {VssmOptions{0, kDefaultMinVariance, 0.0f}, VssmOptions{0, 1e-3f, 0.3f}}) {
                o.light_size = light;
                worst = std::max(worst, check_against_reference(ctx, depth, precision, rx, o, "fractional"));
            }
    }
    std::cout << "[ vssm ] " << backend << " fractional windows: max |got - reference| " << worst << "\n";
}

// The tolerance must not make the test vacuous: most receivers are well conditioned.
TEST(VssmReference, FractionalCaseIsMostlyWellConditioned)
{
    const Image depth = testing::random_depth(29, 23, 5, true);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> uv(-0.05f, 1.05f), z(0.0f, 1.0f);
    int loose = 0, total = 0;
    for (int i = 0; i < 527; ++i) {
        const float u = uv(rng), v = uv(rng), zz = z(rng);
        const Expected e = vssm_expected(depth, Precision::Float, {0.11f, kDefaultMinVariance, 0.0f}, u, v, zz);
        loose += e.tolerance > 1e-3;
        ++total;
    }
    EXPECT_LT(loose, total / 20) << loose << " of " << total << " receivers have a tolerance above 1e-3";
}

// ---- failure modes, every backend --------------------------------------------------

PN_BACKEND_TEST(VssmTest, ConstantMapsAndReceiversInFront)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (Precision precision : {Precision::Float, Precision::Exact}) {
        for (float level : {0.25f, 0.3f, 0.5f, 0.75f, 1.0f}) {
            Image depth(21, 9, 1);
            depth.fill(0, level);
            const MomentTable table = build_moment_table(ctx, depth, 2, precision);
            for (float light : {0.05f, 0.3f, 3.0f}) {
                const VssmOptions o{light, kDefaultMinVariance, 0.0f};
                const std::string where = to_string(precision) + " depth " + std::to_string(level);
                // In front and at the depth: p = 1 (or 1 - 7e-7 at a quantized 0.75), no blocker: exactly 1.
                for (float z : {0.0f, level - 0.1f, level}) {
                    const Image out = vssm(ctx, table, testing::receivers_at_depth(21, 9, z), o);
                    for (int i = 0; i < 21 * 9; ++i) ASSERT_EQ(out.at(0, i % 21, i / 21), 1.0f) << where << " z=" << z;
                }
                if (level < 1.0f) {  // behind by 0.1: p = 2e-5 / 0.01002 = 0.002 in both windows
                    const Image out = vssm(ctx, table, testing::receivers_at_depth(21, 9, level + 0.1f), o);
                    expect_visibility(out);
                    for (int i = 0; i < 21 * 9; ++i) ASSERT_LT(out.at(0, i % 21, i / 21), 0.01f) << where;
                }
            }
        }
        // No blockers: every depth >= 0.5, every receiver in front: exactly 1.
        Image far = testing::random_depth(33, 7, 9);
        for (int y = 0; y < 7; ++y)
            for (int x = 0; x < 33; ++x) far.at(0, x, y) = 0.5f + 0.5f * far.at(0, x, y);
        const MomentTable table = build_moment_table(ctx, far, 2, precision);
        const Image rx = testing::receivers_on_texels(33, 7, 33, 7, 0.0f, 0.5f, 4);
        const Image out = vssm(ctx, table, rx, {0.2f, kDefaultMinVariance, 0.0f});
        for (int i = 0; i < 33 * 7; ++i) ASSERT_EQ(out.at(0, i % 33, i / 33), 1.0f) << to_string(precision);
    }
}

PN_BACKEND_TEST(VssmTest, ZeroVarianceWithoutFloorIsNeverNaN)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (Precision precision : {Precision::Float, Precision::Exact}) {
        for (float level : {0.0f, 0.5f}) {
            Image depth(13, 11, 1);
            depth.fill(0, level);
            const MomentTable table = build_moment_table(ctx, depth, 2, precision);
            // level 0, z = 1e-30: var = 0 and d^2 underflows; p = 0, z_occ = 0 -> floored
            // to 1e-4 z, the widest filter, p = 0 again.
            for (float z : {level, level + 1e-30f, level + 0.1f}) {
                const Image out = vssm(ctx, table, testing::receivers_at_depth(13, 11, z), {0.1f, 0.0f, 0.0f});
                expect_visibility(out);
                const float expected = z <= level ? 1.0f : 0.0f;
                for (int i = 0; i < 13 * 11; ++i)
                    ASSERT_NEAR(out.at(0, i % 13, i / 13), expected, 1e-4) << to_string(precision) << " z=" << z;
            }
        }
    }
}

PN_BACKEND_TEST(VssmTest, DepthsExactlyZeroAndOneAndHugeLights)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image depth = testing::binary_depth(23, 11, 3, 4);
    for (Precision precision : {Precision::Float, Precision::Exact}) {
        // 10 on a 23-wide map: a search half-width of 115 texels, far beyond the
        // map yet inside the exact limit (126).
        for (float light : {0.1f, 0.5f, 10.0f})
            for (float z : {0.0f, 0.5f, 1.0f}) {
                const Image rx = testing::receivers_at_depth(23, 11, z);
                check_against_reference(ctx, depth, precision, rx, {light, kDefaultMinVariance, 0.0f}, "0/1 map");
                if (z == 0.0f) {
                    const Image out = vssm(ctx, build_moment_table(ctx, depth, 2, precision), rx, {light});
                    for (int i = 0; i < 23 * 11; ++i) ASSERT_EQ(out.at(0, i % 23, i / 23), 1.0f);
                }
            }
    }
    // Float tables take any light size: windows of the whole map.
    const Image rx = testing::receivers_on_texels(23, 11, 23, 11, 0.0f, 1.0f, 8);
    check_against_reference(ctx, depth, Precision::Float, rx, {1000.0f, kDefaultMinVariance, 0.0f}, "huge light");
}

// The blocker estimate z_occ = (mean - p z) / (1 - p) goes negative when the
// receiver sits just behind the mean of a mostly-far window: 32x32 at 1.0 with
// a blocker at 0.5 on every 4th texel of every 4th row; search box [8, 25)^2
// (L = 0.5: radius 8 around texel 16), 25 blockers of 289 (q = 0.0865):
// mean = 1 - q/2 = 0.9567, var = q (1 - q) / 4 = 0.0198; z = 0.96875 + 0.005
// = mean + 0.0170: p = 0.0198 / (0.0198 + 2.9e-4) = 0.9856,
// z_occ = (mean - p z) / (1 - p) = -0.21. The kernel floors it at 1e-4 z:
// the widest filter (clamped to the map), the Chebyshev bound over it.
PN_BACKEND_TEST(VssmTest, NegativeBlockerEstimateGivesWidestFilter)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image depth(32, 32, 1);
    depth.fill(0, 1.0f);
    for (int y = 0; y < 32; y += 4)
        for (int x = 0; x < 32; x += 4) depth.at(0, x, y) = 0.5f;
    const float z = 0.96875f + 0.005f;
    const VssmOptions o{0.5f, kDefaultMinVariance, 0.0f};
    for (Precision precision : {Precision::Float, Precision::Exact}) {
        const VssmTrace ref = vssm_reference(depth, precision, o, 0.5, 0.5, z);
        ASSERT_LT(ref.z_occ, 0.0) << "the case must produce a negative estimate";
        ASSERT_GE(ref.filter_half, 32.0) << "the widest filter covers the map";
        const Image rx = repeated_receiver(0.5f, 0.5f, z);
        check_against_reference(ctx, depth, precision, rx, o, "negative z_occ");
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, VssmTest, ::testing::ValuesIn(backend_names()), backend_test_name);

// ---- light-size checks ---------------------------------------------------------

TEST(VssmErrors, RejectsBadLightSizes)
{
    BothPrecisions setup(64, 64, 1);
    Context& ctx = setup.ctx;
    const MomentTable &exact = setup.exact, &floats = setup.floats;
    const Image& rx = setup.rx;
    auto rejects = [&](const MomentTable& table, float light, const std::string& needle) {
        expect_error([&] { vssm(ctx, table, rx, {light}); }, ErrorCategory::InvalidArgument, "vssm", needle);
    };
    for (const MomentTable* t : {&exact, &floats})
        for (float bad : {0.0f, -0.1f, -INFINITY, INFINITY, NAN}) rejects(*t, bad, "light-size must be > 0");
    // Exact tables: the search half-width L * 64 / 2 must stay <= 126 texels
    // (L = 8: half-width 256, a 512-texel search).
    rejects(exact, 8.0f, "light-size 8.000000 needs a blocker search of 512 texels");
    rejects(exact, 3.95f, "more than an exact table keeps exact");
    EXPECT_NO_THROW(vssm(ctx, exact, rx, {126.0f / 32.0f}));
    EXPECT_NO_THROW(vssm(ctx, floats, rx, {8.0f}));
    EXPECT_NO_THROW(vssm(ctx, exact, rx, {1e-6f}));
}

}  // namespace
}  // namespace penumbra
