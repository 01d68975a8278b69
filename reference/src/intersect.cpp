// Ray-primitive intersections (see penumbra/reference/tracer.h for the contract: the
// first surface crossing in (t_min, t_max), entering or leaving the solid).
#include <algorithm>
#include <cmath>

#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

bool inside(double t, double t_min, double t_max) { return t > t_min && t < t_max; }

// Roots of a t^2 + 2 half_b t + c = 0, smaller first. Uses q = -(half_b +
// sign(half_b) sqrt(disc)) so that neither root is the difference of two
// nearly equal numbers (Numerical Recipes, section 5.6).
struct Roots {
    bool real = false;
    double t0 = 0, t1 = 0;
};

Roots solve_quadratic(double a, double half_b, double c, double discriminant)
{
    if (!(discriminant >= 0) || a <= 0) return {};
    const double root = std::sqrt(discriminant);
    const double q = -(half_b + std::copysign(root, half_b));
    if (q == 0) return {true, 0, 0};  // half_b = 0 and c = 0: a double root at 0
    double t0 = q / a, t1 = c / q;
    if (t0 > t1) std::swap(t0, t1);
    return {true, t0, t1};
}

std::optional<double> first_root(const Roots& roots, double t_min, double t_max)
{
    if (!roots.real) return std::nullopt;
    if (inside(roots.t0, t_min, t_max)) return roots.t0;
    if (inside(roots.t1, t_min, t_max)) return roots.t1;
    return std::nullopt;
}

// One slab of the box test: the interval of t where |o + t d| <= h along an axis.
struct Slab {
    double entry, exit;
    bool empty;
};

Slab slab(double origin, double direction, double half)
{
    if (direction == 0) {
        const bool within = std::fabs(origin) <= half;
        return {-INFINITY, INFINITY, !within};
    }
    double t0 = (-half - origin) / direction, t1 = (half - origin) / direction;
    if (t0 > t1) std::swap(t0, t1);
    return {t0, t1, false};
}

// |oc + t d|^2 = r^2 with oc = o - c.
Roots sphere_roots(const Ray& ray, const Sphere& sphere)
{
    const Vec3 oc = ray.origin - sphere.center;
    const double a = dot(ray.direction, ray.direction);
    const double half_b = dot(oc, ray.direction);
    const double c = dot(oc, oc) - sphere.radius * sphere.radius;
    const Vec3 closest = oc - ray.direction * (half_b / a);
    const double discriminant = a * (sphere.radius * sphere.radius - dot(closest, closest));
    return solve_quadratic(a, half_b, c, discriminant);
}

// Slab test (Kay and Kajiya 1986) in the box's own frame: the line's interval
// inside the box and the axes of the faces it enters and leaves by.
struct BoxSpan {
    bool meets = false;
    double entry = -INFINITY, exit = INFINITY;
    int entry_axis = 0, exit_axis = 0;
    Vec3 d;  // the direction in the box's frame
};

BoxSpan box_span(const Ray& ray, const OrientedBox& box)
{
    BoxSpan span;
    const Vec3 o = box.rotation.apply_inverse(ray.origin - box.center);
    span.d = box.rotation.apply_inverse(ray.direction);
    const Slab slabs[3] = {slab(o.x, span.d.x, box.half_size.x), slab(o.y, span.d.y, box.half_size.y),
                           slab(o.z, span.d.z, box.half_size.z)};
    for (int axis = 0; axis < 3; ++axis) {
        if (slabs[axis].empty) return span;
        if (slabs[axis].entry > span.entry) span.entry = slabs[axis].entry, span.entry_axis = axis;
        if (slabs[axis].exit < span.exit) span.exit = slabs[axis].exit, span.exit_axis = axis;
    }
    span.meets = span.entry <= span.exit;
    return span;
}

std::optional<Hit> keep_nearest(std::optional<Hit> a, std::optional<Hit> b)
{
    if (!a) return b;
    if (!b) return a;
    return a->t <= b->t ? a : b;
}

