// Light space: where a world point lands in the shadow map, the PCSS light
// size, and moving the light by sub-texel steps.
//
// Light space (docs/reference.md, "Conventions"): the light's frame (s, t, n)
// = basis_looking_along(light.normal, light.up), origin at the light's centre.
// A world point p has local coordinates x = (p-c).s, y = (p-c).t and depth
// d = (p-c).n (the distance along the light's axis, not along the ray), and
//   perspective:  u = 1/2 + x / (2 d tan(fov/2)),  v = 1/2 + y / (2 d tan(fov/2))
//   orthographic: u = 1/2 + x / extent,            v = 1/2 + y / extent
//   both:         z = (d - near) / (far - near)   (linear depth, 0 at near, 1 at far)
// Texel (i, j) of a W x H map covers u in [i/W, (i+1)/W), v in [j/H, (j+1)/H);
// u grows along s (image columns), v along t (image rows, "down").
#pragma once

#include <vector>

#include "penumbra/reference/scene.h"
#include "penumbra/soft_pcf.h"

namespace penumbra::reference {

class LightProjection {
public:
    // Expects a valid scene (validate_scene); the functions below check theirs.
    explicit LightProjection(const Scene& scene);

    const Basis& basis() const noexcept { return basis_; }
    // (u, v, z) of a world point. u and v are meaningful only for d > 0
    // (in front of the light); they stay finite for any point.
    Vec3 project(Vec3 world) const;
    // The ray through texture coordinate (u, v). Its direction has a unit
    // component along n, so the ray parameter is the depth d of a point on it.
    Ray ray_through(double u, double v) const;
    double depth_of(double z) const { return near_ + z * (far_ - near_); }
    double z_of(double depth) const { return (depth - near_) / (far_ - near_); }
    // World length covered by one unit of u (or v) at depth d.
    double texture_unit_length(double depth) const;

private:
    Basis basis_;
    Vec3 origin_;
    bool perspective_;
    double near_, far_;
    double tan_half_fov_, extent_;
};

// The PCSS filter width, in texture units (a fraction of the map's width),
// for a receiver at linear depth z_receiver behind a planar blocker at
// z_blocker parallel to the light: the width of the cone from the receiver to
// the light where it crosses the blocker's depth, which is the map region
// whose coverage is the light's occluded fraction. With depths d_r, d_b:
//   perspective:  w = L / (2 tan(fov/2)) * (1/d_b - 1/d_r)
//   orthographic: w = (L / extent) * (d_r - d_b) / d_r
// L is the light's width along s, i.e. across u (its diameter for a disk; the
// built-in lights are square, so v gives the same). Depths are in [0, 1]
// (Error otherwise); the width is zero when z_blocker >= z_receiver.
double penumbra_width(const Scene& scene, double z_receiver, double z_blocker);

// The light_size that makes the kernels' estimate
//   w = light_size * (z_receiver - z_blocker) / z_blocker
// equal to penumbra_width for this receiver and blocker depth.
double light_size_at(const Scene& scene, double z_receiver, double z_blocker);

// Reference depths of a scene: the receiver is where the light's axis meets
// the first plane (the ground) in [near, far], else the first surface, else
// the far plane; the blocker is the median depth of the texels of a 64 x 64
// shadow map whose first surface is not a plane and lies nearer than 0.98 x
// the receiver depth, or half the receiver depth when there are none.
struct ReferenceDepths {
    double z_receiver = 1, z_blocker = 0.5;
};
ReferenceDepths reference_depths(const Scene& scene);

// The scene's light_size parameter: light_size_at at its reference depths.
// docs/reference.md derives it and gives the error away from those depths.
double light_size(const Scene& scene);

// The light's width in texture units at the near plane: L / (2 near tan(fov/2))
// (perspective) or L / extent (orthographic). It is NOT the light_size of the
// estimate above (that is about near / d_r times smaller); it is the widest
// blocker-search window a receiver can need, the cone to the light cut at the
// near plane, for a receiver far behind it: (L / (2 tan(fov/2))) (1/near - 1/d_r).
double light_width_at_near_plane(const Scene& scene);

// The light's frustum as Burley's world cone needs it (penumbra::world_cone):
// the map's world width at the near and far planes, and the planes.
LightFrustum light_frustum(const Scene& scene);

// The scene with its light (and the light camera on it) moved within the
// light's plane by (du, dv) texels of a map_width x map_height map, measured
// at the reference receiver depth: a receiver there moves by -du, -dv texels
// in the map.
Scene shift_light(const Scene& scene, double du_texels, double dv_texels, int map_width, int map_height);

// K frames for the flicker metric: frame k is shift_light by (k/K, k/K) texels,
// so the light sweeps one texel diagonally in K sub-texel steps.
std::vector<Scene> flicker_frames(const Scene& scene, int frames, int map_width, int map_height);

}  // namespace penumbra::reference
