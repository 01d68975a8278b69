// The cascaded shadow mask (kernels/cascades.h, penumbra/cascades.h) and its
// reference side (penumbra/reference/cascades.h) on every backend: cascade
// selection against its definition in float64, no seam at the boundaries,
// pancaking's sliver without the fix and none with it, the error against the
// ray-traced hard shadow per scene, agreement with the scalar oracle at odd
// sizes, and bad input. docs/cascades.md states the bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "penumbra/cascades.h"
#include "penumbra/reference/cascades.h"
#include "penumbra/reference/metrics.h"
#include "support/backends.h"
#include "support/cascade_cases.h"
#include "support/errors.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;
using testing::cascade_case;
using testing::expect_error;

constexpr int kWidth = 161, kHeight = 91;  // odd, not a multiple of any lane count

double axis(const std::array<float, 3>& a, const Image& rx, int x, int y)
{
    return double(a[0]) * rx.at(0, x, y) + double(a[1]) * rx.at(1, x, y) + double(a[2]) * rx.at(2, x, y);
}

// How far (texture units; < 0 outside) pixel (x, y) lies inside cascade c's
// box shrunk by the PCF footprint, in float64: the selection's definition.
double inside_by(const CascadeShadows& s, int c, const Image& rx, int x, int y, int grid)
{
    const CascadeFrame& f = s.cascades[std::size_t(c)];
    const double u = axis(s.axis_u, rx, x, y) * f.u_scale + f.u_offset;
    const double v = axis(s.axis_v, rx, x, y) * f.v_scale + f.v_offset;
    const double z = axis(s.axis_z, rx, x, y) * f.z_scale + f.z_offset;
    const double margin = 0.5 * (grid + 1) / s.maps.width();
    return std::min({u - margin, 1 - margin - u, v - margin, 1 - margin - v, z, 1 - z});
}

using CascadeMask = ::testing::TestWithParam<std::string>;

PN_BACKEND_TEST(CascadeMask, EveryPixelGetsTheFinestCascadeThatHoldsIt)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (int count : {2, 3, 4}) {
        reference::CascadeSetup setup;
        setup.count = count;
        setup.map_size = 128;
        const auto& c = cascade_case("contact", 0, kWidth, kHeight, setup);
        const Image out = cascade_mask(ctx, c.shadows, c.rx);
        int used[kMaxCascades] = {}, undecided = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                int expected = -1;
                double nearest = 1;  // how close to a box face the decision came
                for (int k = count - 1; k >= 0 && c.rx.at(4, x, y) > 0; --k) {
                    const double by = inside_by(c.shadows, k, c.rx, x, y, 4);
                    nearest = std::min(nearest, std::abs(by));
                    if (by >= 0) expected = k;
                }
                if (nearest < 1e-5) {  // float32 may decide either way
                    ++undecided;
                    continue;
                }
                ASSERT_EQ(int(out.at(1, x, y)), expected) << count << " cascades, pixel " << x << "," << y;
                if (expected >= 0) ++used[expected];
            }
        for (int k = 0; k < count; ++k) EXPECT_GT(used[k], 0) << "cascade " << k << " of " << count << " never chosen";
        EXPECT_LT(undecided, kWidth * kHeight / 1000);
    }
}

PN_BACKEND_TEST(CascadeMask, SplitDepthSelectionTakesTheFirstSplitBeyondThePixel)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const auto& c = cascade_case("contact", 0, kWidth, kHeight);
    CascadeOptions o;
    o.selection = CascadeSelection::SplitDepth;
    const Image out = cascade_mask(ctx, c.shadows, c.rx, o);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            int expected = -1;
            for (int k = int(c.shadows.cascades.size()) - 1; k >= 0; --k)
                if (c.rx.at(3, x, y) <= c.shadows.cascades[std::size_t(k)].split_far) expected = k;
            if (c.rx.at(4, x, y) == 0) expected = -1;
            ASSERT_EQ(int(out.at(1, x, y)), expected) << x << "," << y;
        }
}

