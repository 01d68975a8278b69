// penumbra pismo-build: a reference scene's Pismo maps (issue 15), written to
// a directory (penumbra/pismo_files.h) for `shade --method pismo --pismo-maps`.
//   --scene S           a built-in scene name or a JSON scene file (as render-scene)
//   --out DIR           created if needed; pismo.json and map-NNNN.exr (with each
//                       layer's surface id), all or none
//   --light-level L, --map-size N, --layers K   the maps (pismo_input.h)
//   --receivers RX.exr  fit the cameras to these receivers (channels P.x, P.y,
//                       P.z, and mask when present) instead of the light's frustum
// The maps and their choices: docs/pismo.md. Bad options exit with 2 and one
// line naming the option.
#include <chrono>
#include <iomanip>
#include <iostream>
#include <string>

#include "args.h"
#include "commands.h"
#include "output_directory.h"
#include "penumbra/output_files.h"
#include "penumbra/pismo_files.h"
#include "pismo_input.h"
#include "scene_input.h"

namespace penumbra::cli {
namespace {

std::string help()
{
    return "usage: penumbra pismo-build --scene NAME|SCENE.json --out DIR [--light-level L] [--map-size N]\n"
           "                            [--layers K] [--receivers RX.exr]\n"
           "  Pismo's maps: the area light as a triangle mesh and a layered depth map from each vertex,\n"
           "  written to DIR as pismo.json and one deep OpenEXR file per map, each layer with the id of the\n"
           "  surface it crosses (channel surface; format version 2, docs/pismo.md)\n" +
           pismo_map_options_help() +
           "  --receivers RX.exr  fit the cameras to these receivers (P.x, P.y, P.z; mask if present)\n"
           "                      instead of the light's whole frustum\n";
}

}  // namespace

int pismo_build_command(const std::vector<std::string>& argv)
{
    std::set<std::string> valued = {"--scene", "--out", "--receivers"};
    valued.insert(kPismoMapFlags.begin(), kPismoMapFlags.end());
    const Args args(argv, valued, {"--help"});
    if (args.flag("--help")) {
        std::cout << help();
        return 0;
    }
    const std::string scene_arg = args.required("--scene");
    const std::string out_dir = args.required("--out");
    const PismoBuild build = pismo_build_from(args);
    const reference::Scene scene = resolve_scene(scene_arg);
    const std::vector<reference::Vec3> region =
        args.get("--receivers") ? receiver_region_from(*args.get("--receivers"), "pismo-build")
                                : std::vector<reference::Vec3>{};
    create_output_directory(out_dir, "--out");

    const auto start = std::chrono::steady_clock::now();
    const PismoMapSet set = render_pismo_set(scene, build, region);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_pismo_maps(out_dir, set);

    std::size_t bytes = 0, layers = 0;
    for (const LayeredDepthMap& map : set.maps) bytes += map.bytes(), layers += map.depths().size();
    std::cout << "wrote " << out_dir << " (" << scene.name << ", level " << build.level << ", "
              << set.triangles.size() << " triangles, " << set.maps.size() << " maps of " << build.maps.size << "^2, "
              << (region.empty() ? "cameras holding the light's frustum" : "cameras fitted to the receivers")
              << (set.surface_ids.empty() ? "" : ", each layer's surface id")
              << "): " << layers << " depths, " << bytes << " bytes of layered maps, " << std::fixed << std::setprecision(2)
              << seconds << " s to render\n";
    return 0;
}

}  // namespace penumbra::cli
