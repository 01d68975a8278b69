// PCSS (kernels/pcss.h) and Burley's bias-cone soft shadows (kernels/burley.h)
// on every backend: hand-computed cases (one blocker at a known depth: the
// blocker estimate, the width, the result), the float64 reference of
// tests/support/soft_pcf_reference.h at odd sizes and with each bias mode,
// and the failure modes the issue names. Tolerance: 1e-6 against the
// reference on receivers whose every tap is at least 1e-4 (depth, or texels
// from a texel edge) from a decision; float32 may decide the others either
// way, and at most 5% of them are left out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "host/backend/backend.h"
#include "penumbra/error.h"
#include "penumbra/soft_pcf.h"
#include "support/backends.h"
#include "support/maps.h"
#include "support/pcf_shade.h"
#include "support/soft_pcf_reference.h"

namespace penumbra {
namespace {

using detail::KernelId;
using testing::backend_names;
using testing::backend_test_name;
using testing::BurleySettings;
using testing::PcssSettings;
using testing::RefBias;
using testing::RefBiasMode;

template <KernelId K>
Image shade(Context& context, const Image& map, const Image& receivers, const SoftPcfParams& p)
{
    return testing::pcf_shade_on<K>(context, map, receivers, p);
}

SoftPcfParams pcss_params(const PcssSettings& s, const RefBias& b)
{
    SoftPcfParams p{};
    p.bias.mode = b.mode == RefBiasMode::Constant ? PN_BIAS_CONSTANT
                  : b.mode == RefBiasMode::Slope  ? PN_BIAS_SLOPE
                                                  : PN_BIAS_RECEIVER_PLANE;
    p.bias.depth_bias = float(b.constant);
    p.bias.slope_scale = float(b.slope_scale);
    p.bias.low = float(b.low);
    p.bias.high = float(b.high);
    p.blocker_samples = s.blocker_samples;
    p.filter_samples = s.filter_samples;
    p.light_size = float(s.light_size);
    return p;
}

SoftPcfParams burley_params(const BurleySettings& s, const RefBias& b)
{
    SoftPcfParams p = pcss_params(PcssSettings{0, s.blocker_samples, s.filter_samples}, b);
    p.min_radius = float(s.min_radius);
    p.max_radius = float(s.max_radius);
    p.bias_slope = float(s.bias_slope);
    p.bias_slope_per_depth = float(s.bias_slope_per_depth);
    p.falloff = float(s.falloff);
    return p;
}

RefBias constant_bias(double beta) { return RefBias{RefBiasMode::Constant, beta}; }

// The 200x9 map of the hand cases: a blocker at depth 0.4 over columns
// x < 100, the receiver's ground at 0.8 elsewhere; the receiver 0.3 texels
// right of the blocker's edge, mid-row, at z = 0.8.
Image half_plane_map()
{
    Image map(200, 9, 1);
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 200; ++x) map.at(0, x, y) = x < 100 ? 0.4f : 0.8f;
    return map;
}

Image one_receiver(double u, double v, double z)
{
    Image rx(1, 1, 3);
    rx.at(0, 0, 0) = float(u);
    rx.at(1, 0, 0) = float(v);
    rx.at(2, 0, 0) = float(z);
    return rx;
}

const double kEdgeU = 100.3 / 200, kMidV = 4.5 / 9;

using SoftPcf = ::testing::TestWithParam<std::string>;

// PCSS, L = 0.02 on a 200-texel map: both discs have radius 0.01 = 2 texels
// across u, 16 taps each. A tap blocks when 2 dx < -0.3 (dx its unit-disc
// offset, sqrt(phi_2(k)) cos(2 pi k / 16)): taps 5 .. 11, all at depth 0.4,
// so z_b = 0.4, w = 0.02 (0.8 - 0.4) / 0.4 = 0.02 and the filter's radius is
// 0.01 again: 9 of 16 taps lit.
PN_BACKEND_TEST(SoftPcf, PcssOneBlockerByHand)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const PcssSettings s{0.02, 16, 16};
    const testing::SoftLookup ref =
        testing::pcss_lookup(half_plane_map(), {kEdgeU, kMidV, 0.8}, constant_bias(1e-3), s);
    EXPECT_TRUE(ref.found);
    EXPECT_DOUBLE_EQ(ref.blocker_depth, double(0.4f));
    EXPECT_NEAR(ref.filter_radius, 0.01, 1e-7);
    EXPECT_DOUBLE_EQ(ref.visibility, 9.0 / 16);
    const Image got = shade<KernelId::pcss>(ctx, half_plane_map(), one_receiver(kEdgeU, kMidV, 0.8),
                                            pcss_params(s, constant_bias(1e-3)));
    EXPECT_FLOAT_EQ(got.at(0, 0, 0), 9.0f / 16);
}

