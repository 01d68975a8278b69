// ssao-vo (kernels/ssao_vo.h, penumbra/ssao.h) on every backend: the closed
// forms (a plane facing the camera is 1/2 exactly; a plane through the point
// halves the sphere at any tilt, which paired samples reproduce at every
// rotation while the alternatives do not once samples become unusable; the
// inside of a right-angle corner is 3/4), the float64 mathematics of the
// method on a scene's depth, odd sizes, continuity under a small camera
// move, the pattern's volumes, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "penumbra/ssao.h"
#include "support/backends.h"
#include "support/errors.h"
#include "support/ssao_reference.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;

constexpr double kFovDegrees = 45.0;
const SsaoUnusable kRules[] = {SsaoUnusable::Paired, SsaoUnusable::Zero, SsaoUnusable::Half,
                               SsaoUnusable::Renormalise};

SsaoOptions obscurance(SsaoUnusable rule, bool rotate = true, int pairs = 3)
{
    SsaoOptions o;
    o.unusable = rule;
    o.rotate = rotate;
    o.pairs = pairs;
    o.output = SsaoOutput::Obscurance;
    return o;
}

// The largest |o - 1/2| over the pixels whose whole disc lies on screen (or all).
double largest_deviation(const Image& o, int margin)
{
    double worst = 0;
    for (int y = margin; y < o.height() - margin; ++y)
        for (int x = margin; x < o.width() - margin; ++x) worst = std::max(worst, std::abs(o.at(0, x, y) - 0.5));
    return worst;
}

class SsaoVoTest : public ::testing::TestWithParam<std::string> {};

PN_BACKEND_TEST(SsaoVoTest, APlaneFacingTheCameraIsHalfOccludedExactly)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    std::vector<std::pair<int, int>> sizes = {{1, 1}, {7, 3}, {64, 48}};
    for (int w : testing::lane_edge_widths()) sizes.push_back({w, 5});
    for (auto [w, h] : sizes)
        for (SsaoUnusable rule : kRules)
            for (bool rotate : {false, true}) {
                Image depth(w, h, 1);
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) depth.at(0, x, y) = 3.0f;
                const Image o = ssao_obscurance(ctx, depth, kFovDegrees, obscurance(rule, rotate));
                // Zero counts off-screen samples as open: exact where the disc is on screen.
                const int margin = rule == SsaoUnusable::Zero ? int(0.07 * h) + 1 : 0;
                EXPECT_EQ(largest_deviation(o, margin), 0.0) << w << "x" << h << " rule " << int(rule);
                SsaoOptions ao = obscurance(rule, rotate);
                ao.output = SsaoOutput::Accessibility;
                const Image a = ssao_obscurance(ctx, depth, kFovDegrees, ao);
                if (margin == 0) {
                    EXPECT_EQ(a.at(0, w - 1, h - 1), 1.0f) << "an open plane has the AO term 1";
                }
            }
}

// The largest |o - 1/2| over the pixels at least `margin` from the border
// whose depth is at least `nearest`.
double largest_deviation_beyond(const Image& o, const Image& depth, int margin, float nearest)
{
    double worst = 0;
    for (int y = margin; y < o.height() - margin; ++y)
        for (int x = margin; x < o.width() - margin; ++x)
            if (depth.at(0, x, y) >= nearest) worst = std::max(worst, std::abs(o.at(0, x, y) - 0.5));
    return worst;
}

