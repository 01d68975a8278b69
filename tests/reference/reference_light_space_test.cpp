// Light space: the projection, the PCSS light size, and sub-texel light moves.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "penumbra/error.h"
#include "penumbra/reference/light_space.h"

namespace penumbra::reference {
namespace {

Scene overhead_scene(Projection projection)
{
    Scene scene;
    scene.primitives = {Plane{{0, 0, 0}, {0, 1, 0}}, Box{{0, 2, 0}, {1, 0.1, 1}, {}}};
    scene.light.center = {0, 6, 0};
    scene.light.normal = {0, -1, 0};
    scene.light.width = scene.light.height = 0.8;
    scene.light_camera = LightCamera{projection, 0.5, 10.5, 50, 8};
    return scene;
}

TEST(ReferenceLightSpace, BasisIsRightHandedAndOrthonormal)
{
    for (Vec3 forward : {Vec3{0, -1, 0}, Vec3{1, -0.1, 0}, Vec3{0.3, -0.8, 0.5}, Vec3{0, 0, 1}})
        for (Vec3 up : {Vec3{0, 1, 0}, Vec3{0, 0, -1}, forward}) {
            const Basis b = basis_looking_along(forward, up);
            EXPECT_NEAR(length(b.s), 1, 1e-12);
            EXPECT_NEAR(length(b.t), 1, 1e-12);
            EXPECT_NEAR(dot(b.s, b.t), 0, 1e-12);
            EXPECT_NEAR(length(cross(b.s, b.t) - b.n), 0, 1e-12);
            EXPECT_NEAR(length(b.n - normalize(forward)), 0, 1e-12);
        }
    // Looking down with the default fallback: u along +x, v along +z.
    const Basis down = basis_looking_along({0, -1, 0}, {0, 1, 0});
    EXPECT_NEAR(length(down.s - Vec3{1, 0, 0}), 0, 1e-12);
    EXPECT_NEAR(length(down.t - Vec3{0, 0, 1}), 0, 1e-12);
}

TEST(ReferenceLightSpace, ProjectionInvertsTheTexelRays)
{
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        Scene scene = builtin_scene("contact");
        scene.light_camera.projection = projection;
        const LightProjection light(scene);
        for (double u : {0.0, 0.25, 0.7, 1.0})
            for (double v : {0.1, 0.5, 0.95})
                for (double depth : {0.5, 3.0, 20.0}) {
                    const Vec3 uvz = light.project(light.ray_through(u, v).at(depth));
                    EXPECT_NEAR(uvz.x, u, 1e-12);
                    EXPECT_NEAR(uvz.y, v, 1e-12);
                    EXPECT_NEAR(uvz.z, light.z_of(depth), 1e-12);
                    EXPECT_NEAR(light.depth_of(uvz.z), depth, 1e-12);
                }
    }
}

TEST(ReferenceLightSpace, PenumbraWidthIsTheConeAtTheBlocker)
{
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        const Scene scene = overhead_scene(projection);
        const LightProjection light(scene);
        const double d_r = 6, d_b = 3.5;  // ground and a blocker 2.5 m above it
        // The receiver's cone to the light, cut at the blocker's depth, in world units.
        const double cone = 0.8 * (d_r - d_b) / d_r;
        const double expected = cone / light.texture_unit_length(d_b);
        EXPECT_NEAR(penumbra_width(scene, light.z_of(d_r), light.z_of(d_b)), expected, 1e-12);
        EXPECT_EQ(penumbra_width(scene, 0.3, 0.4), 0.0);
    }
    // Perspective only: the same width is the receiver-plane penumbra
    // L (d_r - d_b) / d_b seen at the receiver's depth (projective invariance).
    const Scene scene = overhead_scene(Projection::Perspective);
    const LightProjection light(scene);
    EXPECT_NEAR(penumbra_width(scene, light.z_of(6), light.z_of(3.5)),
                0.8 * (6 - 3.5) / 3.5 / light.texture_unit_length(6), 1e-12);
}

TEST(ReferenceLightSpace, LightSizeMakesThePcssEstimateExact)
{
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        const Scene scene = overhead_scene(projection);
        for (double z_r : {0.4, 0.55, 0.9})
            for (double z_b : {0.05, 0.2, 0.35}) {
                const double w = light_size_at(scene, z_r, z_b) * (z_r - z_b) / z_b;
                EXPECT_NEAR(w, penumbra_width(scene, z_r, z_b), 1e-12);
            }
    }
    EXPECT_THROW(light_size_at(overhead_scene(Projection::Perspective), 1.5, 0.2), Error);
    // The near-plane width: 0.8 m over the 2 near tan(25 deg) wide near plane.
    const Scene perspective = overhead_scene(Projection::Perspective);
    EXPECT_NEAR(light_width_at_near_plane(perspective), 0.8 / (2 * 0.5 * std::tan(25 * std::numbers::pi / 180)), 1e-12);
    EXPECT_NEAR(light_width_at_near_plane(overhead_scene(Projection::Orthographic)), 0.1, 1e-12);
}

TEST(ReferenceLightSpace, ReferenceDepthsAreTheGroundAndTheBlocker)
{
    const Scene scene = overhead_scene(Projection::Perspective);
    const LightProjection light(scene);
    const ReferenceDepths depths = reference_depths(scene);
    EXPECT_NEAR(depths.z_receiver, light.z_of(6), 1e-12);
    EXPECT_NEAR(depths.z_blocker, light.z_of(6 - 2.05), 1e-12);  // the slab's top face
    EXPECT_NEAR(light_size(scene), light_size_at(scene, depths.z_receiver, depths.z_blocker), 1e-15);
    for (const std::string& name : builtin_scene_names()) {
        const double size = light_size(builtin_scene(name));
        EXPECT_TRUE(std::isfinite(size) && size > 0 && size < 1) << name << ": " << size;
    }
}

TEST(ReferenceLightSpace, ShiftMovesReceiversBySubTexelSteps)
{
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        const Scene scene = overhead_scene(projection);
        const Vec3 receiver{0.7, 0, -0.4};  // on the ground: the reference receiver depth
        const Vec3 before = LightProjection(scene).project(receiver);
        const Scene moved = shift_light(scene, 0.25, -0.5, 512, 256);
        const Vec3 after = LightProjection(moved).project(receiver);
        EXPECT_NEAR((after.x - before.x) * 512, -0.25, 1e-9);
        EXPECT_NEAR((after.y - before.y) * 256, 0.5, 1e-9);
        EXPECT_NEAR(after.z, before.z, 1e-12);
    }
    const auto frames = flicker_frames(overhead_scene(Projection::Perspective), 4, 256, 256);
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_EQ(frames[0].light.center, overhead_scene(Projection::Perspective).light.center);
    const Vec3 step = frames[1].light.center - frames[0].light.center;
    EXPECT_NEAR(length(frames[3].light.center - frames[0].light.center), 3 * length(step), 1e-12);
    EXPECT_THROW(flicker_frames(overhead_scene(Projection::Perspective), 0, 256, 256), Error);
}

}  // namespace
}  // namespace penumbra::reference
