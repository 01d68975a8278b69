// Pismo's maps for the tool: rendered from a scene (the reference tracer,
// penumbra/reference/pismo_maps.h) with the options `pismo-build` and
// `shade --method pismo` share, or read from a directory pismo-build wrote.
#pragma once

#include <set>
#include <span>
#include <string>
#include <vector>

#include "args.h"
#include "penumbra/pismo_files.h"
#include "penumbra/reference/pismo_maps.h"

namespace penumbra::cli {

// The options that shape the maps: --light-level L (default 2), --map-size N
// (default 512), --layers K (default 8).
inline const std::set<std::string> kPismoMapFlags = {"--light-level", "--map-size", "--layers"};
inline constexpr int kDefaultPismoLevel = 2;

struct PismoBuild {
    int level = kDefaultPismoLevel;
    reference::LayeredMapOptions maps;
};

// Their help lines, for `pismo-build --help` and `shade --help`.
std::string pismo_map_options_help();

// The options as given; their ranges are checked by the build (light_mesh,
// render_layered_depth_map), whose errors render_pismo_set rewords.
PismoBuild pismo_build_from(const Args& args);

// The scene's maps at `build`, cameras fitted to `region` when it is not
// empty (else holding the light's frustum). A value out of range, maps of
// more pixels in all than --max-pixels (what read_pismo_maps would refuse)
// or a scene without an area light is a UsageError naming the option or the
// scene.
PismoMapSet render_pismo_set(const reference::Scene& scene, const PismoBuild& build,
                             std::span<const reference::Vec3> region = {});

// The receivers' world positions in RX.exr (channels P.x, P.y, P.z; only
// where its mask channel, when it has one, is set): a region to fit the
// cameras to. The image's errors name the file; `command` names the line.
std::vector<reference::Vec3> receiver_region_from(const std::string& path, const std::string& command);

// The channels of the world positions Pismo shades.
inline const std::vector<std::string> kWorldPositionChannels = {"P.x", "P.y", "P.z"};
// RX.exr's optional channel of surface ids (docs/pismo.md, "Surface ids in
// the files"): render-scene writes it as FLOAT, -1 where the view sees nothing.
inline constexpr const char* kSurfaceChannel = "surface";

// What `shade` reads from RX.exr for Pismo: P.x, P.y, P.z; then N.x, N.y, N.z
// when the file has all three; then surface when it has it, which needs the
// normals (the kernel's 7th plane follows the 6 of positions and normals):
// surface without them is an Error(InvalidData, command) naming the file.
std::vector<std::string> pismo_receiver_channels(const std::string& path, const std::string& command);

// The surface ids of `receivers` (its 7th plane, when it has one), each -1
// (unknown: that receiver shades without ids) or an integer in [0, the maps'
// surface_count), or in [0, kPismoMaxSurfaceId] when the maps carry no ids.
// Error(InvalidData, command) naming the file, the pixel, the value and the fix.
void check_receiver_surfaces(const Image& receivers, const PismoMapSet& set, const std::string& path,
                             const std::string& command);

}  // namespace penumbra::cli
