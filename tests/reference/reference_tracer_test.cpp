// Ray-primitive intersections and signed distances against hand-worked values.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

constexpr double kTight = 1e-12;

void expect_near(Vec3 a, Vec3 b, double tolerance)
{
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(ReferenceTracer, SphereFromOutsideAndInside)
{
    const Sphere sphere{{0, 0, 5}, 1};
    const auto entry = intersect(Ray{{0, 0, 0}, {0, 0, 1}}, sphere, 0, 100);
    ASSERT_TRUE(entry);
    EXPECT_NEAR(entry->t, 4, kTight);
    expect_near(entry->normal, {0, 0, -1}, kTight);
    // From the centre the first crossing is the way out.
    const auto exit = intersect(Ray{{0, 0, 5}, {0, 0, 2}}, sphere, 0, 100);
    ASSERT_TRUE(exit);
    EXPECT_NEAR(exit->t, 0.5, kTight);
    expect_near(exit->normal, {0, 0, 1}, kTight);
    EXPECT_FALSE(intersect(Ray{{0, 1.001, 0}, {0, 0, 1}}, sphere, 0, 100));
    EXPECT_FALSE(intersect(Ray{{0, 0, 0}, {0, 0, 1}}, sphere, 0, 3.9));  // beyond t_max
}

TEST(ReferenceTracer, RotatedBoxHitsItsTurnedFace)
{
    // A unit cube turned 45 degrees about y: along x its corner reaches sqrt(1/2).
    const OrientedBox box = OrientedBox::from(Box{{0, 0, 0}, {1, 1, 1}, {0, 45, 0}});
    const auto hit = intersect(Ray{{-3, 0.2, 0}, {1, 0, 0}}, box, 0, 100);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 3 - std::sqrt(0.5), 1e-12);
    // The face hit has an outward normal with a negative x component, at 45 degrees.
    EXPECT_NEAR(std::fabs(hit->normal.x), std::sqrt(0.5), 1e-12);
    EXPECT_LT(hit->normal.x, 0);
    EXPECT_NEAR(length(hit->normal), 1, 1e-12);
    // An axis-parallel ray just outside a face misses, just inside hits.
    const OrientedBox axis_aligned = OrientedBox::from(Box{{0, 0, 0}, {2, 2, 2}, {}});
    EXPECT_FALSE(intersect(Ray{{1.0000001, -5, 0}, {0, 1, 0}}, axis_aligned, 0, 100));
    EXPECT_TRUE(intersect(Ray{{0.9999999, -5, 0}, {0, 1, 0}}, axis_aligned, 0, 100));
}

TEST(ReferenceTracer, CapsuleSideAndCaps)
{
    const Capsule capsule{{0, 0, 0}, {0, 2, 0}, 0.5};
    const auto side = intersect(Ray{{-3, 1, 0}, {1, 0, 0}}, capsule, 0, 100);
    ASSERT_TRUE(side);
    EXPECT_NEAR(side->t, 2.5, kTight);
    expect_near(side->normal, {-1, 0, 0}, kTight);
    const auto cap = intersect(Ray{{0, 5, 0}, {0, -1, 0}}, capsule, 0, 100);
    ASSERT_TRUE(cap);
    EXPECT_NEAR(cap->t, 2.5, kTight);
    expect_near(cap->normal, {0, 1, 0}, kTight);
    // Past the end the cap is rounded: at y = 2.4 it reaches only x = -sqrt(0.5^2 - 0.4^2) = -0.3.
    const auto rounded = intersect(Ray{{-3, 2.4, 0}, {1, 0, 0}}, capsule, 0, 100);
    ASSERT_TRUE(rounded);
    EXPECT_NEAR(rounded->t, 2.7, 1e-12);
    EXPECT_FALSE(intersect(Ray{{-3, 2.51, 0}, {1, 0, 0}}, capsule, 0, 100));
}

TEST(ReferenceTracer, CapsuleFromInsideCrossesOnlyItsSurface)
{
    // From the middle along the axis, the upper cap's sphere is entered at
    // y = 1.5, inside the cylinder: not a crossing. The surface is at 2.5.
    const Capsule capsule{{0, 0, 0}, {0, 2, 0}, 0.5};
    const auto exit = intersect(Ray{{0, 1, 0}, {0, 1, 0}}, capsule, 0, 100);
    ASSERT_TRUE(exit);
    EXPECT_NEAR(exit->t, 1.5, kTight);
    expect_near(exit->normal, {0, 1, 0}, kTight);
    // Slantwise from inside: the exit is where the distance to the axis segment is the radius.
    const Ray slant{{0.1, 0.2, 0}, normalize(Vec3{0.3, 1, 0.2})};
    const auto out = intersect(slant, capsule, 0, 100);
    ASSERT_TRUE(out);
    EXPECT_NEAR(signed_distance(slant.at(out->t), capsule), 0, 1e-12);
}

