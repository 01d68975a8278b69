// Pismo's shadow-ray test in float64, written from the notes
// (../shared/seeds/002; docs/pismo.md "The shadow-ray test"): the reference
// the kernel description will be checked against, and the classical
// alternative at the same maps, the area-weighted average of hard shadows.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "penumbra/layered_depth_map.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::testing {

struct PismoReferenceOptions {
    int rays = 64;  // about this many per shading point, stratified per triangle by area
    // A layer occludes a point when it is nearer than the point's depth minus
    // bias_texels times the footprint of one texel at that depth.
    double bias_texels = 2;
    // With the receiver's normal n (a non-zero `normal` below), the receiver's
    // own surface (docs/pismo.md, "The receiver's own surface"): a ray to L
    // with n . (L - P) <= 0 enters P's own solid and is blocked, as the
    // truth's rays from P lifted along n are; a map's bias grows by
    // min(tan theta, max_slope) texels, theta the angle between n and the
    // direction to the map's vertex, the depth P's own surface spans across
    // one texel there.
    double max_slope = 8;
    // For measurement only (bench/pismo_error_classes): answer a part of the
    // test by tracing these casters (pismo_casters of the maps' scene) instead
    // of reading the maps, as maps of unlimited resolution would answer it.
    // Measured, not the method (docs/pismo.md, "What would remove the rest"):
    // above 0, a normal offset instead of the slope term: P is tested (and
    // its rays start) lifted along n by lift_texels texels of map 0 at P's
    // depth times sin theta, theta between n and the direction to the
    // light's centre; the bias is bias_texels alone; the own-surface rules
    // keep P's tangent plane.
    double lift_texels = 0;
    // Measured, not the method yet (docs/pismo.md, "A surface id per layer"):
    // with the receiver's surface id (`surface` >= 0 below) and the maps'
    // (PismoMaps::surface_ids), a layer of P's own surface gets the bias above
    // (the slope term's) or, with skip_own_layers, never occludes P (every
    // caster is a convex solid, which cannot block a ray above the tangent
    // plane at a point of its own surface); a layer of any other surface gets
    // other_bias_texels alone.
    bool surface_ids = false;
    bool skip_own_layers = true;
    double other_bias_texels = 1;
    // With surface_ids, laid out so that a hit's primitive is its surface's
    // index into scene_surfaces (the ids' numbering).
    const reference::PreparedScene* exact_casters = nullptr;
    bool exact_estimate = false;  // O_i on the caster crossing nearest P along R_i (none: O_i = P)
    bool exact_tests = false;     // map k's test along the ray from V_k through the point, not its pixel's centre
};

// The maps Pismo reads: the layered maps (or their maximum-depth variant) and
// the bled copies of the same for the first estimate.
struct PismoReferenceMaps {
    const reference::PismoMaps* source = nullptr;
    std::vector<LayeredDepthMap> test, bled;
    // Per test map, parallel to its depths: each layer's surface (empty: not known).
    std::vector<std::vector<std::int32_t>> test_ids;
    static PismoReferenceMaps layered(const reference::PismoMaps& maps);
    static PismoReferenceMaps maximum_depth(const reference::PismoMaps& maps);
};

// The light's visible fraction at point p, in [0, 1], over the kernel's ray
// pattern (host/src/pismo_rays.h), the same for every point.
// A zero normal: P's surface is unknown, the fixed bias alone. `surface`: P's
// surface id (Receivers::surface), -1 unknown; used with options.surface_ids.
double pismo_visibility(const PismoReferenceMaps& maps, reference::Vec3 p, const PismoReferenceOptions& options,
                        reference::Vec3 normal = {}, int surface = -1);

// The hard shadow-map test of one map at p: its nearest layer at p's pixel
// nearer than p's depth minus the bias (false outside the map).
bool hard_shadow_test(const LayeredDepthMap& map, reference::Vec3 p, double bias_texels);
// The same with P's own surface (options.max_slope, a non-zero normal).
bool hard_shadow_test(const LayeredDepthMap& map, reference::Vec3 p, reference::Vec3 normal,
                      const PismoReferenceOptions& options);
// And with P's surface id and the map's layers' (options.surface_ids).
bool hard_shadow_test(const LayeredDepthMap& map, std::span<const std::int32_t> ids, reference::Vec3 p,
                      reference::Vec3 normal, int surface, const PismoReferenceOptions& options);

// The same maps as hard shadows, each weighted by its vertex's share of the
// light's area (LightMesh::vertex_weights).
double averaged_hard_shadows(const PismoReferenceMaps& maps, reference::Vec3 p, const PismoReferenceOptions& options,
                             reference::Vec3 normal = {}, int surface = -1);

}  // namespace penumbra::testing
