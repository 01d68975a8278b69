// penumbra render-scene: a reference scene in the `penumbra shade` file
// contract, so that anyone can check a method (this library's or their own)
// against the ray-traced ground truth.
//   SM.exr  channel Z: the shadow map (light depth in [0, 1]; --depth picks the
//           first surface, the midpoint of the first two or the second, Woo 1992)
//   RX.exr  channels u, v, z (light space), P.x P.y P.z (world position),
//           N.x N.y N.z (normal), mask (1 where the receiver is valid),
//           surface (the id of the surface seen, its index among the scene's
//           surfaces, -1 where the view sees nothing: Pismo's surface ids,
//           docs/pismo.md; FLOAT like the others, exact to 2^24)
//   GT.exr  channel Y: the fraction of the light that reaches the receiver, in
//           [0, 1]: the mean transmittance to the area light's samples, or the
//           exact transmittance to a point light (one ray; --samples unused)
#include <algorithm>
#include <cmath>
#include <sstream>
#include <iostream>

#include "args.h"
#include "commands.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/output_files.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/render.h"
#include "scene_input.h"

namespace penumbra::cli {

const std::vector<std::string> kReceiverChannels = {"u", "v", "z", "P.x", "P.y", "P.z", "N.x", "N.y", "N.z", "mask", "surface"};

Image pack_receivers(const reference::Receivers& rx)
{
    Image packed(rx.width(), rx.height(), int(kReceiverChannels.size()));
    const Image* sources[] = {&rx.light_uvz, &rx.world_position, &rx.normal, &rx.mask, &rx.surface};
    int c = 0;
    for (const Image* source : sources)
        for (int s = 0; s < source->channels(); ++s, ++c)
            for (int y = 0; y < rx.height(); ++y)
                for (int x = 0; x < rx.width(); ++x) packed.at(c, x, y) = source->at(s, x, y);
    return packed;
}

ViewSize parse_view_size(const std::string& text, const std::string& option, int largest)
{
    ViewSize size{};
    char x = 0;
    std::istringstream in(text);
    if (!(in >> size.width >> x >> size.height) || x != 'x' || !in.eof() || size.width < 1 || size.height < 1 ||
        size.width > largest || size.height > largest)
        throw UsageError{"option " + option + ": '" + text + "' is not WxH with sizes in [1, " +
                         std::to_string(largest) + "]"};
    return size;
}

int strata_for_samples(int samples)
{
    if (samples < 1 || samples > 65536) throw UsageError{"option --samples: must be in [1, 65536]"};
    return std::max(1, int(std::lround(std::sqrt(double(samples)))));
}

namespace {

std::string scene_list()
{
    std::string names;
    for (const std::string& name : reference::builtin_scene_names(reference::SceneSet::All))
        names += (names.empty() ? "" : ", ") + name;
    return names;
}

std::string rays_per_receiver(const reference::Scene& scene, int strata)
{
    if (scene.light.shape == reference::LightShape::Point) return "1 ray each, point light";
    return std::to_string(strata * strata) + " rays each";
}

reference::ShadowDepth parse_shadow_depth(const std::string& text)
{
    try {
        return reference::shadow_depth_from_name(text, "--depth");
    } catch (const Error& e) {
        throw UsageError{"option --depth: " + e.message()};
    }
}

}  // namespace

int render_scene_command(const std::vector<std::string>& argv)
{
    if (!argv.empty() && argv[0] == "--help") {
        std::cout << "usage: penumbra render-scene NAME|SCENE.json --shadow-map SM.exr --receivers RX.exr --truth GT.exr\n"
                     "                             [--map-size N] [--view-size WxH] [--samples S]\n"
                     "                             [--depth first|midpoint|second]\n"
                  << "  scenes: " << scene_list() << " (or a JSON scene file)\n"
                     "  --map-size N     shadow map N x N (default: the scene's own, e.g. 1024)\n"
                     "  --view-size WxH  receivers seen from the view camera (default 320x240)\n"
                     "  --samples S      ground-truth rays per receiver, stratified (default 1024); a point\n"
                     "                   light's truth is exact, one ray each\n"
                     "  --depth D        what the shadow map stores along each light ray (Woo 1992):\n"
                     "                   first (default), midpoint of the first two surfaces, or the\n"
                     "                   second; the far plane (1) stands in for a missing second. Every\n"
                     "                   surface of opacity > 0 is a depth; fog is not\n";
        return 0;
    }
    if (argv.empty() || argv[0].rfind("--", 0) == 0) throw UsageError{"the scene name comes first (see --help)"};
    const reference::Scene scene = resolve_scene(argv[0]);
    const Args args({argv.begin() + 1, argv.end()},
                    {"--shadow-map", "--receivers", "--truth", "--map-size", "--view-size", "--samples", "--depth"}, {});
    const std::string sm_path = args.required("--shadow-map");
    const std::string rx_path = args.required("--receivers");
    const std::string gt_path = args.required("--truth");
    // A scene file is an input too; no output may replace it or another output.
    require_safe_outputs({sm_path, rx_path, gt_path}, {argv[0]}, "render-scene");
    const int map_size = args.integer("--map-size", scene.map_size);
    if (map_size < 1 || map_size > 16384) throw UsageError{"option --map-size: must be in [1, 16384]"};
    const ViewSize view = parse_view_size(args.text("--view-size", "320x240"));
    const int strata = strata_for_samples(args.integer("--samples", 1024));
    const reference::ShadowDepth depth = parse_shadow_depth(args.text("--depth", "first"));

    const Image map = reference::render_shadow_map(scene, map_size, map_size, depth);
    const reference::Receivers rx = reference::render_receivers(scene, view.width, view.height);
    const Image truth = reference::ground_truth(scene, rx, {strata});
    // All three or none: each is written in full before any replaces its target.
    OutputFiles outputs("render-scene");
    stage_exr(outputs, sm_path, map, {"Z"});
    stage_exr(outputs, rx_path, pack_receivers(rx), kReceiverChannels);
    stage_exr(outputs, gt_path, truth, {"Y"});
    outputs.publish();
    std::cout << "wrote " << sm_path << ", " << rx_path << ", " << gt_path << " (" << scene.name << ", map "
              << map_size << "^2 " << reference::shadow_depth_name(depth) << " depth, " << view.width << "x" << view.height << " receivers, " << rays_per_receiver(scene, strata) << ")\n";
    return 0;
}

}  // namespace penumbra::cli
