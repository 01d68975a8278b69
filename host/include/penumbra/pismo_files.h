// Pismo's maps as files, the output of `penumbra pismo-build` and an input of
// `penumbra shade --method pismo --pismo-maps DIR` (docs/pismo.md, "Files").
//
// A directory holds
//   pismo.json       the manifest: {"format": "penumbra pismo maps", "version": 1,
//                    "vertices": [[x, y, z], ...], "triangles": [[i, j, k], ...],
//                    "maps": ["map-0000.exr", ...]} (one map per vertex, in
//                    vertex order, named relative to the directory) and, for
//                    people, what built them ("scene", "level", "fixation")
//   map-NNNN.exr     one layered depth map per vertex (penumbra/layered_exr.h),
//                    its camera in its header
// The layered maps are stored; the bled and maximum-depth maps are derived from
// them when read (PismoMaps, penumbra/pismo.h), a preprocess of milliseconds.
#pragma once

#include <array>
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
// (counts, indices, a camera away from its vertex); Error(Io) for the files.
void write_pismo_maps(const std::string& dir, const PismoMapSet& set);

// Reads and checks a directory written by write_pismo_maps. Every failure is an
// Error naming the file: Io for a missing, unreadable or malformed manifest
// (not JSON, a field missing or of the wrong type, counts over
// kPismoMaxVertices or that disagree, an index out of range, a map name that
// leaves the directory) and for the maps' files (read_layered_exr's errors);
// InvalidData for a map whose camera is not at its vertex or whose size
// differs from the first map's. `limits.max_pixels` bounds the pixels of all
// maps together; each map is read only when the manifest has been checked,
// and no map is read past that budget.
PismoMapSet read_pismo_maps(const std::string& dir, const ExrReadLimits& limits = {});

}  // namespace penumbra
