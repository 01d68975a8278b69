// Cascaded shadow maps of a scene's directional light (scene.h,
// DirectionalLight), fitted to the view camera, and the hard-shadow truth of
// that light: the inputs and the measuring stick of penumbra/cascades.h.
// docs/cascades.md states the choices (split scheme, fitting, pancaking).
#pragma once

#include <vector>

#include "penumbra/cascades.h"
#include "penumbra/image.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"

namespace penumbra::reference {

// What happens to casters nearer the light than a cascade's near plane (the
// plane is fitted to the split's corners, so that the map's depth precision
// covers only the split):
//   Clip     they are lost, as a rasteriser's near-plane clipping loses them;
//            the map is drawn from faces towards the light only (back faces
//            culled), so a ray that starts inside a solid sees none of it:
//            the Toy Story 3 notes' "sliver" where a wall crosses the plane.
//   Pancake  they are clamped to the near plane (depth 0), the notes' fix
//            (their "shadow cookies" bake a caster's depth to 0; a ray caster
//            clamps every caster exactly, with no triangle to distort).
enum class NearPlane { Clip, Pancake };

struct CascadeSetup {
    int count = 3;        // cascades, 1 .. kMaxCascades (the notes: three)
    int map_size = 640;   // each cascade's side (the notes: 640 x 640)
    // The shadowed range of view depths; near = far = 0 takes the closest and
    // the farthest surface the receivers see.
    double near = 0, far = 0;
    double lambda = 0.75;  // practical split scheme: the share of the logarithmic split
    int grid = 4;          // the PCF grid whose footprint the fit keeps inside each map
    NearPlane near_plane = NearPlane::Pancake;
};

// count + 1 view depths, near to far: the practical split scheme of Zhang et
// al. 2006 (GPU Gems 3, ch. 10), d_i = lambda n (f/n)^(i/k) + (1 - lambda)
// (n + (f - n) i / k). Error(InvalidArgument) for count outside
// [1, kMaxCascades] ("cascades"), near <= 0 or far <= near.
std::vector<double> split_depths(double near, double far, int count, double lambda);

// The cascades of directional light `light` (0: the world light, 1: the
// character light) for the view of `receivers` (its aspect ratio, and its
// depth range when setup asks for it). Each cascade is the orthographic box
// around its split's eight frustum corners in the light's frame (a square
// across the light, so that texels are square; widened by grid + 1 texels so
// that a PCF footprint of a pixel inside the split stays inside the map),
// depth from the nearest to the farthest corner. Error(InvalidArgument),
// parameter "light", when the scene has no such light.
CascadeShadows render_cascades(const Scene& scene, int light, const Receivers& receivers, const CascadeSetup& setup);

// The receivers as penumbra::cascade_mask reads them: world x, y, z, view depth, hit.
Image cascade_receivers(const Receivers& receivers);

// The hard shadow of directional light `light`: 1 where the ray from the
// receiver (lifted by kNormalOffset, ground_truth.h) towards the light meets
// nothing (the transmittance through semi-transparent layers), 0 where it is
// blocked; 1 where no surface is seen.
Image directional_truth(const Scene& scene, int light, const Receivers& receivers);

}  // namespace penumbra::reference
