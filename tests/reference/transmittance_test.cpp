// Transmittance through semi-transparent layers and participating media,
// against closed forms: products of 1 - opacity, Beer-Lambert through a slab,
// the chord of a sphere, and the antiderivative of a linear extinction.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

// A vertical segment from (x, y0, z) up to (x, y1, z): t in (0, 1).
Ray vertical(double x, double y0, double y1, double z = 0) { return {{x, y0, z}, {0, y1 - y0, 0}}; }

// A 10 m square sheet, 1 cm thick, at height y.
Box sheet(double y, double opacity) { return Box{{0, y, 0}, {10, 0.01, 10}, {}, opacity}; }

Medium fog_box(Vec3 center, Vec3 size, double k, Vec3 gradient = {})
{
    return Medium{Box{center, size, {}}, k, gradient};
}

TEST(Transmittance, OneSemiTransparentLayerTransmitsOneMinusItsOpacity)
{
    for (double opacity : {0.0, 0.25, 0.6, 1.0}) {
        const PreparedScene sheet_scene({sheet(2, opacity)});
        EXPECT_DOUBLE_EQ(sheet_scene.transmittance(vertical(0.3, 0, 4), 0, 1), 1 - opacity);
        // A plane is a half-space: the segment crosses its surface once.
        const PreparedScene plane_scene({Plane{{0, 2, 0}, {0, 1, 0}, opacity}});
        EXPECT_DOUBLE_EQ(plane_scene.transmittance(vertical(0.3, 0, 4), 0, 1), 1 - opacity);
        // A segment that stops short of the layer is not attenuated.
        EXPECT_EQ(sheet_scene.transmittance(vertical(0.3, 0, 1.5), 0, 1), 1.0);
    }
}

TEST(Transmittance, TwoLayersMultiply)
{
    const PreparedScene scene({sheet(1, 0.4), sheet(2, 0.25)});
    EXPECT_DOUBLE_EQ(scene.transmittance(vertical(0, 0, 3), 0, 1), 0.6 * 0.75);
    EXPECT_DOUBLE_EQ(scene.transmittance(vertical(0, 1.5, 3), 0, 1), 0.75);
    // An oblique segment crosses each sheet's two faces; each layer counts once.
    const Ray oblique{{-1, 0, 0.5}, {2, 3, -1}};
    EXPECT_DOUBLE_EQ(scene.transmittance(oblique, 0, 1), 0.6 * 0.75);
}

TEST(Transmittance, HomogeneousSlabIsBeerLambert)
{
    // k = 0.8 per metre in a slab 0.5 m thick: exp(-k h / cos(theta)) for a
    // segment at angle theta to the slab's normal.
    const double k = 0.8, h = 0.5;
    const PreparedScene scene({}, {fog_box({0, 2, 0}, {100, h, 100}, k)});
    EXPECT_NEAR(scene.transmittance(vertical(0.2, 0, 4), 0, 1), std::exp(-k * h), 1e-15);
    for (double degrees : {10.0, 35.0, 60.0}) {
        const double theta = degrees * M_PI / 180;
        const Ray ray{{0, 0, 0}, {4 * std::tan(theta), 4, 0}};
        EXPECT_NEAR(scene.transmittance(ray, 0, 1), std::exp(-k * h / std::cos(theta)), 1e-14) << degrees;
    }
    // Half inside: from the slab's middle upwards, half the thickness.
    EXPECT_NEAR(scene.transmittance(vertical(0, 2, 4), 0, 1), std::exp(-k * h / 2), 1e-15);
}

TEST(Transmittance, SphereOfFogFollowsTheChordLength)
{
    // A line at distance b from the centre of a sphere of radius R crosses
    // it along 2 sqrt(R^2 - b^2).
    const double R = 0.7, k = 1.3;
    const PreparedScene scene({}, {Medium{Sphere{{0, 2, 0}, R}, k, {}}});
    for (double b : {0.0, 0.2, 0.5, 0.69, 0.75}) {
        const double chord = b < R ? 2 * std::sqrt(R * R - b * b) : 0;
        EXPECT_NEAR(scene.transmittance(vertical(b, 0, 4), 0, 1), std::exp(-k * chord), 1e-14) << b;
        EXPECT_NEAR(scene.optical_depth({{b, 0, 0}, {0, 1, 0}}, 0, 10), k * chord, 1e-14) << b;
    }
    // From the centre outwards: one radius.
    EXPECT_NEAR(scene.transmittance(vertical(0, 2, 4), 0, 1), std::exp(-k * R), 1e-15);
}