// Burley, R = 0.01 (2 texels), min radius 0.0025: every blocking tap sits at
// 0.4, so z_b = 0.4 whatever the weights; the filter radius is
// 0.0025 + 0.0075 (1 - 0.4 / 0.8) = 0.00625 (1.25 texels) and a tap blocks
// when 1.25 dx < -0.3: taps 5 .. 11 again, 9/16 lit. The cone (at most 0.02)
// keeps the ground at 0.8 lit. With falloff 0.8 the opacity is
// 1 - 0.4 / 0.8 = 1/2: visibility 1 - 7/32 = 25/32.
PN_BACKEND_TEST(SoftPcf, BurleyOneBlockerByHand)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    BurleySettings s{0.0025, 0.01, 2.0, 0.0, 16, 16};
    const testing::SoftLookup ref =
        testing::burley_lookup(half_plane_map(), {kEdgeU, kMidV, 0.8}, constant_bias(0), s);
    EXPECT_TRUE(ref.found);
    EXPECT_DOUBLE_EQ(ref.blocker_depth, double(0.4f));
    EXPECT_NEAR(ref.filter_radius, 0.00625, 1e-7);
    EXPECT_DOUBLE_EQ(ref.visibility, 9.0 / 16);
    const Image rx = one_receiver(kEdgeU, kMidV, 0.8);
    EXPECT_FLOAT_EQ(shade<KernelId::burley>(ctx, half_plane_map(), rx, burley_params(s, constant_bias(0))).at(0, 0, 0),
                    9.0f / 16);
    s.falloff = 0.8;
    // (0.8 and 0.4 are read as floats: the opacity is 1/2 to 1e-8.)
    EXPECT_NEAR(testing::burley_lookup(half_plane_map(), {kEdgeU, kMidV, 0.8}, constant_bias(0), s).visibility,
                25.0 / 32, 1e-7);
    EXPECT_NEAR(shade<KernelId::burley>(ctx, half_plane_map(), rx, burley_params(s, constant_bias(0))).at(0, 0, 0),
                25.0f / 32, 1e-6);
}

// Clamp to edge, by hand: on a 20x20 map whose row 0 and column 0 hold a
// blocker at 0.4 (the ground at 0.8), a receiver at the centre of texel
// (0, 0) reads the blocker with every tap left of x = 1 or above y = 1, taps
// outside the map included (they read the edge texels, as a GPU sampler's
// clamp-to-edge does; a border of "lit" or a wrap would give other counts).
// Every blocking tap is at 0.4, so PCSS's z_b = 0.4, w = L and both discs
// have radius L / 2; Burley's filter radius is (min + max) / 2. The expected
// visibility is the count of filter taps at x >= 1 and y >= 1, from the
// pattern in double (std::cos), each tap at least 1e-3 texels from an edge.
Image corner_blocker_map()
{
    Image map(20, 20, 1);
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x) map.at(0, x, y) = x == 0 || y == 0 ? 0.4f : 0.8f;
    return map;
}

double lit_share_at_corner(int taps, double radius_texels)
{
    int lit = 0;
    for (const testing::UnitDiscTap& t : testing::hammersley_disc(taps, true)) {
        const double x = 0.5 + t.dx * radius_texels, y = 0.5 + t.dy * radius_texels;
        EXPECT_GT(std::min(std::abs(x - 1), std::abs(y - 1)), 1e-3) << "a tap on an edge: pick another radius";
        lit += x >= 1 && y >= 1;
    }
    return double(lit) / taps;
}

