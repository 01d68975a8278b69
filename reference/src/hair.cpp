// Hair strands from a seed: chains of thin capsules rooted on a sphere's cap.
//
// Roots are uniform by area on the cap: for a cap of half-angle C about the
// axis, cos(theta) is uniform in [cos C, 1] (Archimedes: a sphere's area
// between two parallel planes is proportional to their distance) and phi in
// [0, 2 pi). A strand leaves the scalp along its normal; each segment's
// direction is the previous one plus droop / segments of a unit step down
// (-y) plus a random vector with components in [-curl, curl], normalised.
#include <cmath>
#include <numbers>

#include "penumbra/reference/scene.h"
#include "splitmix64.h"

namespace penumbra::reference {
namespace {

Vec3 root_normal(const Hair& hair, const Basis& cap, SplitMix64& random)
{
    const double cos_cap = std::cos(hair.cap_degrees * std::numbers::pi / 180);
    const double cos_theta = 1 - random.uniform() * (1 - cos_cap);
    const double sin_theta = std::sqrt(std::fmax(0.0, 1 - cos_theta * cos_theta));
    const double phi = 2 * std::numbers::pi * random.uniform();
    return cap.to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta});
}

Vec3 next_direction(const Hair& hair, Vec3 direction, SplitMix64& random)
{
    auto jitter = [&] { return hair.curl * (2 * random.uniform() - 1); };
    const Vec3 turned = direction + Vec3{0, -hair.droop / hair.segments, 0} + Vec3{jitter(), jitter(), jitter()};
    const double len = length(turned);
    return len > 1e-12 ? turned / len : direction;  // a turn that cancels the direction keeps it
}

}  // namespace

std::vector<Capsule> hair_strands(const Hair& hair)
{
    const Basis cap = basis_looking_along(hair.axis, {0, 0, 1});
    // Hash the seed first, as light_visibility does: nearby seeds then give
    // unrelated strands.
    SplitMix64 random(SplitMix64(hair.seed).next());
    const double step = hair.length / hair.segments;
    std::vector<Capsule> capsules;
    capsules.reserve(std::size_t(hair.strands) * std::size_t(hair.segments));
    for (int s = 0; s < hair.strands; ++s) {
        Vec3 direction = root_normal(hair, cap, random);
        Vec3 at = hair.center + direction * hair.scalp_radius;
        for (int k = 0; k < hair.segments; ++k) {
            direction = next_direction(hair, direction, random);
            const Vec3 end = at + direction * step;
            capsules.push_back(Capsule{at, end, hair.radius, hair.opacity});
            at = end;
        }
    }
    return capsules;
}

}  // namespace penumbra::reference