TEST(Transmittance, LinearDensityMatchesItsAntiderivative)
{
    // k(y) = k0 + g (y - yc) inside a box spanning y in [1, 3]; a vertical
    // segment from y0 to y1 inside it has optical depth
    //   k0 (y1 - y0) + g/2 ((y1 - yc)^2 - (y0 - yc)^2).
    const double k0 = 0.9, g = 0.4, yc = 2;
    const PreparedScene scene({}, {fog_box({0, yc, 0}, {4, 2, 4}, k0, {0, g, 0})});
    auto exact = [&](double y0, double y1) {
        return k0 * (y1 - y0) + g / 2 * ((y1 - yc) * (y1 - yc) - (y0 - yc) * (y0 - yc));
    };
    EXPECT_NEAR(scene.optical_depth(vertical(0, 0, 5), 0, 1), exact(1, 3), 1e-14);
    EXPECT_NEAR(scene.optical_depth(vertical(0.5, 1.2, 2.7), 0, 1), exact(1.2, 2.7), 1e-14);
    EXPECT_NEAR(scene.transmittance(vertical(0.5, 1.5, 9), 0, 1), std::exp(-exact(1.5, 3)), 1e-15);
    // Along an oblique line through a turned box the extinction is linear in
    // the parameter, k(t) = a + b t; its integral over [t0, t1], times |d|,
    // against the closed form, with the box's entry and exit by hand: the box
    // turned 90 degrees about y is the same box, so its faces are y = 1, 3.
    const PreparedScene turned({}, {Medium{Box{{0, yc, 0}, {4, 2, 4}, {0, 90, 0}}, k0, {0.1, g, -0.2}}});
    const Ray ray{{-0.4, 0, 0.3}, {0.2, 1, 0.1}};
    const double t0 = 1, t1 = 3;  // y = t
    const Vec3 p0 = ray.at(t0), p1 = ray.at(t1);
    const Vec3 centre{0, yc, 0}, gradient{0.1, g, -0.2};
    const double ka = k0 + dot(gradient, p0 - centre), kb = k0 + dot(gradient, p1 - centre);
    EXPECT_NEAR(turned.optical_depth(ray, 0, 10), length(ray.direction) * (t1 - t0) * (ka + kb) / 2, 1e-13);
}

TEST(Transmittance, ExtinctionAtIsTheLinearFunctionInsideAndZeroOutside)
{
    const PreparedScene scene({}, {fog_box({0, 2, 0}, {2, 2, 2}, 1.0, {0.25, 0, 0}),
                                   Medium{Sphere{{0, 2, 0}, 0.5}, 0.5, {}}});
    EXPECT_DOUBLE_EQ(scene.extinction_at({0, 2, 0}), 1.5);
    EXPECT_DOUBLE_EQ(scene.extinction_at({0.8, 2, 0}), 1.2);
    EXPECT_EQ(scene.extinction_at({0, 3.5, 0}), 0.0);
}

TEST(Transmittance, OpaqueScenesGiveZeroOrOneAsOccludedDoes)
{
    const Scene scene = builtin_scene("overlap");
    const PreparedScene prepared(scene);
    int checked = 0;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) {
            const Vec3 from{-2 + 0.1 * i, 0.01, -2 + 0.1 * j};
            const Ray ray{from, scene.light.center - from};
            const double t = prepared.transmittance(ray, 0, 1);
            ASSERT_TRUE(t == 0.0 || t == 1.0);
            EXPECT_EQ(t == 0.0, prepared.occluded(ray, 0, 1));
            ++checked;
        }
    EXPECT_EQ(checked, 1600);
}

