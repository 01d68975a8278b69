// Exact signed distances of the analytic primitives (negative inside).
#include <algorithm>
#include <cmath>

#include "penumbra/reference/tracer.h"

namespace penumbra::reference {

double signed_distance(Vec3 p, const Plane& plane)
{
    // The normal is unit length, so the projection is the distance.
    return dot(p - plane.point, plane.normal);
}

double signed_distance(Vec3 p, const Sphere& sphere) { return length(p - sphere.center) - sphere.radius; }

double signed_distance(Vec3 p, const OrientedBox& box)
{
    // By symmetry work in the positive octant of the box frame: q is how far
    // p lies beyond each face plane. Outside (some q > 0) the nearest point
    // clamps the positive components, so the distance is |max(q, 0)|; inside
    // (all q <= 0) it is the nearest face, max(q) (negative).
    const Vec3 q = abs(box.rotation.apply_inverse(p - box.center)) - box.half_size;
    const Vec3 outside{std::fmax(q.x, 0.0), std::fmax(q.y, 0.0), std::fmax(q.z, 0.0)};
    return length(outside) + std::fmin(max_component(q), 0.0);
}

double signed_distance(Vec3 p, const Capsule& capsule)
{
    // Distance to the segment minus the radius; h is the clamped parameter of
    // the closest point on the segment, h = clamp((p - a).(b - a) / |b - a|^2, 0, 1).
    const Vec3 pa = p - capsule.a, ba = capsule.b - capsule.a;
    const double len2 = dot(ba, ba);
    const double h = len2 > 0 ? std::clamp(dot(pa, ba) / len2, 0.0, 1.0) : 0.0;
    return length(pa - ba * h) - capsule.radius;
}

double signed_distance(const Scene& scene, Vec3 p) { return PreparedScene(scene.primitives).signed_distance(p); }

}  // namespace penumbra::reference
