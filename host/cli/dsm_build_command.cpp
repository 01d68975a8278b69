// penumbra dsm-build: a reference scene's deep shadow map (issue 14, item 6),
// written as an OpenEXR deep file (penumbra/deep_exr.h) for `shade --method dsm`.
//   --scene S      a built-in scene name or a JSON scene file (as render-scene)
//   --out DSM.exr  deep scanline file: Z, ZBack, A and penumbra.T per sample
// The generator and its choices: penumbra/reference/deep_map.h and
// docs/reference.md, "Generating a deep shadow map". Bad options exit with 2
// and one line naming the option; the file is written whole or not at all.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include "args.h"
#include "commands.h"
#include "penumbra/deep_exr.h"
#include "penumbra/error.h"
#include "penumbra/output_files.h"
#include "penumbra/reference/deep_map.h"
#include "scene_input.h"

namespace penumbra::cli {
namespace {

std::string help()
{
    char gaussian[128];
    std::snprintf(gaussian, sizeof gaussian, "radius %g pixel, sigma %g", reference::kDeepGaussianRadius,
                  reference::kDeepGaussianSigma);
    return "usage: penumbra dsm-build --scene NAME|SCENE.json --out DSM.exr [--size N] [--samples K]\n"
           "                          [--tolerance E] [--filter box|gaussian] [--seed S]\n"
           "  a deep shadow map (Lokovic and Veach 2000) of a reference scene, as an OpenEXR deep file\n"
           "  --size N          the map is N x N pixels, N in [1, 16384] (default 512)\n"
           "  --samples K       stratified jittered light rays per pixel, in [1, 4096] (default 16)\n"
           "  --tolerance E     compression error bound in [0, 1] (default 0.25/sqrt(K), the paper's)\n"
           "  --filter F        box (the pixel's own samples, default) or gaussian (" +
           std::string(gaussian) + "):\n"
           "                    the samples within the radius of the pixel's centre, its neighbours' too\n"
           "  --seed S          names the samples' streams (default 0)\n";
}

// The library names its option; the tool names its flag.
[[noreturn]] void reword(const Error& e)
{
    for (const char* name : {"size", "samples", "tolerance", "filter"})
        if (e.parameter() == name) throw UsageError{"option --" + std::string(name) + ": " + e.message()};
    throw e;
}

reference::DeepMapOptions options_from(const Args& args)
{
    reference::DeepMapOptions o;
    o.size = args.integer("--size", o.size);
    o.samples = args.integer("--samples", o.samples);
    if (args.get("--tolerance")) o.tolerance = args.number("--tolerance", 0);
    const int seed = args.integer("--seed", 0);
    if (seed < 0) throw UsageError{"option --seed: must be >= 0"};
    o.seed = std::uint64_t(seed);
    try {
        o.filter = reference::deep_map_filter_from_name(args.text("--filter", "box"), "filter");
    } catch (const Error& e) {
        reword(e);
    }
    return o;
}

std::string fixed(double value, int digits)
{
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

}  // namespace

int dsm_build_command(const std::vector<std::string>& argv)
{
    const Args args(argv, {"--scene", "--out", "--size", "--samples", "--tolerance", "--filter", "--seed"},
                    {"--help"});
    if (args.flag("--help")) {
        std::cout << help();
        return 0;
    }
    const std::string scene_arg = args.required("--scene");
    const std::string out_path = args.required("--out");
    require_safe_outputs({out_path}, {scene_arg}, "dsm-build");
    const reference::DeepMapOptions options = options_from(args);
    const reference::Scene scene = resolve_scene(scene_arg);

    const auto start = std::chrono::steady_clock::now();
    reference::DeepMapStats stats;
    DeepShadowMap map;
    try {
        map = reference::render_deep_shadow_map(scene, options, &stats);
    } catch (const Error& e) {
        reword(e);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_deep_exr(out_path, map);

    const std::size_t uncompressed = stats.uncompressed_bytes(map.width(), map.height());
    std::cout << "wrote " << out_path << " (" << scene.name << ", " << map.width() << "^2, " << options.samples
              << " samples/pixel, " << reference::deep_map_filter_name(options.filter) << " filter, tolerance "
              << fixed(stats.tolerance, 4) << "): " << std::size_t(map.width()) * std::size_t(map.height())
              << " pixels, " << map.vertex_count() << " vertices (" << stats.filtered_vertices
              << " uncompressed), " << map.bytes() << " bytes (" << std::filesystem::file_size(out_path)
              << " in the file), compression ratio " << fixed(double(uncompressed) / double(map.bytes()), 2)
              << ", " << fixed(seconds, 2) << " s for " << stats.samples << " rays\n";
    return 0;
}

}  // namespace penumbra::cli
