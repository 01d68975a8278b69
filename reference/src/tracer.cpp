// PreparedScene: ray queries and the signed distance over all primitives.
#include <cmath>
#include <limits>

#include "bvh_traversal.h"
#include "penumbra/reference/scene.h"

namespace penumbra::reference {

OrientedBox OrientedBox::from(const Box& box)
{
    return {box.center, box.size * 0.5, rotation_from_euler_degrees(box.rotation_degrees)};
}

PreparedScene::PreparedScene(const Scene& scene) : PreparedScene(scene_surfaces(scene), scene.media) {}

PreparedScene::PreparedScene(const std::vector<Primitive>& surfaces, const std::vector<Medium>& media)
    : count_(surfaces.size())
{
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        const int index = int(i);
        const Primitive& p = surfaces[i];
        const double opacity = opacity_of(p);
        if (opacity == 0) continue;  // a surface that lets everything through is not there
        if (const auto* plane = std::get_if<Plane>(&p)) {
            planes_.push_back({Plane{plane->point, normalize(plane->normal), opacity}, index});
        } else if (const auto* sphere = std::get_if<Sphere>(&p)) {
            solids_.push_back({*sphere, bounds_of(*sphere), index, opacity});
        } else if (const auto* box = std::get_if<Box>(&p)) {
            const OrientedBox oriented = OrientedBox::from(*box);
            solids_.push_back({oriented, bounds_of(oriented), index, opacity});
        } else {
            const Capsule& capsule = std::get<Capsule>(p);
            solids_.push_back({capsule, bounds_of(capsule), index, opacity});
        }
    }
    if (!solids_.empty()) build(0, int(solids_.size()));
    for (const Medium& medium : media) media_.push_back(PreparedMedium::from(medium));
}

std::optional<Hit> PreparedScene::closest_hit(const Ray& ray, double t_min, double t_max) const
{
    std::optional<Hit> best;
    for (const FlatSurface& flat : planes_)
        if (auto hit = intersect(ray, flat.plane, t_min, t_max)) {
            hit->primitive = flat.index;
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
    for (const FlatSurface& flat : planes_)
        if (intersect(ray, flat.plane, t_min, t_max)) return true;
    return false;
}

double PreparedScene::signed_distance(Vec3 p) const
{
    double best = std::numeric_limits<double>::infinity();
    for (const FlatSurface& flat : planes_) best = std::fmin(best, reference::signed_distance(p, flat.plane));
    for (const Solid& solid : solids_)
        best = std::fmin(best, std::visit([&](const auto& shape) { return reference::signed_distance(p, shape); },
                                          solid.shape));
    return best;
}

}  // namespace penumbra::reference
