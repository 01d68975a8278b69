// The deep shadow map lookup (penumbra/deep_lookup.h, kernels/dsm_lookup.h)
// on every backend against its float64 reference (support/
// deep_lookup_reference.h: each pixel searched in double, the filter summed
// brute force over the map), on odd sizes and strips around every lane
// count, with empty pixels, single steps, receivers at vertices, before the
// first and after the last; monotone in z and never outside [0, 1]; on maps
// dsm-build makes of hair, fog and layers; and the closed forms of one and
// two semi-transparent sheets and a fog slab through the kernel.
//
// Tolerance 2e-6 against float64: the kernel interpolates and weighs in
// float32 (a handful of roundings of values <= 1). Both evaluate at the
// float32 depth z - bias, the contract's (penumbra/deep_lookup.h): in double,
// steep segments of the hair map (a drop of 0.5 over 1e-4 in depth) turn its
// half-ulp rounding into 1.2e-5.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "penumbra/deep_lookup.h"
#include "penumbra/reference/deep_map.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "support/backends.h"
#include "support/deep_lookup_reference.h"
#include "support/deep_scenes.h"
#include "support/errors.h"
#include "support/maps.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;
using testing::reference_deep_lookup;

constexpr double kDsmTolerance = 2e-6;

// Every filter, radius and search the cases run.
std::vector<DeepLookupOptions> option_grid(float bias = 0.0f)
{
    std::vector<DeepLookupOptions> grid;
    for (DeepFilter f : {DeepFilter::Box, DeepFilter::Tent})
        for (int r : {0, 1, 2})
            for (DeepSearch s : {DeepSearch::Binary, DeepSearch::Linear}) grid.push_back({f, r, s, bias});
    return grid;
}

std::string describe(const DeepLookupOptions& o)
{
    return std::string(o.filter == DeepFilter::Box ? "box" : "tent") + " r" + std::to_string(o.radius) +
           (o.search == DeepSearch::Binary ? " binary" : " linear");
}

// Receivers spread over the map and past its edges, z over the depths.
Image scattered(int width, int height, std::uint32_t seed)
{
    return testing::scattered_receivers(width, height, -0.1f, 1.1f, -0.05f, 1.05f, seed);
}

// The largest |lookup - reference| over the receivers; every value in [0, 1].
double worst_error(const DeepShadowMap& map, const Image& rx, const DeepLookupOptions& o, const Image& got)
{
    double worst = 0;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            const float v = got.at(0, x, y);
            EXPECT_TRUE(v >= 0.0f && v <= 1.0f) << v;
            const double expected = reference_deep_lookup(map, o, rx.at(0, x, y), rx.at(1, x, y), rx.at(2, x, y));
            worst = std::max(worst, std::abs(double(v) - expected));
        }
    return worst;
}

using DsmLookup = ::testing::TestWithParam<std::string>;

PN_BACKEND_TEST(DsmLookup, AgreesWithTheFloat64ReferenceOnOddSizesAndLaneWidths)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int map_sizes[][2] = {{1, 1}, {7, 3}, {16, 5}};
    const int receiver_widths[] = {1, 7, 15, 16, 17, 33};
    std::uint32_t seed = 1;
    for (const auto& size : map_sizes) {
        const DeepShadowMap map = testing::random_deep_map(size[0], size[1], seed++);
        for (int width : receiver_widths) {
            const Image rx = scattered(width, 3, seed++);
            for (const DeepLookupOptions& o : option_grid(0.01f)) {
                const Image got = deep_lookup(ctx, map, rx, o);
                EXPECT_LE(worst_error(map, rx, o, got), kDsmTolerance)
                    << describe(o) << ", map " << size[0] << "x" << size[1] << ", receivers " << width << "x3";
            }
        }
    }
}

// Long pixels (up to 200 vertices): the bisection's steps and the linear
// loop's trip counts differ widely between the lanes of one strip.
PN_BACKEND_TEST(DsmLookup, AgreesOnLongPixelsWithMixedTripCounts)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const DeepShadowMap map = testing::random_deep_map(9, 4, 7, 200);
    const Image rx = scattered(33, 4, 8);
    for (const DeepLookupOptions& o : option_grid())
        EXPECT_LE(worst_error(map, rx, o, deep_lookup(ctx, map, rx, o)), kDsmTolerance) << describe(o);
}

// Receivers at pixel centres: the box r = 0 reads that pixel alone, and so
// does the tent r = 0 (its other taps weigh 0 exactly on a power-of-two map).
Image at_centres(int map_w, int map_h, const std::vector<float>& depths)
{
    Image rx(map_w * map_h, int(depths.size()), 3);
    for (int k = 0; k < int(depths.size()); ++k)
        for (int p = 0; p < map_w * map_h; ++p) {
            rx.at(0, p, k) = (float(p % map_w) + 0.5f) / float(map_w);
            rx.at(1, p, k) = (float(p / map_w) + 0.5f) / float(map_h);
            rx.at(2, p, k) = depths[std::size_t(k)];
        }
    return rx;
}