TEST(ReferenceTracer, PlaneIsTheHalfSpaceBelow)
{
    const Plane plane{{0, 1, 0}, {0, 1, 0}};
    const auto hit = intersect(Ray{{0, 3, 0}, {0, -2, 0}}, plane, 0, 100);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1, kTight);
    EXPECT_FALSE(intersect(Ray{{0, 3, 0}, {1, 0, 0}}, plane, 0, 100));
    EXPECT_DOUBLE_EQ(signed_distance({5, -2, 7}, plane), -3);
}

TEST(ReferenceTracer, SignedDistancesMatchClosedForms)
{
    EXPECT_NEAR(signed_distance({0, 3, 0}, Sphere{{0, 0, 0}, 1}), 2, kTight);
    EXPECT_NEAR(signed_distance({0, 0.25, 0}, Sphere{{0, 0, 0}, 1}), -0.75, kTight);
    const OrientedBox box = OrientedBox::from(Box{{0, 0, 0}, {2, 2, 2}, {}});
    EXPECT_NEAR(signed_distance({3, 0, 0}, box), 2, kTight);
    EXPECT_NEAR(signed_distance({2, 2, 0}, box), std::sqrt(2.0), kTight);  // nearest point is an edge
    EXPECT_NEAR(signed_distance({0.5, 0, 0}, box), -0.5, kTight);
    const OrientedBox turned = OrientedBox::from(Box{{0, 0, 0}, {2, 2, 2}, {0, 0, 45}});
    EXPECT_NEAR(signed_distance({0, 3, 0}, turned), 3 - std::sqrt(2.0), 1e-12);  // a corner points up
    const Capsule capsule{{0, 0, 0}, {0, 2, 0}, 0.5};
    EXPECT_NEAR(signed_distance({2, 1, 0}, capsule), 1.5, kTight);
    EXPECT_NEAR(signed_distance({0, 4, 0}, capsule), 1.5, kTight);
    EXPECT_NEAR(signed_distance({0, 1, 0}, capsule), -0.5, kTight);
}

TEST(ReferenceTracer, SceneDistanceIsZeroWhereRaysHit)
{
    const Scene scene = builtin_scene("contact");
    const PreparedScene prepared(scene.primitives);
    EXPECT_EQ(prepared.size(), scene.primitives.size());
    // Rays fanned from the view camera: every hit point lies on the zero set.
    for (int k = 0; k < 50; ++k) {
        const Vec3 direction = normalize(scene.view.target - scene.view.position) +
                               Vec3{0.02 * (k % 7 - 3), 0.02 * (k % 5 - 2), 0.02 * (k % 3 - 1)};
        const Ray ray{scene.view.position, direction};
        const auto hit = prepared.closest_hit(ray, 0, 1e9);
        ASSERT_TRUE(hit);
        EXPECT_NEAR(prepared.signed_distance(ray.at(hit->t)), 0, 1e-9);
    }
    EXPECT_NEAR(signed_distance(scene, {0, 1, 0}), -1, kTight);  // the sphere's centre
    EXPECT_NEAR(signed_distance(scene, {0, 10, 0}), 8, kTight);  // above the sphere's top
}

TEST(ReferenceTracer, HierarchyAgreesWithBruteForce)
{
    // Every closest hit through the hierarchy equals the nearest of the
    // per-primitive intersections.
    const Scene scene = builtin_scene("large");
    const PreparedScene prepared(scene.primitives);
    for (int k = 0; k < 400; ++k) {
        const Ray ray{scene.light.center, Vec3{(k % 20 - 9.5) * 12, -300, (k / 20 - 9.5) * 12} + Vec3{60, 0, 40}};
        double nearest = INFINITY;
        for (const Primitive& p : scene.primitives) {
            std::optional<Hit> hit;
            if (const auto* plane = std::get_if<Plane>(&p)) hit = intersect(ray, *plane, 0, 1e9);
            if (const auto* box = std::get_if<Box>(&p)) hit = intersect(ray, OrientedBox::from(*box), 0, 1e9);
            if (const auto* capsule = std::get_if<Capsule>(&p)) hit = intersect(ray, *capsule, 0, 1e9);
            if (hit) nearest = std::fmin(nearest, hit->t);
        }
        const auto hit = prepared.closest_hit(ray, 0, 1e9);
        ASSERT_TRUE(hit);
        EXPECT_EQ(hit->t, nearest) << k;
        EXPECT_EQ(prepared.occluded(ray, 0, nearest * 0.999), false) << k;
        EXPECT_EQ(prepared.occluded(ray, 0, nearest * 1.001), true) << k;
    }
}

}  // namespace
}  // namespace penumbra::reference
