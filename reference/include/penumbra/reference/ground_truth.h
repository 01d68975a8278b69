// Ground truth: the fraction of the light that reaches each receiver, the
// mean transmittance of the segments from it to the light (tracer.h:
// products of 1 - opacity over the layers crossed, times exp(-integral of k)
// through the media), by stratified ray casting against the analytic scene.
// With opaque surfaces and no media that is the fraction of the area light
// visible; for a point light it is one segment's transmittance, exact.
//
// Sampling (docs/reference.md, "Ground truth"): the light's rectangle, or the
// square that a disk is mapped from by Shirley and Chiu's concentric map
// (area-preserving, so strata stay equal in area), is cut into n x n equal
// strata, one uniformly jittered sample in each. The sample positions come
// from a SplitMix64 stream seeded by (options.seed, pixel index), so a pixel's
// value does not depend on threads, tiles or the image's other pixels.
// Visibility is unweighted (no cosine, no distance falloff): it is the
// quantity the shadow-map methods estimate.
#pragma once

#include <cstdint>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {

struct GroundTruthOptions {
    int strata = 16;  // n: n x n samples per receiver
    std::uint64_t seed = 0x9e3779b97f4a7c15ull;
};

// The receiver's own surface. Where the receivers name the opaque surface a
// receiver lies on (Receivers::surface, as render_receivers writes it), the
// rays leave from the receiver itself: a ray below its tangent plane (normal
// . direction <= 0) enters that surface's solid and is blocked, and the
// surface is left out of the trace of every other ray, which it cannot cross:
// every primitive is a convex solid (a plane's half-space, a sphere, a box, a
// capsule), and a ray that leaves a convex solid's surface above the tangent
// plane there never meets it again. Exact, whatever the rounding of a float
// position. Without an id (-1, or a surface not opaque, or a receiver image
// without the channel) the rays leave from the receiver lifted along its
// normal by kNormalOffset * (1 + max |coordinate|): ten times the rounding of a
// float position (receivers store float), so a receiver never shadows itself
// by rounding, and small enough (1e-6 of the scene's scale) not to open
// contacts. The lift is not exact at a curved surface's terminator: a ray up
// to sqrt(2 h / R) below the tangent plane (h the lift, R the curvature radius)
// passes beside the solid it starts on, 2.8e-3 rad on contact's sphere, 7e-3 on
// its capsule, which lit its terminator band by about 0.5% on average
// (docs/reference.md, "Ground truth").
inline constexpr double kNormalOffset = 1e-6;

// Y: one channel on the receivers' grid, in [0, 1]. 1 where no surface is seen
// (receivers.hit == 0); computed for every hit pixel, in or out of the light
// frustum (the mask is for the shadow-map methods, which cannot see outside it).
// Throws Error(InvalidArgument) for strata outside [1, 4096].
Image ground_truth(const Scene& scene, const Receivers& receivers, const GroundTruthOptions& options = {});

// A receiver's shadow rays by the rule above (reference/src/receiver_rays.cpp):
// from `origin` (the point, or the point lifted when own_surface is -1).
struct ReceiverRays {
    ReceiverRays(Vec3 position, Vec3 normal, int own_surface);
    // The transmittance of origin + t direction for t in (0, t_max); 0 for a
    // direction below the tangent plane of the receiver's own surface.
    double transmittance(const PreparedScene& prepared, Vec3 direction, double t_max) const;
    Vec3 origin, normal;
    int own_surface;
};

// Per index of scene_surfaces(scene): whether that surface is opaque.
std::vector<bool> opaque_surfaces(const Scene& scene);

// The opaque surface receiver (x, y) lies on, or -1: its id in
// Receivers::surface when the image has the channel and the id names one of
// `opaque` (opaque_surfaces) that is.
int receiver_own_surface(const Receivers& receivers, const std::vector<bool>& opaque, int x, int y);

// The light arriving at one receiver point; `stream` seeds its samples (an
// area light's; a point light ignores strata and stream). 0 for a point
// behind the light's plane (the light is one-sided). `own_surface`: the index
// of the opaque surface the point lies on (above: the rays leave from the
// point, blocked below its tangent plane, the surface left out of the trace),
// or -1 (the rays leave from the point lifted by kNormalOffset).
double light_visibility(const PreparedScene& prepared, const AreaLight& light, Vec3 position, Vec3 normal,
                        int strata, std::uint64_t stream, int own_surface = -1);

}  // namespace penumbra::reference