// A plane through the point halves the sphere, whatever its tilt: 1/2. The
// depth is affine in the pixels (a narrow 10-degree view, so that an
// 80-degree plane stays in front of the camera); the kernel's lines, a
// centre pixel's size apart, see at depth z the slope tan(tilt) z0 / z. At
// 45 degrees, where z >= z0, every sample is usable and every rule gives 1/2.
// At 80 degrees the near samples fall beyond the falloff: paired samples
// still give 1/2 everywhere (the partner's inverse is exact on a plane), at
// every rotation of the tile and every azimuth, while the alternatives drift.
// "Exact" is up to the float32 depths' rounding: one ulp of z = 4 (4.8e-7)
// over a line 0.05 long (the capped sphere here) moves e by 1e-5 a tap:
// the bound is 2e-5, a thousandth of the alternatives' drift.
PN_BACKEND_TEST(SsaoVoTest, TiltedPlanesAreHalfOccludedWithPairsAtAnyRotation)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 96, h = 64, margin = 6;
    const double fov = 10.0, z0 = 4.0;
    double drift[4] = {0, 0, 0, 0};
    for (double tilt_degrees : {45.0, 80.0})
        for (double azimuth : {0.0, 0.3, 0.785398, 1.2, 2.0, 3.0})
            for (int r = 0; r < 4; ++r) {
                const Image depth = testing::ssao_plane_depth(w, h, fov, z0, tilt_degrees * M_PI / 180, azimuth);
                const Image o = ssao_obscurance(ctx, depth, fov, obscurance(kRules[r]));
                const std::string where = "tilt " + std::to_string(tilt_degrees) + " azimuth " +
                                          std::to_string(azimuth) + " rule " + std::to_string(r);
                if (kRules[r] == SsaoUnusable::Paired) {
                    EXPECT_LE(largest_deviation(o, 0), 2e-5) << where;
                }
                if (tilt_degrees == 45.0) {
                    EXPECT_LE(largest_deviation_beyond(o, depth, margin, float(z0)), 2e-5) << where;
                }
                drift[r] = std::max(drift[r], largest_deviation(o, margin));
            }
    EXPECT_GT(drift[1], 0.05) << "zero: unusable samples count as open";
    EXPECT_GT(drift[2], 0.01) << "half: right only for planes facing the camera";
    EXPECT_GT(drift[3], 0.01) << "renormalise: the usable samples are one-sided";
}

// The inside of a right-angle corner, at its edge: the free space in front
// is a 90-degree wedge, a quarter of the sphere, so o = 3/4. The estimate is
// a quadrature of that volume; 16 pairs averaged over the tile's 16
// rotations come within 0.02 of it (measured 0.7376), and every pixel
// matches the method's float64 mathematics.
PN_BACKEND_TEST(SsaoVoTest, ACornerIsThreeQuartersOccluded)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 80, h = 60;
    double sum = 0;
    int n = 0;
    const SsaoOptions o = obscurance(SsaoUnusable::Paired, true, 16);
    for (int edge = 40; edge < 44; ++edge) {
        const Image depth = testing::ssao_corner_depth(w, h, kFovDegrees, 5.0, edge);
        const Image out = ssao_obscurance(ctx, depth, kFovDegrees, o);
        for (int y = 20; y < 24; ++y) {
            sum += out.at(0, edge, y);
            ++n;
            EXPECT_NEAR(out.at(0, edge, y), testing::ssao_reference(depth, kFovDegrees, o, edge, y), 1e-5);
        }
    }
    EXPECT_NEAR(sum / n, 0.75, 0.02);
    std::cout << backend << ": corner mean " << sum / n << "\n";
}

// A reference scene's view depth: every option against the float64
// mathematics, at odd sizes; never NaN, always in [0, 1].
PN_BACKEND_TEST(SsaoVoTest, MatchesTheFloat64MathematicsOnASceneAtOddSizes)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const reference::Scene scene = reference::builtin_scene("contact");
    std::vector<std::pair<int, int>> sizes = {{1, 1}, {7, 3}, {61, 37}};
    for (int w : testing::lane_edge_widths()) sizes.push_back({w, 9});
    for (auto [w, h] : sizes) {
        const reference::Receivers rx = reference::render_receivers(scene, w, h);
        for (SsaoUnusable rule : kRules)
            for (SsaoOutput output : {SsaoOutput::Obscurance, SsaoOutput::Accessibility}) {
                SsaoOptions o = obscurance(rule);
                o.output = output;
                o.radius = 0.4;
                const Image got = ssao_obscurance(ctx, rx.view_depth, scene.view.fov_degrees, o);
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) {
                        const float v = got.at(0, x, y);
                        ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << v;
                        ASSERT_NEAR(v, testing::ssao_reference(rx.view_depth, scene.view.fov_degrees, o, x, y), 2e-5)
                            << w << "x" << h << " (" << x << ", " << y << ") rule " << int(rule);
                    }
            }
    }
}

