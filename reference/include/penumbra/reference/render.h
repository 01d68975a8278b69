// Rendering a reference scene: the shadow map seen from the light and the
// receivers seen from the view camera, at any resolution. Both cast one ray
// per pixel centre against the analytic primitives (double precision) and run
// rows in parallel with oneTBB.
#pragma once

#include "penumbra/image.h"
#include "penumbra/reference/scene.h"

namespace penumbra::reference {

// The shadow map: one channel, the linear light depth z in [0, 1] of the first
// surface along the ray through each texel centre ((i + 1/2)/W, (j + 1/2)/H),
// between the near and far planes; 1 (the far plane) where the ray meets nothing.
Image render_shadow_map(const Scene& scene, int width, int height);

// What the view camera sees, per pixel (all images width x height).
//  light_uvz       3 channels: u, v, z in light space (light_space.h)
//  world_position  3 channels: x, y, z of the visible point
//  normal          3 channels: the outward unit normal there
//  view_depth      1 channel: distance along the view camera's axis
//  hit             1 channel: 1 where the pixel sees a surface, else 0
//  mask            1 channel: 1 where the pixel is a valid receiver: it sees a
//                  surface whose (u, v, z) lies in [0, 1]^3, inside the light's
//                  frustum; 0 elsewhere.
// Pixels that see nothing get (u, v, z) = (0, 0, 1) (the far plane), zero
// position, normal and depth. Pixels that see a surface outside the light's
// frustum keep their position, normal and depth, and get (u, v, z) clamped to
// [0, 1], so no kernel ever reads out of range; the mask flags both.
struct Receivers {
    Image light_uvz;
    Image world_position;
    Image normal;
    Image view_depth;
    Image hit;
    Image mask;

    int width() const noexcept { return mask.width(); }
    int height() const noexcept { return mask.height(); }
    // Zero-filled images of the given size (for receivers built by hand).
    static Receivers allocate(int width, int height);
};

Receivers render_receivers(const Scene& scene, int width, int height);

}  // namespace penumbra::reference
