// SDF soft shadows on the reference scenes: baking a distance grid from a
// scene's analytic signed distance, and the settings that make the method
// comparable with the shadow-map methods (k from the light's size).
// docs/sdf.md derives the relation and gives the measured errors.
#pragma once

#include <cstddef>

#include "penumbra/reference_scene.h"
#include "penumbra/sdf.h"

namespace penumbra {

// An axis-aligned world box.
struct GridBox {
    reference::Vec3 lo, hi;
};

// The bounded primitives' bounds (spheres, boxes, capsules) grown by
// `margin` on every side; planes crossing that box are cut by it. A scene of
// planes only gets a box of side 2 margin about the light's axis meeting the
// first plane. Throws Error(InvalidArgument) for an invalid scene or a margin
// that is not finite and >= 0.
GridBox distance_grid_box(const reference::Scene& scene, double margin);
// With a margin of 0.02 D, D the light's distance to its reference receiver
// (as for sdf_hardness below).
GridBox distance_grid_box(const reference::Scene& scene);

// Nodes every `voxel_size` from box.lo, enough of them to reach box.hi on
// every axis (at least 2), each holding the scene's exact signed distance
// (reference::PreparedScene::signed_distance, in double, stored as float).
// Runs in parallel. Throws Error(InvalidArgument) for a bad scene, box or
// voxel size, or a grid of more than 2^31 - 1 nodes.
DistanceGrid bake_distance_grid(const reference::Scene& scene, const GridBox& box, double voxel_size);

// The grid of the demo and the measured figures: distance_grid_box(scene)
// with the smallest voxel size that
// keeps it within `max_nodes` nodes (8 Mi nodes, 32 MiB, by default: 14 mm on
// contact, 5.9 mm on fence, 58 cm on large, whose 30 cm poles it then loses).
inline constexpr std::size_t kSdfGridNodes = std::size_t(1) << 23;
DistanceGrid bake_distance_grid(const reference::Scene& scene, std::size_t max_nodes = kSdfGridNodes);

// The light's half-angle from distance D is about W / (2 D) for a light of
// width W (a square's side, a disk's diameter); a ray whose clearance angle
// h / t reaches it sees the whole light. k = fit 2 D / W makes the estimate
// reach 1 at 1 / fit of that angle. The estimate is 0 where the ray to the
// light's centre is blocked (where the truth is still 1/2), so it sees only
// the outer half of a penumbra; fit = 2 minimises the squared error across a
// straight edge's penumbra (docs/sdf.md derives it) and, measured against the
// ground truth, is within 1% of the best fit on contact, overlap and grazing.
inline constexpr double kSdfHardnessFit = 2.0;
double sdf_hardness(double light_width, double distance, double fit = kSdfHardnessFit);
// With D the distance from the light's centre to the scene's reference
// receiver (where the light's axis meets the ground; reference::reference_depths).
double sdf_hardness(const reference::Scene& scene, double fit = kSdfHardnessFit);

// The settings of the demo and the measured figures: rays towards the light's
// centre; k = kSdfHardnessFit relative to each receiver's view of the light
// (light_width = the light's width, so every receiver gets
// sdf_hardness(W, its distance)); the estimate given; hit epsilon 1e-5 D (D
// as above); receivers lifted along their normals by 4 epsilon and t_min
// 4 epsilon; 256 steps. Use with the receivers' normals
// (reference::render_receivers(...).normal).
SdfOptions sdf_options_for(const reference::Scene& scene, SdfEstimate estimate = SdfEstimate::Classic);

}  // namespace penumbra