// The flicker metric: the mean |change| of the blurred AO term between two
// frames whose camera moved 1 cm sideways (about a tenth of a pixel at the
// contact scene's ground, 11 m away), over pixels that see a surface in both. Line
// integrals change continuously with depth, so the change stays below 0.002
// (measured 0.00043 on every backend, 2026-12-03; docs/ssao.md).
PN_BACKEND_TEST(SsaoVoTest, ASmallCameraMoveChangesTheMaskLittle)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    reference::Scene scene = reference::builtin_scene("contact");
    const int w = 160, h = 90;
    const reference::Receivers a = reference::render_receivers(scene, w, h);
    scene.view.position.x += 0.01;
    scene.view.target.x += 0.01;
    const reference::Receivers b = reference::render_receivers(scene, w, h);
    const Image ao_a = ssao_blurred(ctx, a.view_depth, scene.view.fov_degrees);
    const Image ao_b = ssao_blurred(ctx, b.view_depth, scene.view.fov_degrees);
    double sum = 0;
    int n = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (a.hit.at(0, x, y) > 0 && b.hit.at(0, x, y) > 0) {
                sum += std::abs(ao_a.at(0, x, y) - ao_b.at(0, x, y));
                ++n;
            }
    ASSERT_GT(n, w * h / 2);
    EXPECT_LT(sum / n, 0.002);
    std::cout << backend << ": mean change " << sum / n << "\n";
}

INSTANTIATE_TEST_SUITE_P(Backends, SsaoVoTest, ::testing::ValuesIn(backend_names()), backend_test_name);

TEST(SsaoPattern, VolumesSumToOneAndComeOutNearlyEqual)
{
    for (int pairs : {1, 3, 8, 16}) {
        const SsaoPattern p = ssao_pattern(pairs);
        double total = p.centre_weight, low = p.centre_weight, high = p.centre_weight;
        for (const SsaoSample& s : p.pairs) {
            total += 2 * s.weight;
            low = std::min(low, s.weight);
            high = std::max(high, s.weight);
            EXPECT_LT(s.x * s.x + s.y * s.y, 1.0);
        }
        EXPECT_NEAR(total, 1.0, 1e-12);
        // Equal shares would be 1 / (2 pairs + 1); docs/ssao.md has the spread.
        EXPECT_LT(high / low, 3.0) << pairs << " pairs";
    }
}

TEST(SsaoErrors, BadInputIsATypedErrorNamingIt)
{
    Context& ctx = PN_CONTEXT_OR_SKIP("scalar");
    Image depth(8, 4, 1);
    auto run = [&](SsaoOptions o, double fov = kFovDegrees) { return [&ctx, &depth, o, fov] { ssao_obscurance(ctx, depth, fov, o); }; };
    auto with = [](auto set) {
        SsaoOptions o;
        set(o);
        return o;
    };
    using testing::expect_error;
    const auto bad = ErrorCategory::InvalidArgument;
    expect_error(run(with([](SsaoOptions& o) { o.radius = 0; })), bad, "ssao", {"radius"});
    expect_error(run(with([](SsaoOptions& o) { o.radius = -1; })), bad, "ssao", {"radius"});
    expect_error(run(with([](SsaoOptions& o) { o.radius = NAN; })), bad, "ssao", {"radius"});
    expect_error(run(with([](SsaoOptions& o) { o.pairs = 0; })), bad, "ssao", {"pairs"});
    expect_error(run(with([](SsaoOptions& o) { o.pairs = 17; })), bad, "ssao", {"pairs", "16"});
    expect_error(run(with([](SsaoOptions& o) { o.falloff = 1; })), bad, "ssao", {"falloff"});
    expect_error(run(with([](SsaoOptions& o) { o.max_screen_radius = 0; })), bad, "ssao", {"max-screen-radius"});
    expect_error(run({}, 0.0), bad, "ssao", {"field of view"});
    expect_error(run({}, 180.0), bad, "ssao", {"field of view"});
    depth.at(0, 5, 2) = -1.0f;
    expect_error(run({}), ErrorCategory::InvalidData, "ssao", {"(5, 2)", "finite and >= 0"});
    depth.at(0, 5, 2) = NAN;
    expect_error(run({}), ErrorCategory::InvalidData, "ssao", {"(5, 2)"});
    const Image two(8, 4, 2);
    expect_error([&] { ssao_obscurance(ctx, two, kFovDegrees); }, bad, "ssao", {"1 channel"});
    Image same(8, 4, 1);
    expect_error([&] { ssao_obscurance(ctx, same, kFovDegrees, {}, same); }, bad, "ssao", {"another"});
}

}  // namespace
}  // namespace penumbra