PN_BACKEND_TEST(DsmLookup, AtAVertexReturnsItsValueBeforeTheFirstOneAfterTheLastTheLast)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const DeepShadowMap map = testing::random_deep_map(16, 2, 11, 20);
    for (DeepFilter f : {DeepFilter::Box, DeepFilter::Tent})
        for (DeepSearch s : {DeepSearch::Binary, DeepSearch::Linear}) {
            const DeepLookupOptions o{f, 0, s, 0.0f};
            for (int p = 0; p < 32; ++p) {
                const int x = p % 16, y = p / 16;
                const auto zs = map.depths(x, y);
                const auto ts = map.transmittances(x, y);
                std::vector<float> depths(zs.begin(), zs.end());
                if (zs.empty()) depths = {0.5f};
                depths.push_back(zs.empty() ? -1.0f : std::nextafter(zs.front(), -1.0f));
                depths.push_back(zs.empty() ? 2.0f : std::nextafter(zs.back(), 2.0f));
                Image rx(1, int(depths.size()), 3);
                for (int k = 0; k < rx.height(); ++k) {
                    rx.at(0, 0, k) = (float(x) + 0.5f) / 16.0f;
                    rx.at(1, 0, k) = (float(y) + 0.5f) / 2.0f;
                    rx.at(2, 0, k) = depths[std::size_t(k)];
                }
                const Image got = deep_lookup(ctx, map, rx, o);
                for (std::size_t i = 0; i < zs.size(); ++i) {
                    // At a step's depth the value before it: the first vertex at that depth.
                    std::size_t first = i;
                    while (first > 0 && zs[first - 1] == zs[i]) --first;
                    EXPECT_EQ(got.at(0, 0, int(i)), ts[first]) << describe(o) << " pixel " << p << " vertex " << i;
                }
                const int n = int(zs.size());
                EXPECT_EQ(got.at(0, 0, rx.height() - 2), 1.0f) << "before the first vertex, pixel " << p;
                EXPECT_EQ(got.at(0, 0, rx.height() - 1), zs.empty() ? 1.0f : ts[std::size_t(n - 1)])
                    << "after the last vertex, pixel " << p;
            }
        }
}

PN_BACKEND_TEST(DsmLookup, IsMonotoneInDepthAndInsideTheUnitInterval)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const DeepShadowMap map = testing::random_deep_map(7, 5, 21, 30);
    const Image spots = scattered(17, 1, 22);
    std::vector<float> depths;
    for (int k = 0; k <= 600; ++k) depths.push_back(-0.1f + 1.2f * float(k) / 600.0f);
    // Every vertex depth too, and its neighbours: where rounding could turn V up.
    for (float d : map.depths())
        for (float e : {std::nextafter(d, -1.0f), d, std::nextafter(d, 2.0f)}) depths.push_back(e);
    std::sort(depths.begin(), depths.end());
    Image rx(17, int(depths.size()), 3);
    for (int k = 0; k < rx.height(); ++k)
        for (int x = 0; x < 17; ++x) {
            rx.at(0, x, k) = spots.at(0, x, 0);
            rx.at(1, x, k) = spots.at(1, x, 0);
            rx.at(2, x, k) = depths[std::size_t(k)];
        }
    for (const DeepLookupOptions& o : option_grid()) {
        const Image got = deep_lookup(ctx, map, rx, o);
        for (int x = 0; x < 17; ++x)
            for (int k = 0; k < rx.height(); ++k) {
                ASSERT_TRUE(got.at(0, x, k) >= 0.0f && got.at(0, x, k) <= 1.0f) << describe(o);
                if (k == 0) continue;
                ASSERT_LE(got.at(0, x, k), got.at(0, x, k - 1))
                    << describe(o) << " receiver " << x << " z " << depths[std::size_t(k)];
            }
    }
}

PN_BACKEND_TEST(DsmLookup, EmptyMapsAndEmptyPixelsAreLit)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    DeepShadowMapBuilder builder(5, 3);
    for (int p = 0; p < 15; ++p) builder.add_pixel({}, {});
    const DeepShadowMap empty = builder.build();
    const Image rx = scattered(17, 3, 31);
    for (const DeepLookupOptions& o : option_grid()) {
        const Image got = deep_lookup(ctx, empty, rx, o);
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 17; ++x) ASSERT_EQ(got.at(0, x, y), 1.0f) << describe(o);
    }
}