// Across every boundary (a pixel whose right or lower neighbour took another
// cascade), the pixel shaded by its own cascade and by the other differs by
// little: the texel size changes, not the shadow.
PN_BACKEND_TEST(CascadeMask, NoSeamAtCascadeBoundaries)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const char* scene : {"contact", "courtyard"}) {
        const auto& c = cascade_case(scene, 0, 321, 181);
        const Image out = cascade_mask(ctx, c.shadows, c.rx);
        std::vector<Image> alone;
        for (int k = 0; k < int(c.shadows.cascades.size()); ++k)
            alone.push_back(cascade_mask(ctx, testing::single_cascade(c.shadows, k), c.rx));
        std::vector<double> differences;
        for (int y = 0; y + 1 < out.height(); ++y)
            for (int x = 0; x + 1 < out.width(); ++x) {
                const int here = int(out.at(1, x, y));
                for (const int there : {int(out.at(1, x + 1, y)), int(out.at(1, x, y + 1))}) {
                    if (here < 0 || there < 0 || here == there) continue;
                    // Both cascades hold the pixel where the finer one does (the boxes nest along the view).
                    if (alone[std::size_t(there)].at(1, x, y) < 0) continue;
                    differences.push_back(std::abs(alone[std::size_t(here)].at(0, x, y) -
                                                   alone[std::size_t(there)].at(0, x, y)));
                }
            }
        ASSERT_GT(differences.size(), 20u) << scene;
        std::sort(differences.begin(), differences.end());
        double mean = 0;
        for (double d : differences) mean += d / double(differences.size());
        const double p99 = differences[std::size_t(0.99 * double(differences.size() - 1))];
        std::printf("%s: %zu boundary probes, mean %.4f, p99 %.4f, max %.4f\n", scene, differences.size(), mean, p99,
                    differences.back());
        // The coarser cascade's PCF footprint is wider in the world, so a shadow
        // edge moves a little; no probe may flip lit and shadowed (docs/cascades.md).
        EXPECT_LT(mean, 0.05) << scene;
        EXPECT_LT(differences.back(), 0.5) << scene;
    }
}

// Light leaking in the first cascade: pixels it shades above 0.5 where the
// truth is in shadow.
int leaks_in_first_cascade(const Image& out, const Image& truth)
{
    int leaks = 0;
    for (int y = 0; y < out.height(); ++y)
        for (int x = 0; x < out.width(); ++x)
            leaks += out.at(1, x, y) == 0 && truth.at(0, x, y) == 0 && out.at(0, x, y) > 0.5f;
    return leaks;
}

PN_BACKEND_TEST(CascadeMask, PancakingSliverWithoutTheFixAndNoneWithIt)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    reference::CascadeSetup clip;
    clip.near_plane = reference::NearPlane::Clip;
    const auto& clipped = cascade_case("courtyard", 0, 321, 181, clip);
    const auto& pancaked = cascade_case("courtyard", 0, 321, 181);
    const int sliver = leaks_in_first_cascade(cascade_mask(ctx, clipped.shadows, clipped.rx), clipped.truth);
    const int fixed = leaks_in_first_cascade(cascade_mask(ctx, pancaked.shadows, pancaked.rx), pancaked.truth);
    std::printf("courtyard: first-cascade leaks, clipped %d, pancaked %d\n", sliver, fixed);
    EXPECT_GT(sliver, 500);
    EXPECT_LT(fixed, sliver / 20);
}

struct TruthCase {
    const char* scene;
    int light;
    double rmse, p99;  // bounds, docs/cascades.md
};

