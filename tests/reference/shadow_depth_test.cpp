// First, midpoint and second-surface shadow maps (Woo 1992) against the
// closed form of a slab of known thickness over the ground, at odd sizes.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/error.h"
#include "penumbra/reference/render.h"

namespace penumbra::reference {
namespace {

// An orthographic light 5 m above the origin looking down (s = +x, t = +z),
// covering x, z in [-2, 2], near 1 and far 9: a point at height y has axial
// depth d = 5 - y and z = (d - 1) / 8. Under it the ground (y = 0) and a slab
// 2 m wide, from y = 0.75 to y = 1.25 (0.5 m thick), with a 0.75 m gap.
Scene slab_over_ground()
{
    Scene scene;
    scene.name = "slab";
    scene.primitives = {Plane{{0, 0, 0}, {0, 1, 0}}, Box{{0, 1, 0}, {2, 0.5, 2}, {}}};
    scene.light.center = {0, 5, 0};
    scene.light.normal = {0, -1, 0};
    scene.light.up = {0, 0, -1};
    scene.light_camera = LightCamera{Projection::Orthographic, 1, 9, 60, 4};
    scene.view = ViewCamera{{0, 4, 3}, {0, 0, 0}, {0, 1, 0}, 40};
    return scene;
}

double z_at_height(double y) { return (5 - y - 1) / 8; }

// The closed form: over the slab the first two crossings are its top and
// bottom; beside it the ground is the only one, and the far plane (z = 1)
// stands in for the missing second (render.h).
double expected(double x, double zw, ShadowDepth depth)
{
    const bool over_slab = std::fabs(x) < 1 && std::fabs(zw) < 1;
    const double first = over_slab ? z_at_height(1.25) : z_at_height(0);
    const double second = over_slab ? z_at_height(0.75) : 1.0;
    switch (depth) {
    case ShadowDepth::First: return first;
    case ShadowDepth::Midpoint: return 0.5 * (first + second);
    case ShadowDepth::Second: return second;
    }
    return -1;
}

TEST(ShadowDepth, SlabOverGroundMatchesTheClosedFormAtOddSizes)
{
    const Scene scene = slab_over_ground();
    // Sizes whose texel centres never fall on the slab's edges (x = +-1).
    const int sizes[][2] = {{1, 1}, {7, 3}, {3, 7}, {9, 5}, {17, 17}};
    for (const ShadowDepth depth : {ShadowDepth::First, ShadowDepth::Midpoint, ShadowDepth::Second})
        for (const auto& size : sizes) {
            const int w = size[0], h = size[1];
            const Image map = render_shadow_map(scene, w, h, depth);
            ASSERT_EQ(map.width(), w);
            ASSERT_EQ(map.height(), h);
            for (int j = 0; j < h; ++j)
                for (int i = 0; i < w; ++i) {
                    const double x = (i + 0.5) / w * 4 - 2, zw = (j + 0.5) / h * 4 - 2;
                    EXPECT_NEAR(map.at(0, i, j), expected(x, zw, depth), 1e-6)
                        << shadow_depth_name(depth) << " " << w << "x" << h << " texel " << i << ", " << j;
                }
        }
}

TEST(ShadowDepth, FirstIsTheDefault)
{
    const Scene scene = slab_over_ground();
    const Image implicit = render_shadow_map(scene, 7, 3);
    const Image first = render_shadow_map(scene, 7, 3, ShadowDepth::First);
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 7; ++i) EXPECT_EQ(implicit.at(0, i, j), first.at(0, i, j));
}

TEST(ShadowDepth, SphereOnTheAxisInPerspective)
{
    // A sphere of radius 1 at height 2 under a light at height 5: the axial
    // ray crosses its top at d = 2 and its bottom at d = 4; z = (d - 1) / 8.
    Scene scene = slab_over_ground();
    scene.primitives = {Sphere{{0, 2, 0}, 1}};
    scene.light_camera = LightCamera{Projection::Perspective, 1, 9, 60, 10};
    const Image first = render_shadow_map(scene, 65, 65, ShadowDepth::First);
    const Image mid = render_shadow_map(scene, 65, 65, ShadowDepth::Midpoint);
    const Image second = render_shadow_map(scene, 65, 65, ShadowDepth::Second);
    EXPECT_FLOAT_EQ(first.at(0, 32, 32), 1.0f / 8);
    EXPECT_FLOAT_EQ(mid.at(0, 32, 32), 2.0f / 8);
    EXPECT_FLOAT_EQ(second.at(0, 32, 32), 3.0f / 8);
    // A ray that meets nothing stores the far plane in every mode.
    for (const Image* map : {&first, &mid, &second}) EXPECT_EQ(map->at(0, 0, 0), 1.0f);
}

TEST(ShadowDepth, NamesRoundTripAndBadNamesNameTheParameter)
{
    for (const ShadowDepth depth : {ShadowDepth::First, ShadowDepth::Midpoint, ShadowDepth::Second})
        EXPECT_EQ(shadow_depth_from_name(shadow_depth_name(depth), "depth"), depth);
    try {
        shadow_depth_from_name("third", "--depth");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.category(), ErrorCategory::InvalidArgument);
        EXPECT_EQ(e.parameter(), "--depth");
        EXPECT_NE(std::string(e.what()).find("midpoint"), std::string::npos) << e.what();
    }
    EXPECT_THROW(render_shadow_map(slab_over_ground(), 4, 4, ShadowDepth(7)), Error);
}

}  // namespace
}  // namespace penumbra::reference
