// Pismo's maps as files, the output of `penumbra pismo-build` and an input of
// `penumbra shade --method pismo --pismo-maps DIR` (docs/pismo.md, "Files").
//
// A directory holds
//   pismo.json       the manifest: {"format": "penumbra pismo maps", "version": 2,
//                    "vertices": [[x, y, z], ...], "triangles": [[i, j, k], ...],
//                    "maps": ["map-0000.exr", ...]} (one map per vertex, in
//                    vertex order, named relative to the directory), with
//                    surface ids "surfaces": N (every id is below N, the
//                    scene's count of surfaces) and, for people, what built
//                    them ("scene", "level", "fixation")
//   map-NNNN.exr     one layered depth map per vertex (penumbra/layered_exr.h),
//                    its camera in its header, with "surfaces" its ids in the
//                    deep UINT channel surface
// Version 1 (before surface ids) still reads, as a set without ids.
// The layered maps are stored; the bled and maximum-depth maps are derived from
// them when read (PismoMaps, penumbra/pismo.h), a preprocess of milliseconds.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "penumbra/exr_io.h"
#include "penumbra/layered_depth_map.h"

namespace penumbra {

// The light mesh and its layered maps, as stored.
struct PismoMapSet {
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<int, 3>> triangles;
    std::vector<LayeredDepthMap> maps;  // one per vertex, in vertex order
    // Optional (docs/pismo.md, "A surface id per layer"): per map, parallel to
    // its depths(), the id of the surface each layer crosses; empty: no ids.
    std::vector<std::vector<std::int32_t>> surface_ids;
    // With ids, how many surfaces they index (the scene's): every layer's id,
    // and every receiver's shaded with these maps, is below it. 0 without ids.
    int surface_count = 0;
    // For people reading the manifest; not read back for shading.
    std::string scene;
    int level = 0;
    std::array<double, 3> fixation{0, 0, 0};
};

inline constexpr const char* kPismoManifest = "pismo.json";
// The most vertices a manifest may list: a rectangle light at level 5 has
// 1089, a disk 3169 (kMaxLightLevel of penumbra/reference/pismo_maps.h).
inline constexpr int kPismoMaxVertices = 4096;

// Writes every map and then the manifest into `dir` (which must exist), all
// or none (penumbra/output_files.h): a failure leaves the directory's files as
// they were. Error(InvalidArgument) for a set read_pismo_maps would refuse
// (counts, indices, a camera away from its vertex; parameter "surface-ids" for
// ids of the wrong count or outside [0, surface_count)); Error(Io) for the files.
void write_pismo_maps(const std::string& dir, const PismoMapSet& set);

// Reads and checks a directory written by write_pismo_maps. Every failure is an
// Error naming the file: Io for a missing, unreadable or malformed manifest
// (not JSON, a field missing or of the wrong type, counts over
// kPismoMaxVertices or that disagree, an index out of range, a map name that
// leaves the directory) and for the maps' files (read_layered_exr's errors);
// InvalidData for a map whose camera is not at its vertex or whose size
// differs from the first map's, and, when the manifest counts "surfaces"
// (then an integer in [1, kPismoMaxSurfaceId + 1], else Io), for a map without
// channel surface or with an id not below the count (naming pixel and layer). `limits.max_pixels` bounds the pixels of all
// maps together; each map is read only when the manifest has been checked,
// and no map is read past that budget.
PismoMapSet read_pismo_maps(const std::string& dir, const ExrReadLimits& limits = {});

}  // namespace penumbra