TEST(Transmittance, EventsAreOrderedAndEndAtTheFirstOpaqueSurface)
{
    // Upwards from the ground: fog from y = 0.5 to 2.5 (k = 0.3 + 0.1 (y - 1.5)),
    // a sheet of opacity 0.4 at 1, an opaque sphere from 2 to 2.4, a sheet at 3.
    Scene scene;
    scene.primitives = {sheet(1, 0.4), Sphere{{0, 2.2, 0}, 0.2}, sheet(3, 0.5)};
    scene.media = {fog_box({0, 1.5, 0}, {4, 2, 4}, 0.3, {0, 0.1, 0})};
    const PreparedScene prepared(scene);
    const auto events = prepared.events(vertical(0, 0, 4), 0, 1);  // t = y / 4
    using K = RayEvent::Kind;
    ASSERT_EQ(events.size(), 4u);
    EXPECT_EQ(events[0].kind, K::MediumEntry);
    EXPECT_NEAR(events[0].t, 0.5 / 4, 1e-15);
    EXPECT_NEAR(events[0].extinction, 0.2, 1e-15);
    EXPECT_EQ(events[1].kind, K::Surface);
    EXPECT_NEAR(events[1].t, 0.995 / 4, 1e-15);  // the sheet's lower face
    EXPECT_EQ(events[1].opacity, 0.4);
    EXPECT_EQ(events[1].index, 0);
    EXPECT_EQ(events[2].kind, K::Surface);
    EXPECT_NEAR(events[2].t, 2.0 / 4, 1e-15);
    EXPECT_EQ(events[2].opacity, 1.0);
    EXPECT_EQ(events[2].index, 1);
    // The fog is still open at the sphere: it exits there.
    EXPECT_EQ(events[3].kind, K::MediumExit);
    EXPECT_EQ(events[3].t, events[2].t);
    EXPECT_NEAR(events[3].extinction, 0.35, 1e-15);
    // Without the sphere: the fog's own exit, then the upper sheet.
    scene.primitives[1] = Sphere{{0, 2.2, 0}, 0.2, 0.0};
    const auto open = PreparedScene(scene).events(vertical(0, 0, 4), 0, 1);
    ASSERT_EQ(open.size(), 4u);
    EXPECT_EQ(open[2].kind, K::MediumExit);
    EXPECT_NEAR(open[2].t, 2.5 / 4, 1e-15);
    EXPECT_EQ(open[3].index, 2);
}

// A point light straight above the ground at height 4, over `scene`'s primitives.
Scene under_point_light(std::vector<Primitive> primitives, std::vector<Medium> media = {})
{
    Scene scene;
    scene.primitives = std::move(primitives);
    scene.primitives.push_back(Plane{{0, 0, 0}, {0, 1, 0}});
    scene.media = std::move(media);
    scene.light.shape = LightShape::Point;
    scene.light.center = {0, 4, 0};
    scene.light.normal = {0, -1, 0};
    scene.light.width = scene.light.height = 0;
    scene.light_camera.near = 0.5;
    scene.light_camera.far = 10;
    return scene;
}

TEST(Transmittance, PointLightTruthIsExactPerReceiver)
{
    // Ground receivers at x = -1.5 (under no sheet), -0.5 (under the upper
    // sheet only), 0.5 (under both) and 1.5 (under both and a fog ball of
    // radius 0.1 centred on its segment: chord 0.2). The segment from x to
    // the light crosses height y at x (1 - y / 4): the sheets span x in
    // [-0.25, 2.25] at y = 1 and [-0.3, 1.3] at y = 2, and the ball sits at
    // (0.375, 3, 0), 0.25 m from the next segment.
    const Scene scene = under_point_light(
        {Box{{1, 1, 0}, {2.5, 0.01, 2}, {}, 0.4}, Box{{0.5, 2, 0}, {1.6, 0.01, 2}, {}, 0.25}},
        {Medium{Sphere{{0.375, 3, 0}, 0.1}, 2, {}}});
    const double xs[] = {-1.5, -0.5, 0.5, 1.5};
    Receivers r = Receivers::allocate(4, 1);
    for (int i = 0; i < 4; ++i) {
        r.world_position.at(0, i, 0) = float(xs[i]);
        r.normal.at(1, i, 0) = 1;
        r.hit.at(0, i, 0) = r.mask.at(0, i, 0) = 1;
    }
    const Image y = ground_truth(scene, r, {4});
    const double expected[] = {1, 0.75, 0.6 * 0.75, 0.6 * 0.75 * std::exp(-2 * 0.2)};
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(y.at(0, i, 0), expected[i], 1e-6) << xs[i];
}

TEST(Transmittance, ShadowMapStoresTheFirstSurfaceOfAnyOpacityButNotFog)
{
    // Overhead point light at 4 m, near 0.5, far 10: z = (d - 0.5) / 9.5.
    const auto z = [](double d) { return float((d - 0.5) / 9.5); };
    const Scene layered = under_point_light({sheet(2, 0.3)});
    EXPECT_FLOAT_EQ(render_shadow_map(layered, 1, 1).at(0, 0, 0), z(4 - 2.005));
    const Scene foggy = under_point_light({}, {fog_box({0, 2, 0}, {4, 1, 4}, 5)});
    EXPECT_FLOAT_EQ(render_shadow_map(foggy, 1, 1).at(0, 0, 0), z(4));
    // Opacity 0: not there for the map, the receivers or the light.
    const Scene invisible = under_point_light({sheet(2, 0.0)});
    EXPECT_FLOAT_EQ(render_shadow_map(invisible, 1, 1).at(0, 0, 0), z(4));
}

}  // namespace
}  // namespace penumbra::reference
