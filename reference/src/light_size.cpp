// The PCSS penumbra width and the light_size parameter of the shadow-map
// methods. Derivation (docs/reference.md, "light_size"):
//
// A receiver at depth d_r sees the light (width L, at depth 0) through a cone.
// At the blocker's depth d_b the cone is L (d_r - d_b) / d_r wide in world
// units (similar triangles, apex at the receiver). One texture unit at depth
// d_b is 2 d_b tan(fov/2) world units (perspective) or `extent` (orthographic),
// so the cone covers, in texture units,
//   perspective:  w = L (d_r - d_b) / (2 tan(fov/2) d_b d_r)
//   orthographic: w = L (d_r - d_b) / (extent d_r).
// The kernels estimate w = light_size (z_r - z_b) / z_b with linear depths
// z = (d - near) / (far - near) = (d - near) / D. Since z_r - z_b = (d_r - d_b) / D
// and z_b = (d_b - near) / D, equating the two gives
//   perspective:  light_size = L / (2 tan(fov/2)) * (d_b - near) / (d_b d_r)
//   orthographic: light_size = (L / extent) * (d_b - near) / d_r.
// No constant does it for every pair of depths: the value depends on the
// receiver's depth, and (weakly, when near << d_b) on the blocker's.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "penumbra/error.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

double half_fov_tangent(const Scene& scene)
{
    return std::tan(scene.light_camera.fov_degrees * std::numbers::pi / 360.0);
}

bool perspective(const Scene& scene) { return scene.light_camera.projection == Projection::Perspective; }

// The first plane the light's axis meets in [near, far], as a depth.
std::optional<double> axis_plane_depth(const Scene& scene, const LightProjection& projection)
{
    std::vector<Primitive> planes;
    for (const Primitive& p : scene.primitives)
        if (std::holds_alternative<Plane>(p)) planes.push_back(p);
    const auto hit = PreparedScene(planes).closest_hit(projection.ray_through(0.5, 0.5), scene.light_camera.near,
                                                       scene.light_camera.far);
    return hit ? std::optional<double>(hit->t) : std::nullopt;
}

double reference_receiver_z(const Scene& scene, const LightProjection& projection)
{
    if (const auto depth = axis_plane_depth(scene, projection)) return projection.z_of(*depth);
    const auto hit = PreparedScene(scene)
                         .closest_hit(projection.ray_through(0.5, 0.5), scene.light_camera.near,
                                      scene.light_camera.far);
    return hit ? projection.z_of(hit->t) : 1.0;
}

double reference_blocker_z(const Scene& scene, const LightProjection& projection, double z_receiver)
{
    constexpr int kSide = 64;
    const std::vector<Primitive> surfaces = scene_surfaces(scene);
    const PreparedScene prepared(surfaces);
    std::vector<double> blockers;
    for (int j = 0; j < kSide; ++j)
        for (int i = 0; i < kSide; ++i) {
            const Ray ray = projection.ray_through((i + 0.5) / kSide, (j + 0.5) / kSide);
            const auto hit = prepared.closest_hit(ray, scene.light_camera.near, scene.light_camera.far);
            // Planes are the receivers of these scenes, not blockers (a tilted
            // ground is nearer than the reference receiver in half the map).
            const bool solid = hit && !std::holds_alternative<Plane>(surfaces[std::size_t(hit->primitive)]);
            if (solid && projection.z_of(hit->t) < 0.98 * z_receiver) blockers.push_back(projection.z_of(hit->t));
        }
    if (blockers.empty()) return 0.5 * z_receiver;
    auto middle = blockers.begin() + std::ptrdiff_t(blockers.size() / 2);
    std::nth_element(blockers.begin(), middle, blockers.end());
    return *middle;
}

void require_depths(std::string_view operation, double z_receiver, double z_blocker)
{
    require(z_receiver >= 0 && z_receiver <= 1 && z_blocker >= 0 && z_blocker <= 1, operation,
            "depths must be linear light depths in [0, 1] (got z_receiver " + std::to_string(z_receiver) +
                ", z_blocker " + std::to_string(z_blocker) + ")");
}

}  // namespace

double penumbra_width(const Scene& scene, double z_receiver, double z_blocker)
{
    validate_scene(scene, "penumbra_width");
    require_depths("penumbra_width", z_receiver, z_blocker);
    if (z_blocker >= z_receiver) return 0;
    const LightProjection projection(scene);
    const double d_r = projection.depth_of(z_receiver), d_b = projection.depth_of(z_blocker);
    const double light = scene.light.width;
    if (perspective(scene)) return light / (2 * half_fov_tangent(scene)) * (1 / d_b - 1 / d_r);
    return light / scene.light_camera.extent * (d_r - d_b) / d_r;
}

double light_size_at(const Scene& scene, double z_receiver, double z_blocker)
{
    validate_scene(scene, "light_size_at");
    require_depths("light_size_at", z_receiver, z_blocker);
    const LightProjection projection(scene);
    const double d_r = projection.depth_of(z_receiver), d_b = projection.depth_of(z_blocker);
    const double near = scene.light_camera.near, light = scene.light.width;
    if (perspective(scene)) return light / (2 * half_fov_tangent(scene)) * (d_b - near) / (d_b * d_r);
    return light / scene.light_camera.extent * (d_b - near) / d_r;
}

double light_width_at_near_plane(const Scene& scene)
{
    validate_scene(scene, "light_width_at_near_plane");
    const double light = scene.light.width;
    if (perspective(scene)) return light / (2 * scene.light_camera.near * half_fov_tangent(scene));
    return light / scene.light_camera.extent;
}

ReferenceDepths reference_depths(const Scene& scene)
{
    validate_scene(scene, "reference_depths");
    const LightProjection projection(scene);
    const double z_receiver = reference_receiver_z(scene, projection);
    return {z_receiver, reference_blocker_z(scene, projection, z_receiver)};
}

double light_size(const Scene& scene)
{
    const ReferenceDepths depths = reference_depths(scene);
    return light_size_at(scene, depths.z_receiver, depths.z_blocker);
}

}  // namespace penumbra::reference