PN_BACKEND_TEST(SoftPcf, TapsOutsideTheMapReadTheEdgeTexels)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image rx = one_receiver(0.5 / 20, 0.5 / 20, 0.8);
    const PcssSettings pcss{0.23, 32, 48};                  // both radii 0.115 = 2.3 texels
    const BurleySettings burley{0.05, 0.17, 2.0, 0.0, 32, 48};  // filter radius 0.11 = 2.2 texels
    const double pcss_lit = lit_share_at_corner(48, 2.3), burley_lit = lit_share_at_corner(48, 2.2);
    ASSERT_GT(pcss_lit, 0.1);
    ASSERT_LT(pcss_lit, 0.5);
    EXPECT_FLOAT_EQ(shade<KernelId::pcss>(ctx, corner_blocker_map(), rx, pcss_params(pcss, constant_bias(1e-3)))
                        .at(0, 0, 0),
                    float(pcss_lit));
    EXPECT_FLOAT_EQ(shade<KernelId::burley>(ctx, corner_blocker_map(), rx, burley_params(burley, constant_bias(1e-3)))
                        .at(0, 0, 0),
                    float(burley_lit));
}

// Random receivers (u, v off the texel grid, z across the map's depths) with
// derivative planes for the slope and receiver-plane modes.
Image random_receivers(int width, int height, std::uint32_t seed)
{
    Image rx(width, height, 6);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), slope(-0.5f, 0.5f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            rx.at(0, x, y) = unit(rng) * 1.1f - 0.05f;  // a few outside [0, 1]: clamped
            rx.at(1, x, y) = unit(rng) * 1.1f - 0.05f;
            rx.at(2, x, y) = 0.15f + 0.85f * unit(rng);
            rx.at(3, x, y) = slope(rng);
            rx.at(4, x, y) = slope(rng);
            rx.at(5, x, y) = unit(rng) < 0.8f ? 1.0f : 0.0f;
        }
    return rx;
}

// Receivers compared with the reference, and left out for a small margin.
struct Coverage {
    int compared = 0, skipped = 0;
};

// Kernel against reference: compared where the reference's margin allows.
template <KernelId K, class Lookup>
void expect_matches_reference(Context& ctx, const Image& map, const Image& rx, const SoftPcfParams& p,
                              Lookup&& reference, const std::string& what, Coverage& coverage)
{
    const Image got = shade<K>(ctx, map, rx, p);
    int& compared = coverage.compared;
    int& skipped = coverage.skipped;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            const testing::SoftLookup ref = reference(testing::ref_receiver(rx, x, y));
            if (ref.margin < 1e-4) {
                ++skipped;
                continue;
            }
            ++compared;
            EXPECT_NEAR(got.at(0, x, y), ref.visibility, 1e-6) << what << " receiver " << x << ", " << y;
        }
}

std::vector<RefBias> bias_modes()
{
    return {constant_bias(2e-3), RefBias{RefBiasMode::Slope, 1e-3, 1.0, 1e-4, 0.05},
            RefBias{RefBiasMode::ReceiverPlane, 1e-3, 1.0, 1e-4, 0.05}};
}