// The side of a finite cylinder (axis from a along unit w, length `len`).
std::optional<Hit> intersect_cylinder_side(const Ray& ray, Vec3 a, Vec3 w, double len, double radius,
                                           double t_min, double t_max)
{
    // Remove the axial parts: the side is |o_perp + t d_perp| = r.
    const Vec3 oa = ray.origin - a;
    const Vec3 o_perp = oa - w * dot(oa, w);
    const Vec3 d_perp = ray.direction - w * dot(ray.direction, w);
    const double qa = dot(d_perp, d_perp);
    if (qa == 0) return std::nullopt;  // parallel to the axis: only the caps can be hit
    const double half_b = dot(o_perp, d_perp);
    const double c = dot(o_perp, o_perp) - radius * radius;
    // discriminant/qa = r^2 - |o_perp - d_perp half_b/qa|^2: the squared
    // distance from the axis at closest approach, free of cancellation.
    const Vec3 closest = o_perp - d_perp * (half_b / qa);
    const double discriminant = qa * (radius * radius - dot(closest, closest));
    const Roots roots = solve_quadratic(qa, half_b, c, discriminant);
    if (!roots.real) return std::nullopt;
    for (double t : {roots.t0, roots.t1}) {
        const double s = dot(oa, w) + t * dot(ray.direction, w);
        if (inside(t, t_min, t_max) && s >= 0 && s <= len)
            return Hit{t, normalize(o_perp + d_perp * t), -1};
    }
    return std::nullopt;
}

}  // namespace

std::optional<Hit> intersect(const Ray& ray, const Plane& plane, double t_min, double t_max)
{
    const double denominator = dot(plane.normal, ray.direction);
    if (denominator == 0) return std::nullopt;
    const double t = dot(plane.normal, plane.point - ray.origin) / denominator;
    if (!inside(t, t_min, t_max)) return std::nullopt;
    return Hit{t, plane.normal, -1};
}

std::optional<Hit> intersect(const Ray& ray, const Sphere& sphere, double t_min, double t_max)
{
    const auto t = first_root(sphere_roots(ray, sphere), t_min, t_max);
    if (!t) return std::nullopt;
    return Hit{*t, (ray.at(*t) - sphere.center) / sphere.radius, -1};
}

std::optional<Hit> intersect(const Ray& ray, const OrientedBox& box, double t_min, double t_max)
{
    const BoxSpan span = box_span(ray, box);
    if (!span.meets) return std::nullopt;
    const double direction[3] = {span.d.x, span.d.y, span.d.z};
    const Vec3 axes[3] = {box.rotation.x, box.rotation.y, box.rotation.z};
    // Entering through a face means moving against its outward normal; leaving, along it.
    if (inside(span.entry, t_min, t_max))
        return Hit{span.entry, axes[span.entry_axis] * (direction[span.entry_axis] > 0 ? -1.0 : 1.0), -1};
    if (inside(span.exit, t_min, t_max))
        return Hit{span.exit, axes[span.exit_axis] * (direction[span.exit_axis] > 0 ? 1.0 : -1.0), -1};
    return std::nullopt;
}

std::optional<Hit> intersect(const Ray& ray, const Capsule& capsule, double t_min, double t_max)
{
    // The capsule is the union of two spheres and a finite cylinder, the
    // points within `radius` of the segment [a, b]. Its surface is where that
    // distance equals the radius. The earliest crossing of a part is one of
    // the union's unless it lies inside another part (a cap's inner half, from
    // a ray that starts inside): then the search goes on past it. Layered
    // depth maps (Pismo) need every true crossing, not only the first.
    const Vec3 axis = capsule.b - capsule.a;
    const double len = length(axis);
    const auto earliest_part = [&](double from) {
        std::optional<Hit> best = intersect(ray, Sphere{capsule.a, capsule.radius}, from, t_max);
        best = keep_nearest(best, intersect(ray, Sphere{capsule.b, capsule.radius}, from, best ? best->t : t_max));
        if (len > 0)
            best = keep_nearest(best, intersect_cylinder_side(ray, capsule.a, axis / len, len, capsule.radius, from,
                                                              best ? best->t : t_max));
        return best;
    };
    const auto on_surface = [&](const Hit& hit) {
        const Vec3 p = ray.at(hit.t);
        const double s = len > 0 ? std::clamp(dot(p - capsule.a, axis) / (len * len), 0.0, 1.0) : 0.0;
        return length(p - (capsule.a + axis * s)) >= capsule.radius * (1 - 1e-9);
    };
    // A line crosses the three parts' surfaces at most six times.
    double from = t_min;
    for (int crossing = 0; crossing < 6; ++crossing) {
        const std::optional<Hit> hit = earliest_part(from);
        if (!hit || on_surface(*hit)) return hit;
        from = hit->t;
    }
    return std::nullopt;
}

std::optional<Chord> chord(const Ray& ray, const Sphere& sphere)
{
    const Roots roots = sphere_roots(ray, sphere);
    if (!roots.real) return std::nullopt;
    return Chord{roots.t0, roots.t1};
}

std::optional<Chord> chord(const Ray& ray, const OrientedBox& box)
{
    const BoxSpan span = box_span(ray, box);
    if (!span.meets) return std::nullopt;
    return Chord{span.entry, span.exit};
}

}  // namespace penumbra::reference