PN_BACKEND_TEST(CascadeMask, AgainstTheRayTracedHardShadow)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const TruthCase t : {TruthCase{"contact", 0, 0.07, 0.45}, TruthCase{"contact", 1, 0.07, 0.45},
                              TruthCase{"large", 0, 0.14, 0.75}, TruthCase{"courtyard", 0, 0.06, 0.3}}) {
        const auto& c = cascade_case(t.scene, t.light, 321, 181);
        const Image out = cascade_mask(ctx, c.shadows, c.rx);
        Image visibility(out.width(), out.height(), 1), held(out.width(), out.height(), 1);
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) {
                visibility.at(0, x, y) = out.at(0, x, y);
                held.at(0, x, y) = out.at(1, x, y) >= 0 ? 1.0f : 0.0f;
                ASSERT_TRUE(std::isfinite(out.at(0, x, y)));
            }
        const double rmse = reference::rmse(visibility, c.truth, &held);
        const double p99 = reference::p99_abs_error(visibility, c.truth, &held);
        std::printf("%s light %d: rmse %.4f p99 %.4f\n", t.scene, t.light, rmse, p99);
        EXPECT_LT(rmse, t.rmse) << t.scene << " " << t.light;
        EXPECT_LE(p99, t.p99) << t.scene << " " << t.light;
    }
}

using CascadeAgreement = ::testing::TestWithParam<std::string>;

// Odd sizes (1x1, 7x3, widths around every lane count): the scalar oracle's
// result within 1e-5 (the Gaussian's exponentials), never NaN.
PN_BACKEND_TEST(CascadeAgreement, OddSizesAgreeWithTheScalarOracle)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Context& oracle = testing::scalar_oracle(backend);
    const auto& c = cascade_case("contact", 0, kWidth, kHeight);
    std::vector<std::pair<int, int>> sizes = {{1, 1}, {7, 3}};
    for (int w : testing::lane_edge_widths()) sizes.emplace_back(w, 2);
    for (const auto& [w, h] : sizes) {
        Image rx(w, h, kCascadeReceiverChannels);
        for (int ch = 0; ch < kCascadeReceiverChannels; ++ch)
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) rx.at(ch, x, y) = c.rx.at(ch, (40 + x) % kWidth, 45 + y);
        const Image got = cascade_mask(ctx, c.shadows, rx), expected = cascade_mask(oracle, c.shadows, rx);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                ASSERT_TRUE(got.at(0, x, y) >= 0 && got.at(0, x, y) <= 1) << w << "x" << h;
                EXPECT_NEAR(got.at(0, x, y), expected.at(0, x, y), 1e-5) << w << "x" << h << " at " << x;
                EXPECT_EQ(got.at(1, x, y), expected.at(1, x, y)) << w << "x" << h << " at " << x;
            }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, CascadeMask, ::testing::ValuesIn(backend_names()), backend_test_name);
INSTANTIATE_TEST_SUITE_P(Backends, CascadeAgreement, ::testing::ValuesIn(testing::non_scalar_backends()),
                         backend_test_name);

TEST(CascadeMaskErrors, BadInputNamesWhatIsWrong)
{
    Context& ctx = PN_CONTEXT_OR_SKIP("scalar");
    const auto& c = cascade_case("contact", 0, 33, 17);
    const ErrorCategory bad = ErrorCategory::InvalidArgument;
    CascadeShadows none = c.shadows;
    none.cascades.clear();
    expect_error([&] { cascade_mask(ctx, none, c.rx); }, bad, "cascade-mask", {"no cascades"});
    CascadeShadows five = c.shadows;
    five.cascades.resize(5, c.shadows.cascades[0]);
    five.maps = Image(c.shadows.maps.width(), c.shadows.maps.width() * 5, 1);
    expect_error([&] { cascade_mask(ctx, five, c.rx); }, bad, "cascade-mask", {"5 cascades", "at most 4"});
    CascadeShadows uneven = c.shadows;
    uneven.maps = Image(c.shadows.maps.width(), c.shadows.maps.height() + 1, 1);
    expect_error([&] { cascade_mask(ctx, uneven, c.rx); }, bad, "cascade-mask", {"not a multiple"});
    CascadeShadows nan = c.shadows;
    nan.cascades[1].u_scale = NAN;
    expect_error([&] { cascade_mask(ctx, nan, c.rx); }, bad, "cascade-mask", {"cascade 1"});
    const Image three(33, 17, 3);
    expect_error([&] { cascade_mask(ctx, c.shadows, three); }, bad, "cascade-mask", {"5 channels"});
    Image small(32, 17, 2);
    expect_error([&] { cascade_mask(ctx, c.shadows, c.rx, {}, small); }, bad, "cascade-mask", {"33x17"});
    CascadeOptions o;
    o.grid = 17;
    expect_error([&] { cascade_mask(ctx, c.shadows, c.rx, o); }, bad, "cascade-mask", {"grid"});
    o = {};
    o.bias_min = 9;
    expect_error([&] { cascade_mask(ctx, c.shadows, c.rx, o); }, bad, "cascade-mask", {"exceeds bias-max"});
    Image nan_rx = c.rx;
    nan_rx.at(0, 3, 5) = NAN;
    expect_error([&] { cascade_mask(ctx, c.shadows, nan_rx); }, ErrorCategory::InvalidData, "cascade-mask",
                 {"receivers", "(3, 5)"});
}