PN_BACKEND_TEST(SoftPcf, BothAgreeWithTheFloat64ReferenceAtOddSizes)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int maps[][2] = {{9, 5}, {31, 17}};
    const int grids[][2] = {{1, 1}, {7, 3}, {15, 2}, {17, 2}, {33, 1}, {49, 1}};
    const PcssSettings pcss{0.15, 16, 24};
    const BurleySettings burley{0.01, 0.12, 2.0, 0.5, 16, 24};
    // A world cone (world_cone's form): the slope grows with the receiver's depth.
    const BurleySettings burley_world{0.01, 0.12, 0.25, 0.5, 16, 24, 3.5};
    std::uint32_t seed = 1;
    Coverage coverage;
    for (const auto& m : maps)
        for (const auto& g : grids)
            for (const RefBias& bias : bias_modes()) {
                const Image map = testing::random_depth(m[0], m[1], seed);
                const Image rx = random_receivers(g[0], g[1], ++seed);
                const std::string what = std::to_string(m[0]) + "x" + std::to_string(m[1]) + " map, " +
                                         std::to_string(g[0]) + "x" + std::to_string(g[1]) + " receivers, bias mode " +
                                         std::to_string(int(bias.mode));
                expect_matches_reference<KernelId::pcss>(
                    ctx, map, rx, pcss_params(pcss, bias),
                    [&](const testing::RefReceiver& r) { return testing::pcss_lookup(map, r, bias, pcss); },
                    "pcss " + what, coverage);
                expect_matches_reference<KernelId::burley>(
                    ctx, map, rx, burley_params(burley, bias),
                    [&](const testing::RefReceiver& r) { return testing::burley_lookup(map, r, bias, burley); },
                    "burley " + what, coverage);
                expect_matches_reference<KernelId::burley>(
                    ctx, map, rx, burley_params(burley_world, bias),
                    [&](const testing::RefReceiver& r) { return testing::burley_lookup(map, r, bias, burley_world); },
                    "burley, world cone, " + what, coverage);
            }
    EXPECT_LE(coverage.skipped, (coverage.compared + coverage.skipped) / 20);
    std::cout << coverage.compared << " receivers compared, " << coverage.skipped << " left out for their margin\n";
}

Image flat_map(int w, int h, float depth)
{
    Image map(w, h, 1);
    map.fill(0, depth);
    return map;
}

PN_BACKEND_TEST(SoftPcf, NoBlockerIsLitAndEveryTapBlockedIsDark)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image rx = testing::receivers_at_depth(13, 7, 0.8f);
    const PcssSettings pcss{0.2, 16, 24};
    const BurleySettings burley{0.01, 0.1, 2.0, 0.0, 16, 24};
    for (const auto& [depth, expected] : {std::pair{0.9f, 1.0f}, std::pair{0.8f, 1.0f}, std::pair{0.3f, 0.0f}}) {
        const Image map = flat_map(13, 7, depth);
        const Image a = shade<KernelId::pcss>(ctx, map, rx, pcss_params(pcss, constant_bias(0)));
        const Image b = shade<KernelId::burley>(ctx, map, rx, burley_params(burley, constant_bias(0)));
        for (int y = 0; y < 7; ++y)
            for (int x = 0; x < 13; ++x) {
                EXPECT_EQ(a.at(0, x, y), expected) << "pcss, map at " << depth;
                EXPECT_EQ(b.at(0, x, y), expected) << "burley, map at " << depth;
            }
    }
}

// Light size 0: every tap reads the receiver's own texel, a hard shadow
// equal to pcf with radius 0 (the window contract) on the same map.
PN_BACKEND_TEST(SoftPcf, PcssWithLightSizeZeroIsPcfRadiusZero)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image map = testing::random_depth(31, 17, 9);
    Image rx = random_receivers(33, 5, 10);
    const Image soft = shade<KernelId::pcss>(ctx, map, rx, pcss_params(PcssSettings{0.0, 16, 24}, constant_bias(1e-3)));
    PcfParams p{};
    p.bias.mode = PN_BIAS_CONSTANT;
    p.bias.depth_bias = 1e-3f;
    p.radius = 0;
    Image hard(rx.width(), rx.height(), 1);
    std::vector<int> bad_rows(std::size_t(rx.height()), 0);
    p.depth = detail::dims_of(map);
    p.receivers = detail::dims_of(rx);
    p.out = detail::dims_of(hard);
    detail::receiver_lookup<KernelId::pcf>(ctx.impl(), map, rx, p, hard, bad_rows.data());
    int shadowed = 0;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            EXPECT_EQ(soft.at(0, x, y), hard.at(0, x, y)) << x << ", " << y;
            shadowed += hard.at(0, x, y) == 0.0f;
        }
    EXPECT_GT(shadowed, 0);
}

