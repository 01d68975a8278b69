// PreparedScene: ray queries and the signed distance over all primitives.
#include <cmath>
#include <limits>

#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

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

double direction_along(const Ray& ray, int axis)
{
    return axis == 0 ? ray.direction.x : axis == 1 ? ray.direction.y : ray.direction.z;
}

}  // namespace

OrientedBox OrientedBox::from(const Box& box)
{
    return {box.center, box.size * 0.5, rotation_from_euler_degrees(box.rotation_degrees)};
}

PreparedScene::PreparedScene(const std::vector<Primitive>& primitives) : count_(primitives.size())
{
    for (std::size_t i = 0; i < primitives.size(); ++i) {
        const int index = int(i);
        const Primitive& p = primitives[i];
        if (const auto* plane = std::get_if<Plane>(&p)) {
            planes_.push_back(Plane{plane->point, normalize(plane->normal)});
            plane_indices_.push_back(index);
        } else if (const auto* sphere = std::get_if<Sphere>(&p)) {
            solids_.push_back({*sphere, bounds_of(*sphere), index});
        } else if (const auto* box = std::get_if<Box>(&p)) {
            const OrientedBox oriented = OrientedBox::from(*box);
            solids_.push_back({oriented, bounds_of(oriented), index});
        } else {
            const Capsule& capsule = std::get<Capsule>(p);
            solids_.push_back({capsule, bounds_of(capsule), index});
        }
    }
    if (!solids_.empty()) build(0, int(solids_.size()));
}

// Visits the solids whose node bounds the ray overlaps in (t_min, t_max),
// nearer child first; `visit` returns true to stop. t_max is read through a
// reference so that a closest-hit visitor's shrinking interval prunes nodes.
template <class Visit>
void PreparedScene::traverse(const Ray& ray, double t_min, const double& t_max, Visit&& visit) const
{
    if (nodes_.empty()) return;
    const SlabRay slab_ray(ray);
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
        const bool left_is_near = direction_along(ray, node.axis) >= 0;
        stack[depth++] = left_is_near ? right : left;
        stack[depth++] = left_is_near ? left : right;
    }
}

std::optional<Hit> PreparedScene::closest_hit(const Ray& ray, double t_min, double t_max) const
{
    std::optional<Hit> best;
    for (std::size_t i = 0; i < planes_.size(); ++i)
        if (auto hit = intersect(ray, planes_[i], t_min, t_max)) {
            hit->primitive = plane_indices_[i];
            t_max = hit->t;
            best = hit;
        }
    traverse(ray, t_min, t_max, [&](const Solid& solid) {
        auto hit = std::visit([&](const auto& shape) { return intersect(ray, shape, t_min, t_max); }, solid.shape);
        if (hit) {
            hit->primitive = solid.index;
            t_max = hit->t;
            best = hit;
        }
        return false;
    });
    return best;
}

bool PreparedScene::occluded(const Ray& ray, double t_min, double t_max) const
{
    bool blocked = false;
    traverse(ray, t_min, t_max, [&](const Solid& solid) {
        blocked = std::visit([&](const auto& shape) { return intersect(ray, shape, t_min, t_max).has_value(); },
                             solid.shape);
        return blocked;
    });
    if (blocked) return true;
    for (const Plane& plane : planes_)
        if (intersect(ray, plane, t_min, t_max)) return true;
    return false;
}

double PreparedScene::signed_distance(Vec3 p) const
{
    double best = std::numeric_limits<double>::infinity();
    for (const Plane& plane : planes_) best = std::fmin(best, reference::signed_distance(p, plane));
    for (const Solid& solid : solids_)
        best = std::fmin(best, std::visit([&](const auto& shape) { return reference::signed_distance(p, shape); },
                                          solid.shape));
    return best;
}

}  // namespace penumbra::reference
