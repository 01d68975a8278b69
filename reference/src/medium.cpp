// Participating media: where a ray is inside a region of fog, and the optical
// depth along it in closed form.
//
// k(p) = extinction + g . (p - centre) is linear in p, so along a ray p(t) =
// o + t d it is linear in t, and its integral over [a, b] is exact by the
// midpoint rule: integral of k |d| dt = |d| (b - a) k(p((a + b) / 2)).
#include <algorithm>
#include <cmath>

#include "penumbra/reference/tracer.h"

namespace penumbra::reference {

PreparedMedium PreparedMedium::from(const Medium& medium)
{
    PreparedMedium prepared;
    if (const auto* sphere = std::get_if<Sphere>(&medium.region)) {
        prepared.region = *sphere;
        prepared.center = sphere->center;
    } else {
        const OrientedBox box = OrientedBox::from(std::get<Box>(medium.region));
        prepared.region = box;
        prepared.center = box.center;
    }
    prepared.extinction = medium.extinction;
    prepared.gradient = medium.gradient;
    return prepared;
}

std::optional<Chord> PreparedMedium::chord(const Ray& ray) const
{
    return std::visit([&](const auto& shape) { return reference::chord(ray, shape); }, region);
}

double PreparedMedium::extinction_at(Vec3 p) const
{
    bool within;
    if (const auto* sphere = std::get_if<Sphere>(&region)) {
        within = dot(p - sphere->center, p - sphere->center) <= sphere->radius * sphere->radius;
    } else {
        const OrientedBox& box = std::get<OrientedBox>(region);
        const Vec3 q = abs(box.rotation.apply_inverse(p - box.center));
        within = q.x <= box.half_size.x && q.y <= box.half_size.y && q.z <= box.half_size.z;
    }
    return within ? extinction_within(p) : 0.0;
}

double PreparedMedium::extinction_within(Vec3 p) const
{
    // Validation keeps k >= 0 in the region; the clamp only absorbs rounding.
    return std::max(0.0, extinction + dot(gradient, p - center));
}

double PreparedMedium::optical_depth(const Ray& ray, double t0, double t1) const
{
    const auto span = chord(ray);
    if (!span) return 0;
    const double a = std::max(span->entry, t0), b = std::min(span->exit, t1);
    if (!(b > a)) return 0;
    return (b - a) * length(ray.direction) * extinction_within(ray.at(0.5 * (a + b)));
}

}  // namespace penumbra::reference
