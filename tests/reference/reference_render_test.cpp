// Shadow maps and receivers: ranges, conventions and consistency.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/error.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

// A light straight above the origin looking down, over `primitives`.
Scene overhead_scene(std::vector<Primitive> primitives, double height = 5)
{
    Scene scene;
    scene.name = "overhead";
    scene.primitives = std::move(primitives);
    scene.light.center = {0, height, 0};
    scene.light.normal = {0, -1, 0};
    scene.light_camera = LightCamera{Projection::Perspective, 1, 9, 60, 10};
    scene.view = ViewCamera{{0, 4, 3}, {0, 0, 0}, {0, 1, 0}, 40};
    return scene;
}

void expect_in_unit_range(const Image& image, int channel, const std::string& what)
{
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const float v = image.at(channel, x, y);
            ASSERT_TRUE(v >= 0 && v <= 1) << what << " (" << x << ", " << y << ") = " << v;
        }
}

TEST(ReferenceRender, EveryBuiltinSceneRendersSmallInRange)
{
    for (const std::string& name : builtin_scene_names(SceneSet::All)) {
        const Scene scene = builtin_scene(name);
        const Image map = render_shadow_map(scene, 64, 48);
        EXPECT_NO_THROW(require_finite(map, "test", name + " shadow map"));
        expect_in_unit_range(map, 0, name + " shadow map");
        const Receivers receivers = render_receivers(scene, 40, 30);
        for (const Image* image : {&receivers.light_uvz, &receivers.world_position, &receivers.normal,
                                   &receivers.view_depth, &receivers.mask})
            EXPECT_NO_THROW(require_finite(*image, "test", name + " receivers"));
        for (int c = 0; c < 3; ++c) expect_in_unit_range(receivers.light_uvz, c, name + " light_uvz");
        double valid = 0;
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < 40; ++x) {
                valid += receivers.mask.at(0, x, y);
                EXPECT_LE(receivers.mask.at(0, x, y), receivers.hit.at(0, x, y));
            }
        // The scenes are framed so that the view sees (almost) only what the light's frustum covers.
        EXPECT_GT(valid / (40 * 30), 0.85) << name;
    }
}

TEST(ReferenceRender, GroundUnderAnOverheadLightHasOneDepth)
{
    const Image map = render_shadow_map(overhead_scene({Plane{{0, 0, 0}, {0, 1, 0}}}), 7, 5);
    // d = 5 everywhere on a plane perpendicular to the axis: z = (5 - 1) / (9 - 1).
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 7; ++i) EXPECT_FLOAT_EQ(map.at(0, i, j), 0.5f);
}

TEST(ReferenceRender, SphereTopOnTheAxisAndEmptyTexelsAtFar)
{
    const Image map = render_shadow_map(overhead_scene({Sphere{{0, 2, 0}, 1}}), 65, 65);
    EXPECT_FLOAT_EQ(map.at(0, 32, 32), float((5.0 - 3.0 - 1.0) / 8.0));  // top at y = 3, d = 2
    EXPECT_EQ(map.at(0, 0, 0), 1.0f);                                      // nothing there: the far plane
}

TEST(ReferenceRender, OrthographicTexelsCoverTheirFootprint)
{
    Scene scene = overhead_scene({Plane{{0, 0, 0}, {0, 1, 0}}, Box{{0, 1, 0}, {2, 2, 2}, {}}});
    scene.light.up = {0, 0, -1};  // s = +x, t = +z
    scene.light_camera = LightCamera{Projection::Orthographic, 1, 9, 60, 4};
    const Image map = render_shadow_map(scene, 8, 8);
    // Texel centres at x = (i + 1/2) / 8 * 4 - 2 = -1.75, -1.25, ...: texels 2..5 lie over the box.
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
            const bool over_box = i >= 2 && i <= 5 && j >= 2 && j <= 5;
            EXPECT_FLOAT_EQ(map.at(0, i, j), over_box ? 0.25f : 0.5f) << i << ", " << j;
        }
}

TEST(ReferenceRender, ReceiversAgreeWithTheLightsRays)
{
    // A ray from the light through a valid receiver's (u, v) meets its first
    // surface no farther than the receiver, and at the receiver when lit.
    const Scene scene = builtin_scene("contact");
    const Receivers receivers = render_receivers(scene, 32, 24);
    const LightProjection projection(scene);
    const PreparedScene prepared(scene.primitives);
    int reached = 0;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) {
            if (receivers.mask.at(0, x, y) == 0) continue;
            const Vec3 world{receivers.world_position.at(0, x, y), receivers.world_position.at(1, x, y),
                             receivers.world_position.at(2, x, y)};
            const Vec3 uvz = projection.project(world);
            EXPECT_NEAR(uvz.z, receivers.light_uvz.at(2, x, y), 1e-6);
            const auto hit = prepared.closest_hit(projection.ray_through(uvz.x, uvz.y), 0, 1e9);
            ASSERT_TRUE(hit);
            const double receiver_depth = projection.depth_of(uvz.z);
            EXPECT_LE(hit->t, receiver_depth * (1 + 1e-6));
            reached += hit->t > receiver_depth * (1 - 1e-6);
        }
    EXPECT_GT(reached, 32 * 24 / 2);  // most of the view is lit ground
}

TEST(ReferenceRender, PixelsThatSeeNothingAreFlagged)
{
    Scene scene = overhead_scene({Sphere{{0, 0, 0}, 1}});
    scene.view = ViewCamera{{0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 90};  // the sphere, and sky around it
    const Receivers r = render_receivers(scene, 16, 16);
    EXPECT_EQ(r.hit.at(0, 0, 0), 0.0f);
    EXPECT_EQ(r.mask.at(0, 0, 0), 0.0f);
    EXPECT_EQ(r.light_uvz.at(2, 0, 0), 1.0f);
    EXPECT_EQ(r.view_depth.at(0, 0, 0), 0.0f);
    EXPECT_EQ(r.hit.at(0, 8, 8), 1.0f);
    EXPECT_NEAR(r.view_depth.at(0, 8, 8), 3.04, 0.02);  // just off the axis: 3 + a little
    const Vec3 n{r.normal.at(0, 8, 8), r.normal.at(1, 8, 8), r.normal.at(2, 8, 8)};
    EXPECT_NEAR(length(n), 1, 1e-6);
}

TEST(ReferenceRender, BadSizesAreErrors)
{
    const Scene scene = builtin_scene("contact");
    EXPECT_THROW(render_shadow_map(scene, 0, 4), Error);
    EXPECT_THROW(render_receivers(scene, 4, -1), Error);
    Scene broken = scene;
    broken.light_camera.far = broken.light_camera.near;
    EXPECT_THROW(render_shadow_map(broken, 4, 4), Error);
}

}  // namespace
}  // namespace penumbra::reference