// PCSS (L = 0.2) and Burley (R = 0.1) at one receiver, 32/32 taps: the
// reference's steps, after checking that the kernels give its visibility.
std::pair<testing::SoftLookup, testing::SoftLookup> both_at(Context& ctx, const Image& map,
                                                            const testing::RefReceiver& r)
{
    const PcssSettings pcss{0.2, 32, 32};
    const BurleySettings burley{0.005, 0.1, 2.0, 0.0, 32, 32};
    const testing::SoftLookup a = testing::pcss_lookup(map, r, constant_bias(1e-3), pcss);
    const testing::SoftLookup b = testing::burley_lookup(map, r, constant_bias(0), burley);
    const Image rx = one_receiver(r.u, r.v, r.z);
    EXPECT_NEAR(shade<KernelId::pcss>(ctx, map, rx, pcss_params(pcss, constant_bias(1e-3))).at(0, 0, 0),
                a.visibility, 1e-6);
    EXPECT_NEAR(shade<KernelId::burley>(ctx, map, rx, burley_params(burley, constant_bias(0))).at(0, 0, 0),
                b.visibility, 1e-6);
    return {a, b};
}

// A small near occluder (2x2 texels at depth 0.2) at the centre of a large
// far one (0.6 everywhere else), the receiver at 0.8 under the small one.
// PCSS's plain mean is pulled to the far occluder; Burley's centre-weighted
// estimate stays near the small one (section 3.1), so its penumbra is the
// narrower, as the contact asks.
PN_BACKEND_TEST(SoftPcf, SmallNearOccluderInsideALargeFarOne)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image map = flat_map(64, 64, 0.6f);
    for (int y = 31; y <= 32; ++y)
        for (int x = 31; x <= 32; ++x) map.at(0, x, y) = 0.2f;
    const auto [a, b] = both_at(ctx, map, {32.1 / 64, 31.9 / 64, 0.8});
    ASSERT_TRUE(a.found && b.found);
    EXPECT_GT(a.blocker_depth, 0.5);  // mostly the far occluder
    EXPECT_LT(b.blocker_depth, a.blocker_depth - 0.05);
    EXPECT_GT(b.blocker_depth, 0.2);
}

// Two blockers at different depths overlapping the search disc: the estimate
// lies between them, and the kernels follow the reference.
PN_BACKEND_TEST(SoftPcf, OverlappingBlockersAtDifferentDepths)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image map = flat_map(64, 64, 0.8f);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            if (x < 32) map.at(0, x, y) = 0.3f;
            if (y < 30) map.at(0, x, y) = 0.5f;  // the upper one crosses the lower
        }
    const auto [a, b] = both_at(ctx, map, {32.3 / 64, 30.4 / 64, 0.8});
    for (const testing::SoftLookup& s : {a, b}) {
        EXPECT_GT(s.blocker_depth, 0.3);
        EXPECT_LT(s.blocker_depth, 0.5);
        EXPECT_GT(s.visibility, 0.0);
        EXPECT_LT(s.visibility, 1.0);
    }
}

// A steep receiver with zero base bias, the case the cone is for: the map is
// the receiver itself, z = 0.05 + 0.9 u (0.9 depth per texture unit, below
// the cone's slope 2), receivers at the texel centres. A tap rho texels out
// reads a texel at most rho + 1/2 texels nearer the light, 0.9 (rho + 1/2) / W
// in depth, which the cone's 2 rho / W covers for rho >= 1/2 (nearer taps read
// the receiver's own texel): Burley sees no acne. PCSS with the same zero
// bias shadows itself on every receiver whose disc reaches a nearer texel.
PN_BACKEND_TEST(SoftPcf, SteepReceiverWithZeroBaseBiasHasNoAcneOnTheCone)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int W = 64, H = 9;
    Image map(W, H, 1), rx(W, H, 3);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float u = (float(x) + 0.5f) / W;
            map.at(0, x, y) = 0.05f + 0.9f * u;
            rx.at(0, x, y) = u;
            rx.at(1, x, y) = (float(y) + 0.5f) / H;
            rx.at(2, x, y) = map.at(0, x, y);
        }
    const BurleySettings burley{0.01, 0.1, 2.0, 0.0, 32, 32};
    const Image cone = shade<KernelId::burley>(ctx, map, rx, burley_params(burley, constant_bias(0)));
    const Image flat = shade<KernelId::pcss>(ctx, map, rx, pcss_params(PcssSettings{0.2, 32, 32}, constant_bias(0)));
    int acne = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            EXPECT_EQ(cone.at(0, x, y), 1.0f) << x << ", " << y;
            acne += flat.at(0, x, y) < 1.0f;
        }
    // Without the cone: self-shadowing (PCSS then finds its own surface as a
    // blocker just in front, so its penumbra is narrow and the acne mild:
    // a mean of 0.90 here, measured).
    EXPECT_GT(acne, W * H / 2);
}

