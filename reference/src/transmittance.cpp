// PreparedScene's transmittance queries: the light a segment lets through,
// and the ordered events from which a deep shadow map builds its
// transmittance function of depth (Lokovic and Veach 2000: a step of
// 1 - opacity at each surface, exp(-integral of k) through the media).
#include <algorithm>
#include <cmath>

#include "bvh_traversal.h"

namespace penumbra::reference {

double PreparedScene::transmittance(const Ray& ray, double t_min, double t_max, int skip) const
{
    // The product is order-free; an opaque crossing ends it at exactly 0.
    double surviving = 1;
    traverse(ray, t_min, t_max, [&](const Solid& solid) {
        const bool crosses = solid.index != skip && std::visit([&](const auto& shape) {
            return intersect(ray, shape, t_min, t_max).has_value();
        }, solid.shape);
        if (crosses) surviving *= 1 - solid.opacity;
        return surviving == 0;
    });
    for (const FlatSurface& flat : planes_)
        if (surviving > 0 && flat.index != skip && intersect(ray, flat.plane, t_min, t_max))
            surviving *= 1 - flat.plane.opacity;
    if (surviving == 0 || media_.empty()) return surviving;
    return surviving * std::exp(-optical_depth(ray, t_min, t_max));
}

std::vector<RayEvent> PreparedScene::events(const Ray& ray, double t_min, double t_max) const
{
    std::vector<RayEvent> out;
    // Nothing beyond the nearest opaque crossing found so far can matter.
    double limit = t_max;
    auto add = [&](const std::optional<Hit>& hit, int index, double opacity) {
        if (!hit) return;
        out.push_back({RayEvent::Kind::Surface, hit->t, index, opacity, 0});
        if (opacity == 1) limit = std::min(limit, hit->t);
    };
    traverse(ray, t_min, limit, [&](const Solid& solid) {
        add(std::visit([&](const auto& shape) { return intersect(ray, shape, t_min, limit); }, solid.shape),
            solid.index, solid.opacity);
        return false;
    });
    for (const FlatSurface& flat : planes_)
        add(intersect(ray, flat.plane, t_min, limit), flat.index, flat.plane.opacity);
    // Crossings found before `limit` shrank may lie beyond it.
    std::erase_if(out, [&](const RayEvent& e) { return e.t > limit; });
    for (std::size_t m = 0; m < media_.size(); ++m) {
        const auto span = media_[m].chord(ray);
        if (!span) continue;
        const double a = std::max(span->entry, t_min), b = std::min(span->exit, limit);
        if (!(b > a)) continue;
        const int index = int(m);
        out.push_back({RayEvent::Kind::MediumEntry, a, index, 0, media_[m].extinction_within(ray.at(a))});
        out.push_back({RayEvent::Kind::MediumExit, b, index, 0, media_[m].extinction_within(ray.at(b))});
    }
    // Increasing t; at one t, entries, then surfaces, then exits (a fixed order).
    std::sort(out.begin(), out.end(), [](const RayEvent& x, const RayEvent& y) {
        auto rank = [](RayEvent::Kind k) { return k == RayEvent::Kind::MediumEntry ? 0 : k == RayEvent::Kind::Surface ? 1 : 2; };
        if (x.t != y.t) return x.t < y.t;
        if (rank(x.kind) != rank(y.kind)) return rank(x.kind) < rank(y.kind);
        return x.index < y.index;
    });
    return out;
}

double PreparedScene::extinction_at(Vec3 p) const
{
    double k = 0;
    for (const PreparedMedium& medium : media_) k += medium.extinction_at(p);
    return k;
}

double PreparedScene::optical_depth(const Ray& ray, double t_min, double t_max) const
{
    double depth = 0;
    for (const PreparedMedium& medium : media_) depth += medium.optical_depth(ray, t_min, t_max);
    return depth;
}

}  // namespace penumbra::reference
