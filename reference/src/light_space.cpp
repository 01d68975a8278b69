// LightProjection: world points to shadow-map coordinates and back (the
// formulas are in penumbra/reference/light_space.h).
#include <cmath>
#include <numbers>

#include "penumbra/reference/light_space.h"

namespace penumbra::reference {

LightProjection::LightProjection(const Scene& scene)
    : basis_(basis_looking_along(scene.light.normal, scene.light.up)),
      origin_(scene.light.center),
      perspective_(scene.light_camera.projection == Projection::Perspective),
      near_(scene.light_camera.near),
      far_(scene.light_camera.far),
      tan_half_fov_(std::tan(scene.light_camera.fov_degrees * std::numbers::pi / 360.0)),
      extent_(scene.light_camera.extent)
{
}

double LightProjection::texture_unit_length(double depth) const
{
    return perspective_ ? 2.0 * depth * tan_half_fov_ : extent_;
}

Vec3 LightProjection::project(Vec3 world) const
{
    const Vec3 local = basis_.to_local(world - origin_);
    // Behind the light a perspective projection is meaningless; a tiny
    // positive depth keeps u and v finite (the caller checks z).
    const double depth_for_scale = perspective_ ? std::fmax(local.z, 1e-12 * (1 + std::fabs(local.z))) : 1.0;
    const double unit = texture_unit_length(depth_for_scale);
    return {0.5 + local.x / unit, 0.5 + local.y / unit, z_of(local.z)};
}

Ray LightProjection::ray_through(double u, double v) const
{
    if (perspective_) {
        // At depth 1 the frustum spans 2 tan(fov/2) across u and v.
        const double x = (2 * u - 1) * tan_half_fov_, y = (2 * v - 1) * tan_half_fov_;
        return {origin_, basis_.to_world({x, y, 1})};
    }
    const double x = (u - 0.5) * extent_, y = (v - 0.5) * extent_;
    return {origin_ + basis_.to_world({x, y, 0}), basis_.n};
}

LightFrustum light_frustum(const Scene& scene)
{
    const LightProjection light(scene);
    const LightCamera& camera = scene.light_camera;
    return {float(light.texture_unit_length(camera.near)), float(light.texture_unit_length(camera.far)),
            float(camera.near), float(camera.far)};
}

}  // namespace penumbra::reference