// The perspective light of the world-cone cases: the reference scenes'
// default camera (60 degrees, near 0.1, far 20).
constexpr double kFov = 60 * std::numbers::pi / 180, kNear = 0.1, kFar = 20;

// The map's world width at linear depth z: 2 d tan(fov/2), d = near + z (far - near).
double map_width_at(double z) { return 2 * (kNear + z * (kFar - kNear)) * std::tan(kFov / 2); }

LightFrustum perspective_frustum()
{
    return {float(map_width_at(0)), float(map_width_at(1)), float(kNear), float(kFar)};
}

// A plane tilted at world slope g under a perspective light, seen in the map:
// its depth changes by g per world unit across u, g w(z) / (far - near) per
// texture unit, so dz/du = alpha (q + z), alpha = 2 g tan(fov/2), q = near /
// (far - near): z(u) = (z0 + q) e^(alpha u) - q. Across one row (the taps'
// v clamps into it) q + z grows 10x (g = 2: z from 0.05 to 0.55), and the
// plane's slope per texture unit with it. world_cone(2.2 g) makes the cone
// 2.2 times the plane's slope at every depth, above the 2 the no-acne bound
// asks for (the steep-receiver case above; z is convex in u, so towards the
// light it falls no faster than at the receiver): no acne anywhere, with zero
// base bias. One slope per texture unit, set so for the nearest receiver, is
// too shallow beyond u = ln(2.2) / alpha = 0.34: straight taps there see acne.
PN_BACKEND_TEST(SoftPcf, WorldConeClearsAPerspectivePlaneAtEveryDepth)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int W = 64;
    const double g = 2.0, alpha = 2 * g * std::tan(kFov / 2), q = kNear / (kFar - kNear), z0 = 0.05;
    Image map(W, 1, 1), rx(W, 1, 3);
    for (int x = 0; x < W; ++x) {
        const double u = (x + 0.5) / W;
        map.at(0, x, 0) = float((z0 + q) * std::exp(alpha * u) - q);
        rx.at(0, x, 0) = float(u);
        rx.at(1, x, 0) = 0.5f;
        rx.at(2, x, 0) = map.at(0, x, 0);
    }
    BurleyOptions options{.min_radius = 0.01f, .max_radius = 0.1f, .blocker_samples = 32, .filter_samples = 32};
    options.bias = DepthBias{BiasMode::Constant, 0.0f};
    const BurleyOptions world = world_cone(options, float(2.2 * g), perspective_frustum());
    ASSERT_GT(world.bias_slope_per_depth, 0.0f);
    const Image cone = burley(ctx, map, rx, world);
    BurleyOptions single = world;
    single.bias_slope = float(2.2 * g * map_width_at(map.at(0, 0, 0)) / (kFar - kNear));
    single.bias_slope_per_depth = 0;
    const Image flat = burley(ctx, map, rx, single);
    int acne = 0;
    for (int x = 0; x < W; ++x) {
        EXPECT_EQ(cone.at(0, x, 0), 1.0f) << x;
        acne += flat.at(0, x, 0) < 1.0f;
    }
    EXPECT_GT(acne, W / 2);
}

INSTANTIATE_TEST_SUITE_P(Backends, SoftPcf, ::testing::ValuesIn(backend_names()), backend_test_name);