// What dsm-build writes (the reference renderer with the paper's tolerance),
// small, looked up at the scene's own receivers.
PN_BACKEND_TEST(DsmLookup, AgreesOnTheMapsOfHairFogAndLayers)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const char* name : {"hair", "fog", "layers"}) {
        const reference::Scene scene = reference::builtin_scene(name);
        reference::DeepMapOptions build;
        build.size = 40;
        build.samples = 4;
        const DeepShadowMap map = reference::render_deep_shadow_map(scene, build);
        const Image rx = reference::render_receivers(scene, 33, 9).light_uvz;
        int shadowed = 0;
        for (const DeepLookupOptions& o : option_grid(kDeepDefaultBias)) {
            const Image got = deep_lookup(ctx, map, rx, o);
            EXPECT_LE(worst_error(map, rx, o, got), kDsmTolerance) << name << " " << describe(o);
            for (int y = 0; y < rx.height(); ++y)
                for (int x = 0; x < rx.width(); ++x) shadowed += got.at(0, x, y) < 0.9f;
        }
        EXPECT_GT(shadowed, 0) << name << ": a case that shades nothing proves nothing";
    }
}

// The closed forms under the overhead light (support/deep_scenes.h): between
// the sheets and the ground V is 1 - a, (1 - a)(1 - b); under a fog slab of
// extinction k and thickness s, exp(-k s). Uniform maps, so every filter gives
// the pixel's own value; the bound is the map's compression tolerance and, for
// fog, its volume step.
PN_BACKEND_TEST(DsmLookup, MatchesTheClosedFormsOfSheetsAndFog)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    struct Case {
        const char* what;
        std::string primitives, media;
        double expected;
    };
    const std::vector<Case> cases = {
        {"one sheet", testing::sheet_json(2, 0.4), "", 0.6},
        {"two sheets", testing::sheet_json(3, 0.5) + ", " + testing::sheet_json(2, 0.4), "", 0.5 * 0.6},
        {"fog slab", "",
         R"({"type": "box", "center": [0, 2.5, 0], "size": [40, 1, 40], "extinction": 0.7})", std::exp(-0.7)},
    };
    reference::DeepMapOptions build;
    build.size = 8;
    build.samples = 4;
    build.tolerance = 0.002f;
    for (const Case& c : cases) {
        const reference::Scene scene = testing::overhead_scene(c.primitives, c.media);
        const DeepShadowMap map = reference::render_deep_shadow_map(scene, build);
        // Just above the ground (height 0.5): below every sheet and the slab.
        const Image rx = at_centres(8, 8, {float(testing::overhead_z(0.5))});
        for (const DeepLookupOptions& o : option_grid()) {
            const Image got = deep_lookup(ctx, map, rx, o);
            for (int p = 0; p < 64; ++p)
                ASSERT_NEAR(got.at(0, p, 0), c.expected, 0.01) << c.what << " " << describe(o) << " pixel " << p;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, DsmLookup, ::testing::ValuesIn(backend_names()), backend_test_name);

TEST(DsmLookupErrors, BadOptionsAndReceiversNameTheParameter)
{
    Context ctx(ContextOptions{Backend::Scalar, {}});
    const DeepShadowMap map = testing::random_deep_map(4, 4, 3);
    const Image rx = scattered(5, 2, 4);
    auto parameter_of = [&](const DeepLookupOptions& o, const Image& receivers) {
        try {
            deep_lookup(ctx, map, receivers, o);
        } catch (const Error& e) {
            return std::string(e.parameter());
        }
        return std::string("(accepted)");
    };
    EXPECT_EQ(parameter_of({DeepFilter::Tent, -1}, rx), "radius");
    EXPECT_EQ(parameter_of({DeepFilter::Box, 256}, rx), "radius");
    EXPECT_EQ(parameter_of({DeepFilter::Box, 0, DeepSearch::Linear, std::nanf("")}, rx), "depth-bias");
    EXPECT_EQ(parameter_of({DeepFilter::Box, 0, DeepSearch::Linear, -0.1f}, rx), "depth-bias");
    EXPECT_EQ(parameter_of({}, Image(5, 2, 2)), "receivers");
    Image nan = rx;
    nan.at(2, 3, 1) = std::nanf("");
    testing::expect_error([&] { deep_lookup(ctx, map, nan, {}); }, ErrorCategory::InvalidData, "dsm",
                          "receivers");
    Image wrong(4, 2, 1);
    testing::expect_error([&] { deep_lookup(ctx, map, rx, {}, wrong); }, ErrorCategory::InvalidArgument, "dsm",
                          "output");
}

}  // namespace
}  // namespace penumbra