TEST(CascadeReference, ASceneWithoutADirectionalLightIsRefused)
{
    const reference::Scene scene = reference::builtin_scene("fence");
    const reference::Receivers r = reference::render_receivers(scene, 8, 8);
    expect_error([&] { reference::render_cascades(scene, 0, r, {}); }, ErrorCategory::InvalidArgument,
                 "render_cascades", {"no", "directional_lights"});
    reference::CascadeSetup five;
    five.count = 5;
    const reference::Scene contact = reference::builtin_scene("contact");
    expect_error([&] { reference::render_cascades(contact, 0, reference::render_receivers(contact, 8, 8), five); },
                 ErrorCategory::InvalidArgument, "split_depths", {"5 cascades"});
    expect_error([&] { reference::directional_truth(contact, 2, r); }, ErrorCategory::InvalidArgument,
                 "directional_truth", {"light 2"});
}

TEST(CascadeReference, PracticalSplitsBlendTheLogarithmicAndUniformSchemes)
{
    const std::vector<double> log = reference::split_depths(1, 100, 2, 1), uni = reference::split_depths(1, 100, 2, 0);
    EXPECT_NEAR(log[1], 10, 1e-12);
    EXPECT_NEAR(uni[1], 50.5, 1e-12);
    const std::vector<double> mix = reference::split_depths(1, 100, 4, 0.75);
    ASSERT_EQ(mix.size(), 5u);
    for (std::size_t i = 1; i < mix.size(); ++i) EXPECT_GT(mix[i], mix[i - 1]);
    EXPECT_EQ(mix.front(), 1);
    EXPECT_EQ(mix.back(), 100);
}

TEST(CascadeReference, DirectionalLightsRoundTripThroughJson)
{
    const reference::Scene scene = reference::builtin_scene("contact");
    ASSERT_EQ(scene.directional_lights.size(), 2u);
    const reference::Scene back = reference::scene_from_json(reference::scene_to_json(scene));
    ASSERT_EQ(back.directional_lights.size(), 2u);
    EXPECT_EQ(back.directional_lights[1].direction, scene.directional_lights[1].direction);
    expect_error(
        [] {
            reference::scene_from_json(R"({"primitives": [{"type": "sphere", "center": [0, 1, 0], "radius": 1}],
              "light": {"shape": "point", "center": [0, 5, 0], "normal": [0, -1, 0]},
              "light_camera": {"projection": "perspective", "near": 1, "far": 9, "fov_degrees": 60},
              "view": {"position": [0, 2, 5], "target": [0, 0, 0], "fov_degrees": 45},
              "directional_lights": [{"direction": [0, 0, 0]}]})");
        },
        ErrorCategory::InvalidArgument, "", {"directional_lights[0].direction"});
}

}  // namespace
}  // namespace penumbra