// world_cone against its closed form: at depth z the cone's slope per texture
// unit times (far - near) / w(z) is the world slope, for a perspective and an
// orthographic light (w constant: no growth with depth); the rest of the
// options are kept.
TEST(SoftPcfOperations, WorldConeIsTheWorldSlopeAtEveryDepth)
{
    BurleyOptions options;
    options.max_radius = 0.03f;
    const BurleyOptions world = world_cone(options, 2.0f, perspective_frustum());
    EXPECT_EQ(world.max_radius, 0.03f);
    for (double z : {0.0, 0.3, 1.0}) {
        const double slope = double(world.bias_slope) + double(world.bias_slope_per_depth) * z;
        EXPECT_NEAR(slope * (kFar - kNear) / map_width_at(z), 2.0, 2e-6) << z;
    }
    const BurleyOptions ortho = world_cone(options, 2.0f, LightFrustum{10, 10, 1, 21});
    EXPECT_NEAR(ortho.bias_slope, 2.0 * 10 / 20, 1e-6);
    EXPECT_EQ(ortho.bias_slope_per_depth, 0.0f);
}

// ---- the operations' checks ----------------------------------------------------

void expect_parameter(const std::function<void()>& run, const std::string& parameter)
{
    try {
        run();
        ADD_FAILURE() << "no error for " << parameter;
    } catch (const Error& e) {
        // InvalidArgument for an option, InvalidData for a value inside an image.
        EXPECT_NE(e.category(), ErrorCategory::Backend) << e.what();
        EXPECT_EQ(e.parameter(), parameter) << e.what();
    }
}

TEST(SoftPcfOperations, BadOptionsAndInputsNameTheParameter)
{
    Context ctx(ContextOptions{Backend::Scalar, {}});
    const Image map = flat_map(8, 8, 0.5f), rx = testing::receivers_at_depth(8, 8, 0.7f);
    auto with_pcss = [&](auto edit) {
        PcssOptions o;
        edit(o);
        return [&, o] { pcss(ctx, map, rx, o); };
    };
    auto with_burley = [&](auto edit) {
        BurleyOptions o;
        edit(o);
        return [&, o] { burley(ctx, map, rx, o); };
    };
    expect_parameter(with_pcss([](PcssOptions& o) { o.blocker_samples = -1; }), "blocker-samples");
    expect_parameter(with_pcss([](PcssOptions& o) { o.filter_samples = kMaxSoftSamples + 1; }), "filter-samples");
    expect_parameter(with_pcss([](PcssOptions& o) { o.light_size = -0.1f; }), "light-size");
    expect_parameter(with_pcss([](PcssOptions& o) { o.bias.constant = NAN; }), "depth-bias");
    expect_parameter(with_burley([](BurleyOptions& o) { o.min_radius = 0.02f, o.max_radius = 0.01f; }), "min-radius");
    expect_parameter(with_burley([](BurleyOptions& o) { o.bias_slope = -1; }), "bias-slope");
    expect_parameter(with_burley([](BurleyOptions& o) { o.bias_slope_per_depth = -3; }), "bias-slope-per-depth");
    expect_parameter(with_burley([](BurleyOptions& o) { o.falloff = -1; }), "falloff");
    expect_parameter(with_burley([](BurleyOptions& o) { o.blocker_samples = 0; }), "blocker-samples");
    Image bad = map;
    bad.at(0, 3, 2) = NAN;
    expect_parameter([&] { pcss(ctx, bad, rx, {}); }, "depth");
    expect_parameter([&] { burley(ctx, map, Image(8, 8, 2), {}); }, "receivers");
    Image bad_rx = rx;
    bad_rx.at(2, 1, 1) = INFINITY;
    expect_parameter([&] { burley(ctx, map, bad_rx, {}); }, "receivers");
    const LightFrustum light{1, 2, 0.5f, 10};
    expect_parameter([&] { world_cone({}, -1, light); }, "bias-slope");
    expect_parameter([&] { world_cone({}, 2, LightFrustum{1, 2, 10, 10}); }, "light");
    expect_parameter([&] { world_cone({}, 2, LightFrustum{0, 2, 0.5f, 10}); }, "light");
    expect_parameter([&] { world_cone({}, 2, LightFrustum{1, NAN, 0.5f, 10}); }, "light");
    expect_parameter([&] { world_cone({}, 1000, LightFrustum{1, 100, 0.5f, 1}); }, "bias-slope");
}

}  // namespace
}  // namespace penumbra
