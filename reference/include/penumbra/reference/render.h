// Rendering a reference scene: the shadow map seen from the light and the
// receivers seen from the view camera, at any resolution. Both cast one ray
// per pixel centre against the analytic primitives (double precision) and run
// rows in parallel with oneTBB.
#pragma once

#include <string>

#include "penumbra/image.h"
#include "penumbra/reference/scene.h"

namespace penumbra::reference {

// Which depth a shadow-map texel stores (Woo 1992, "The Shadow Depth Map
// Revisited", Graphics Gems III; named in Burley's bias-cone paper and the
// real-time shadow notes). Along the ray through the texel centre, with z1 the
// first surface crossing and z2 the next one strictly beyond it (entering or
// leaving a solid, the tracer's crossings: for a slab, its top then its bottom):
//   First     z1, the classic map (Williams 1978).
//   Midpoint  (z1 + z2) / 2: a receiver (which is a first surface) then lies
//             half an occluder's thickness in front of the stored depth, so it
//             needs far less bias; a thin occluder still leaks.
//   Second    z2: the receiver's own back face decides (Wang and Molnar 1994's
//             second-depth idea; it needs closed, watertight solids).
// The surfaces are those of opacity > 0, whatever their opacity (a
// semi-transparent layer is a depth like any other); media are not surfaces.
// Where the ray has no second crossing before the far plane (the ground is a
// half-space: rays enter it and never leave), z2 is the far plane, 1; so
// Second stores 1 and Midpoint (z1 + 1) / 2 there: lit ground with nothing
// behind it can shadow nothing. Where the ray meets nothing all three store 1.
enum class ShadowDepth { First, Midpoint, Second };

// "first", "midpoint", "second"; Error(InvalidArgument) naming `parameter`
// and the valid names for anything else.
ShadowDepth shadow_depth_from_name(const std::string& name, const std::string& parameter);
const char* shadow_depth_name(ShadowDepth depth);

// The shadow map: one channel, the linear light depth z in [0, 1] (`depth`
// chooses which surface, above) along the ray through each texel centre
// ((i + 1/2)/W, (j + 1/2)/H), between the near and far planes; 1 (the far
// plane) where the ray meets nothing.
Image render_shadow_map(const Scene& scene, int width, int height, ShadowDepth depth = ShadowDepth::First);

// What the view camera sees, per pixel (all images width x height).
//  light_uvz       3 channels: u, v, z in light space (light_space.h)
//  world_position  3 channels: x, y, z of the visible point
//  normal          3 channels: the outward unit normal there
//  view_depth      1 channel: distance along the view camera's axis
//  hit             1 channel: 1 where the pixel sees a surface (of opacity > 0;
//                  the view sees through media), else 0
//  mask            1 channel: 1 where the pixel is a valid receiver: it sees a
//                  surface whose (u, v, z) lies in [0, 1]^3, inside the light's
//                  frustum; 0 elsewhere.
//  surface         1 channel: the index into scene_surfaces(scene) of the
//                  surface seen (its identity: Pismo's surface ids,
//                  docs/pismo.md), -1 where the pixel sees nothing
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
    Image surface;

    int width() const noexcept { return mask.width(); }
    int height() const noexcept { return mask.height(); }
    // Zero-filled images of the given size (for receivers built by hand),
    // but `surface`, -1 (unknown) everywhere.
    static Receivers allocate(int width, int height);
    // World positions then normals, 6 planes: what Pismo reads to count the
    // receiver's own surface (docs/pismo.md), as RX.exr's P and N channels.
    Image positions_and_normals() const;
    // The same and then `surface`, 7 planes: with maps that carry surface ids,
    // what Pismo reads to tell P's own surface from the others.
    Image positions_normals_and_surface() const;
};

Receivers render_receivers(const Scene& scene, int width, int height);

}  // namespace penumbra::reference
