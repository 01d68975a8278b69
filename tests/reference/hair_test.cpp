// Hair: strands generated from a seed are the same for the same seed, are
// continuous chains rooted on the scalp's cap, and are thinner than a texel.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/reference/light_space.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

Hair small_hair(std::uint64_t seed)
{
    return Hair{.center = {0.5, 1, -0.2}, .scalp_radius = 0.4, .axis = {0.3, 1, 0}, .cap_degrees = 50,
                .strands = 200, .segments = 5, .length = 0.25, .radius = 0.001, .droop = 0.8, .curl = 0.2,
                .seed = seed};
}

bool same(const std::vector<Capsule>& a, const std::vector<Capsule>& b)
{
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!(a[i].a == b[i].a && a[i].b == b[i].b && a[i].radius == b[i].radius)) return false;
    return true;
}

TEST(Hair, SameSeedSameStrandsOtherSeedOthers)
{
    EXPECT_TRUE(same(hair_strands(small_hair(7)), hair_strands(small_hair(7))));
    EXPECT_FALSE(same(hair_strands(small_hair(7)), hair_strands(small_hair(8))));
}

TEST(Hair, StrandsAreChainsRootedOnTheCap)
{
    const Hair h = small_hair(3);
    const std::vector<Capsule> capsules = hair_strands(h);
    ASSERT_EQ(capsules.size(), std::size_t(h.strands * h.segments));
    const Vec3 axis = normalize(h.axis);
    const double cos_cap = std::cos(h.cap_degrees * M_PI / 180);
    for (int s = 0; s < h.strands; ++s) {
        const Capsule& root = capsules[std::size_t(s * h.segments)];
        EXPECT_NEAR(length(root.a - h.center), h.scalp_radius, 1e-12) << s;
        EXPECT_GE(dot(normalize(root.a - h.center), axis), cos_cap - 1e-12) << s;
        for (int k = 0; k < h.segments; ++k) {
            const Capsule& c = capsules[std::size_t(s * h.segments + k)];
            EXPECT_NEAR(length(c.b - c.a), h.length / h.segments, 1e-12);
            EXPECT_EQ(c.radius, h.radius);
            if (k > 0) {
                EXPECT_EQ(c.a, capsules[std::size_t(s * h.segments + k - 1)].b);
            }
        }
    }
}

TEST(Hair, TheHairSceneStrandsAreThinnerThanATexel)
{
    // A texel of the scene's design map at a strand's depth d spans
    // texture_unit_length(d) / map_size; a strand's width is its diameter.
    const Scene scene = builtin_scene("hair");
    const LightProjection projection(scene);
    const Basis frame = basis_looking_along(scene.light.normal, scene.light.up);
    double widest = 0;
    for (const Capsule& c : hair_strands(scene.hair.at(0))) {
        const double d = std::fmin(dot(c.a - scene.light.center, frame.n), dot(c.b - scene.light.center, frame.n));
        const double texel = projection.texture_unit_length(d) / scene.map_size;
        widest = std::fmax(widest, 2 * c.radius / texel);
    }
    EXPECT_LT(widest, 0.25);  // measured: about a seventh of a texel
    EXPECT_GT(widest, 0.0);
}

TEST(Hair, StrandsAreSurfacesAfterThePrimitives)
{
    Scene scene = builtin_scene("hair");
    const std::vector<Primitive> surfaces = scene_surfaces(scene);
    ASSERT_EQ(surfaces.size(), scene.primitives.size() + 4000u * 6u);
    // A ray across a strand's first segment, from 1 mm off its axis, hits
    // that strand (no other lies so close).
    const Capsule& c = std::get<Capsule>(surfaces[scene.primitives.size()]);
    const Vec3 mid = (c.a + c.b) * 0.5;
    const Vec3 side = normalize(cross(c.b - c.a, {0.3, 0.1, 1}));
    const auto hit = PreparedScene(scene).closest_hit({mid + side * 0.001, -side}, 0, 1);
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->primitive, int(scene.primitives.size()));
    EXPECT_NEAR(hit->t, 0.001 - c.radius, 1e-9);
}

}  // namespace
}  // namespace penumbra::reference
