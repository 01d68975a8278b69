// SDF soft shadows on the reference scenes: the scene's primitives as the
// library's SDF types, baking a distance grid from a scene's analytic signed
// distance, and the settings that make the method comparable with the
// shadow-map methods (k from the light's size). docs/sdf.md derives the
// relation and gives the measured errors.
//
// This is the one place where the reference model meets penumbra/sdf.h: the
// library's SDF API has its own types (SdfVec3, SdfPrimitive) and knows
// nothing of reference scenes (docs/architecture.md).
#pragma once

#include <cstddef>
#include <vector>

#include "penumbra/reference/scene.h"
#include "penumbra/sdf.h"

namespace penumbra::reference {

inline SdfVec3 to_sdf(Vec3 v) { return {v.x, v.y, v.z}; }
inline Vec3 from_sdf(SdfVec3 v) { return {v.x, v.y, v.z}; }

// A box's Euler angles become its axes (OrientedBox::from); the other kinds
// copy their fields. No validation here: AnalyticScene checks the result.
SdfPrimitive to_sdf(const Primitive& primitive);
// The scene's primitives packed for the analytic kernel, in their order (so
// AnalyticScene's "primitives[i]" names the scene's i-th primitive).
AnalyticScene analytic_scene(const std::vector<Primitive>& primitives);

// An axis-aligned world box.
struct GridBox {
    Vec3 lo, hi;
};

// The bounded primitives' bounds (spheres, boxes, capsules) grown by
// `margin` on every side; planes crossing that box are cut by it. A scene of
// planes only gets a box of side 2 margin about the light's axis meeting the
// first plane. Throws Error(InvalidArgument) for an invalid scene or a margin
// that is not finite and >= 0.
GridBox distance_grid_box(const Scene& scene, double margin);
// With a margin of 0.02 D, D the light's distance to its reference receiver
// (as for sdf_hardness below).
GridBox distance_grid_box(const Scene& scene);

// Nodes every `voxel_size` from box.lo, enough of them to reach box.hi on
// every axis (at least 2), each holding the scene's exact signed distance
// (PreparedScene::signed_distance, in double, stored as float).
// Runs in parallel. Throws Error(InvalidArgument) for a bad scene, box or
// voxel size, or a grid of more than 2^31 - 1 nodes.
DistanceGrid bake_distance_grid(const Scene& scene, const GridBox& box, double voxel_size);

// The grid of the demo and the measured figures: distance_grid_box(scene)
// with the smallest voxel size that
// keeps it within `max_nodes` nodes (8 Mi nodes, 32 MiB, by default: 14 mm on
// contact, 5.9 mm on fence, 58 cm on large, whose 30 cm poles it then loses).
inline constexpr std::size_t kSdfGridNodes = std::size_t(1) << 23;
DistanceGrid bake_distance_grid(const Scene& scene, std::size_t max_nodes = kSdfGridNodes);

// penumbra::sdf_hardness(W, D, fit) for the scene's light: W its width (the
// geometric mean of a rectangle's sides), D its centre's distance to the
// scene's reference receiver (where the light's axis meets the ground;
// reference_depths).
double sdf_hardness(const Scene& scene, double fit = kSdfHardnessFit);

// The settings of the demo and the measured figures: rays towards the light's
// centre; k relative to each receiver's view of the light (light_width = the
// light's width, so every receiver gets sdf_hardness(W, its distance, k)):
// kSdfHardnessFit for Classic and Improved, kSdfInnerHardnessFit x W / the
// light's mean breadth for InnerPenumbra (pi / 4 for a square light, 1 for a
// disk: the light's extent across an edge of any direction); the estimate
// given (default: the inner-penumbra one); hit epsilon 1e-5 D (D
// as above); receivers lifted along their normals by 4 epsilon and t_min
// 4 epsilon; 256 steps. Use with the receivers' normals
// (render_receivers(...).normal).
SdfOptions sdf_options_for(const Scene& scene, SdfEstimate estimate = SdfEstimate::InnerPenumbra);

}  // namespace penumbra::reference
