// PreparedScene's hierarchy walk, shared by the ray queries (tracer.cpp) and
// the transmittance queries (transmittance.cpp). Private to reference/src.
#pragma once

#include <cmath>

#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace detail {

// A ray's reciprocal direction for slab tests against node bounds. A zero
// component is replaced by a tiny one of the same sign, so 1/d is huge but
// finite: (bound - origin) * (1/d) is then +-huge (a miss when the origin lies
// outside that slab, all of t when inside) and never 0 * inf = NaN, even for
// an origin exactly on a bound, which axis-aligned light rays do meet.
struct SlabRay {
    Vec3 origin, inverse;

    explicit SlabRay(const Ray& ray) : origin(ray.origin)
    {
        auto reciprocal = [](double d) { return 1 / (d != 0 ? d : std::copysign(1e-300, d)); };
        inverse = {reciprocal(ray.direction.x), reciprocal(ray.direction.y), reciprocal(ray.direction.z)};
    }

    // Plain comparisons, not fmin/fmax: no NaN can arise, and these compile to
    // single instructions where fmin/fmax are library calls (they took a third
    // of the ground truth's time).
    static double smaller(double a, double b) { return a < b ? a : b; }
    static double larger(double a, double b) { return a > b ? a : b; }

    bool overlaps(const Bounds& b, double t_min, double t_max) const
    {
        const double x0 = (b.lo.x - origin.x) * inverse.x, x1 = (b.hi.x - origin.x) * inverse.x;
        const double y0 = (b.lo.y - origin.y) * inverse.y, y1 = (b.hi.y - origin.y) * inverse.y;
        const double z0 = (b.lo.z - origin.z) * inverse.z, z1 = (b.hi.z - origin.z) * inverse.z;
        const double entry = larger(larger(smaller(x0, x1), smaller(y0, y1)), larger(smaller(z0, z1), t_min));
        const double exit = smaller(smaller(larger(x0, x1), larger(y0, y1)), smaller(larger(z0, z1), t_max));
        return entry <= exit;
    }
};

inline double direction_along(const Ray& ray, int axis)
{
    return axis == 0 ? ray.direction.x : axis == 1 ? ray.direction.y : ray.direction.z;
}

}  // namespace detail

// Visits the solids whose node bounds the ray overlaps in (t_min, t_max),
// nearer child first; `visit` returns true to stop. t_max is read through a
// reference so that a closest-hit visitor's shrinking interval prunes nodes.
template <class Visit>
void PreparedScene::traverse(const Ray& ray, double t_min, const double& t_max, Visit&& visit) const
{
    if (nodes_.empty()) return;
    const detail::SlabRay slab_ray(ray);
    int stack[64];
    int depth = 0;
    stack[depth++] = 0;
    while (depth > 0) {
        const Node& node = nodes_[stack[--depth]];
        if (!slab_ray.overlaps(node.bounds, t_min, t_max)) continue;
        if (node.count > 0) {
            for (int i = node.first; i < node.first + node.count; ++i)
                if (visit(solids_[i])) return;
            continue;
        }
        const int left = int(&node - nodes_.data()) + 1, right = node.first;
        // Push the farther child first so the nearer one is popped first.
        const bool left_is_near = detail::direction_along(ray, node.axis) >= 0;
        stack[depth++] = left_is_near ? right : left;
        stack[depth++] = left_is_near ? left : right;
    }
}

}  // namespace penumbra::reference
