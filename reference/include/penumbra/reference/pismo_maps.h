// The maps of Pismo (Neulander, "Pismo: Parallax-Interpolated Shadow Map
// Occlusion"; notes in ../shared/seeds/002): the area light as a triangle
// mesh, one perspective layered depth map per mesh vertex, every camera
// fixated on one point central to the casting geometry. docs/pismo.md states
// the choices.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "penumbra/layered_depth_map.h"
#include "penumbra/pismo_files.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {

// A planar triangle mesh of the light, in world space.
//   Rectangle: level 0 is its two triangles (4 vertices, corners).
//   Disk: level 0 is a fan of 6 triangles about the centre (7 vertices: the
//         centre and a hexagon on the rim).
// Each further level splits every triangle into four at its edges' midpoints;
// a midpoint on the disk's rim is moved out onto the circle, so the mesh
// converges to the disk (a rectangle's mesh is the rectangle at every level).
// Vertices shared by triangles are stored once. A rectangle at level L has
// (2^L + 1)^2 vertices: 4, 9, 25, 81, 289, 1089 at levels 0 to 5.
struct LightMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> triangles;  // indices into vertices

    double triangle_area(int triangle) const;
    double area() const;
    // Each vertex's share of the mesh's area (a third of each triangle it
    // belongs to, over the whole): the weights of the averaged hard shadows.
    std::vector<double> vertex_weights() const;
};

inline constexpr int kMaxLightLevel = 5;

// Error(InvalidArgument, "light_mesh") for a point light or a level outside
// [0, kMaxLightLevel].
LightMesh light_mesh(const AreaLight& light, int level);

// What the maps hold: the scene's surfaces without the planes whose solid
// (the half-space behind the plane) holds no point of the light. Such a
// plane cannot occlude any segment from a point outside it to the light (both
// ends lie in the complementary half-space, which is convex), so it is a
// receiver only; leaving it out keeps empty the pixels that see no caster,
// which the bled maps fill. scene_surfaces order otherwise.
std::vector<Primitive> pismo_casters(const Scene& scene);
// The index into scene_surfaces(scene) of each of pismo_casters(scene).
std::vector<int> pismo_caster_surfaces(const Scene& scene);

// The point every map camera looks at: the centre of the bounding box of the
// bounded casters (spheres, boxes, capsules, hair), or, without any, the
// point on the light's axis halfway through its camera's depth range.
Vec3 pismo_fixation_point(const Scene& scene);

// Where a map's pixel grid sits: its camera turned so that the fixation point
// lands (x, y) texels of a size x size map off the image's centre. The maps
// all look at one point, so on the surface through it they share one pixel
// grid: a caster there a texel or two wide is rounded to whole pixels alike
// in every map, and no number of maps averages that away. Shifting each grid
// by a different fraction of a texel makes the rounding differ from map to
// map (docs/pismo.md, "Where fence's error comes from"). size 0: no turn.
struct SubTexelShift {
    double x = 0, y = 0;
    int size = 0;
};

// The shift of the map at vertex index `vertex`: the R2 sequence (Roberts
// 2018, the plastic number's inverse powers), ((0.5 + j a1) mod 1 - 0.5,
// (0.5 + j a2) mod 1 - 0.5), a1 = 0.7548776662, a2 = 0.5698402910: low
// discrepancy over any run of vertices, in [-1/2, 1/2)^2, none at vertex 0.
SubTexelShift pismo_subtexel_shift(int vertex, int size);

// The camera of the map at `vertex`: at the vertex, looking at `fixation`,
// rows "down" against the light's `up`. Its field of view is the narrowest
// square one (times 1.02) that holds the scene's light frustum from the
// nearest depth of the casters' bounding box to the far plane: the frustum
// slab is the convex hull of its eight corners, so holding the corners holds
// it all, every receiver the light camera sees and every caster between them
// and the light. Error(InvalidArgument) when a corner lies behind the vertex.
// With `shift`, turned by it, its field of view fitted again so that it still
// holds all that.
MapCamera pismo_vertex_camera(const Scene& scene, Vec3 vertex, Vec3 fixation, SubTexelShift shift = {});

// The same camera fitted to a region instead of the whole frustum: the
// narrowest square field of view (times 1.02) that holds every point of
// `region` (the receivers to be shaded) and the corners of the bounded
// casters' bounding box, so their convex hull. The light frustum of a scene
// holds far more ground than a view sees: fitted maps spend their texels on
// the receivers that are shaded and on what shadows them (docs/pismo.md,
// "Cameras fitted to the receivers"). A caster outside the box (an unbounded
// plane) is seen only where it falls inside. Error(InvalidArgument) when a
// point lies behind the vertex.
MapCamera pismo_fitted_camera(const Scene& scene, Vec3 vertex, Vec3 fixation, std::span<const Vec3> region,
                              SubTexelShift shift = {});

// The world positions of the valid receivers (mask): a region to fit to.
std::vector<Vec3> receiver_region(const Receivers& rx);

struct LayeredMapOptions {
    int size = 512;        // each map is size x size, in [1, 8192]
    int max_layers = 8;    // per pixel, in [1, 64]: the nearest this many surfaces are kept
    // Proximity pruning: a surface within prune * d of the last kept depth d
    // (the two faces of a strand thinner than that, a box's coincident faces)
    // adds no layer. In [0, 0.1].
    double prune = 1e-3;
    // render_pismo_maps: each map's grid shifted by pismo_subtexel_shift (off:
    // every grid centred on the fixation point, as before; kept to measure it).
    bool shift_grids = true;
};

// The layered depth map of `camera` over the casters (pismo_casters of a
// validated scene): per pixel, the ray through its centre and the radial
// distance of every surface crossing (entering and leaving each solid), pruned
// and capped as above. Rows in parallel; the result does not depend on the
// thread count. Error(InvalidArgument) naming the option out of range.
// With `crossed`, it is set to the caster (its index in `casters`) each layer
// crosses, parallel to the map's depths().
LayeredDepthMap render_layered_depth_map(const PreparedScene& casters, const MapCamera& camera,
                                         const LayeredMapOptions& options,
                                         std::vector<std::int32_t>* crossed = nullptr);

struct PismoMaps {
    LightMesh mesh;
    Vec3 fixation;
    std::vector<LayeredDepthMap> maps;  // one per mesh vertex, in vertex order
    // Per map, parallel to its depths(): the surface each layer crosses, its
    // index into scene_surfaces(scene), as Receivers::surface names the
    // receiver's (docs/pismo.md, "A surface id per layer").
    std::vector<std::vector<std::int32_t>> surface_ids;
};

// The mesh at `level` and a layered map from each of its vertices: cameras of
// pismo_vertex_camera, or of pismo_fitted_camera when `region` is not empty,
// each shifted by pismo_subtexel_shift unless options.shift_grids is off.
PismoMaps render_pismo_maps(const Scene& scene, int level, const LayeredMapOptions& options,
                            std::span<const Vec3> region = {});

// The same, as the library's set of maps (penumbra/pismo_files.h: what
// pismo-build writes and pismo_shade's maps are made of).
PismoMapSet render_pismo_map_set(const Scene& scene, int level, const LayeredMapOptions& options,
                                 std::span<const Vec3> region = {});

}  // namespace penumbra::reference
