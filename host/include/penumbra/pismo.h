// Pismo (Neulander, "Pismo: Parallax-Interpolated Shadow Map Occlusion",
// Rhythm & Hues; notes in ../shared/seeds/002): area-light soft shadows from
// depth maps rendered at the vertices of a triangle mesh of the light.
// Each shadow ray from a shading point P to a point L on a light triangle is
// answered by three lookups, into the maps of that triangle's corners, with
// barycentric and parallax interpolation (kernels/pismo.h; docs/pismo.md).
//
// Receivers: world positions, planes x, y, z (the reference's
// `world_position` render), in the units of the maps' cameras.
// Output: one plane, the light's visible fraction in [0, 1].
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/layered_depth_map.h"
#include "penumbra/parameter_range.h"

namespace penumbra {

namespace detail {
struct PismoArrays;  // host/src/pismo_pack.h
}

// Which depths the shadow-ray test reads: every layer of the layered maps,
// or the single-channel maximum-depth variant (maximum_depth_map), which the
// source says is accurate only outside the casters' convex hull.
enum class PismoDepths { Layered, MaximumDepth };

// The light as a mesh and one map per vertex, ready for pismo_shade: the
// maps the test reads (layered or maximum-depth) and their bled copies for the
// first estimate (bleed_empty_pixels), both made once, here, and held packed
// as the kernel reads them, so that shading copies no map. Copies share them.
class PismoMaps {
public:
    PismoMaps() = default;  // no maps: pismo_shade refuses it

    // vertices: world positions of the light mesh; triangles: indices into
    // them; maps: the layered map of each vertex, in vertex order, each
    // camera at its vertex (MapCamera::position). Error(InvalidArgument),
    // parameter "maps", for no vertex or no triangle, a count of maps other
    // than of vertices, an index out of range, a triangle of zero area, a map
    // of 0 pixels, maps of different sizes, a camera away from its vertex, or
    // more than 2^31 depths in all.
    // surface_ids (optional; docs/pismo.md, "A surface id per layer"): per
    // map, parallel to its depths(), the id of the surface each layer crosses,
    // in [0, kPismoMaxSurfaceId]; Error(InvalidArgument), parameter
    // "surface-ids", for a count other than the maps' or a map's layers', an
    // id out of range, or ids with the maximum-depth maps (whose one layer
    // per pixel is no crossing of one surface).
    PismoMaps(std::vector<std::array<double, 3>> vertices, std::vector<std::array<int, 3>> triangles,
              const std::vector<LayeredDepthMap>& maps, PismoDepths depths = PismoDepths::Layered,
              const std::vector<std::vector<std::int32_t>>& surface_ids = {});

    const std::vector<std::array<double, 3>>& vertices() const noexcept { return vertices_; }
    const std::vector<std::array<int, 3>>& triangles() const noexcept { return triangles_; }
    // The maps as held, rebuilt from the packed arrays (a copy: for inspection).
    std::vector<LayeredDepthMap> test_maps() const;
    std::vector<LayeredDepthMap> bled_maps() const;
    PismoDepths depths() const noexcept { return depths_; }
    bool has_surface_ids() const noexcept { return has_surface_ids_; }
    bool empty() const noexcept { return vertices_.empty(); }
    std::size_t bytes() const noexcept;  // of the test and bled maps as held
    // The library's own: the packed arrays (nullptr when empty).
    const detail::PismoArrays* arrays() const noexcept { return arrays_.get(); }

private:
    std::vector<std::array<double, 3>> vertices_;
    std::vector<std::array<int, 3>> triangles_;
    std::shared_ptr<const detail::PismoArrays> arrays_;
    PismoDepths depths_ = PismoDepths::Layered;
    bool has_surface_ids_ = false;
};

// About this many rays per shading point, stratified per triangle by area:
// n x n strata with n = max(1, round(sqrt(rays x area share))), so a mesh of
// many small triangles casts at least one ray through each.
inline constexpr int kPismoMaxRays = 4096;
inline constexpr ParameterRange kPismoRaysRange{
    "rays", "rays", 1, kPismoMaxRays, false, false,
    ", a 64 x 64 grid of strata on a one-triangle light; past it the maps' texels, not the rays, limit the answer"};
// The depth bias in texel footprints at the point's depth.
inline constexpr ParameterRange kPismoBiasRange{"bias-texels", "bias-texels", 0, 64, false, false};

// With normals, a map's bias grows by min(tan theta, this) texels, theta the
// angle between the receiver's normal and the direction to the map's vertex
// (docs/pismo.md, "The receiver's own surface").
inline constexpr float kPismoMaxSlopeTexels = 8.0f;

// With surface ids (maps made with them and receivers with a 7th plane), a
// layer of another surface than the receiver's occludes with this bias, in
// texels, and a layer of its own surface never (docs/pismo.md, "A surface id
// per layer": 0, 0.5 and 1 measured alike; 1 leaves a margin for surfaces
// that touch). Ids are stored as floats: at most 2^24 - 1.
inline constexpr float kPismoOtherSurfaceBiasTexels = 1.0f;
inline constexpr std::int32_t kPismoMaxSurfaceId = (1 << 24) - 1;

struct PismoOptions {
    int rays = 64;            // kPismoRaysRange
    float bias_texels = 2.0f;  // kPismoBiasRange (docs/pismo.md: why 2)
};

// Throws Error(InvalidArgument) naming the parameter: rays, bias-texels,
// maps (empty), receivers (3 channels x, y, z, world positions, or 6: then
// the normals' x, y, z, and the receiver's own surface takes part, or 7: then
// the id of the receiver's surface, -1 unknown, used when the maps carry
// surface ids: an integer in [-1, kPismoMaxSurfaceId], else InvalidData naming
// the pixel; not empty, finite), out (1 channel of the receivers' size).
void pismo_shade(Context& context, const PismoMaps& maps, const Image& receivers, const PismoOptions& options,
                 Image& out);
Image pismo_shade(Context& context, const PismoMaps& maps, const Image& receivers, const PismoOptions& options = {});

}  // namespace penumbra
