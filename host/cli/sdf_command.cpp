// penumbra sdf-shade: SDF soft shadows (docs/sdf.md), file contract:
//   --scene S       a built-in scene name or a JSON scene: its primitives
//                   (marched analytically, or through a grid baked from them
//                   with --source grid) and its light
//   --grid G.pnsdf  a distance grid file (docs/sdf.md, "Grid files"); the light
//                   and k then come from the options
//   RX.exr          float channels P.x, P.y, P.z: world positions; N.x, N.y, N.z
//                   (unit normals) when the receivers are lifted along them
//                   (--normal-offset, on by default with --scene). Other
//                   channels (the shade contract's u, v, z; render-scene's
//                   mask) may be present and are ignored.
//   OUT.exr         float channel Y: visibility in [0, 1] on the receivers'
//                   grid; with --steps also `steps`, each ray's distance
//                   evaluations.
// penumbra sdf-bake: a scene's grid into a grid file.
// Bad input exits with 2 and one line naming the file, channel or option; the
// output is written atomically.
#include "sdf_command.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include "args.h"
#include "input_limits.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/output_files.h"
#include "penumbra/reference.h"
#include "penumbra/reference/sdf_scene.h"
#include "penumbra/sdf.h"
#include "scene_input.h"

namespace penumbra::cli {
namespace {

const char* kShadeHelp =
    "usage: penumbra sdf-shade (--scene NAME|SCENE.json | --grid GRID.pnsdf) --receivers RX.exr --out OUT.exr\n"
    "                          [options]\n"
    "  RX.exr: float channels P.x, P.y, P.z (world positions) and, for --normal-offset > 0, N.x, N.y, N.z\n"
    "  (render-scene writes both); OUT.exr: float channel Y, visibility in [0, 1] (and steps with --steps).\n"
    "options:\n"
    "  --source S            with --scene: analytic (default: the primitives) or grid (baked from them)\n"
    "  --voxel V             grid baked from --scene: node spacing in world units (default: 8 Mi nodes)\n"
    "  --estimate E          inner (default: signed k h / t through solids, both halves of a penumbra),\n"
    "                        classic (k h / t, 0 once the ray hits) or improved (closest approach from two steps)\n"
    "  --k K                 hardness > 0 (default with --scene, relative to the light's width: inner pi/4\n"
    "                        for a square light, 1 for a disk; classic and improved 2)\n"
    "  --light-width W       > 0: k is relative to the light's half-angle seen from each receiver\n"
    "                        (default with --scene: the scene light's width; 0 = k is absolute)\n"
    "  --light-position X,Y,Z  rays end at the light's centre (default with --scene: the scene's light)\n"
    "  --light-direction X,Y,Z rays go towards a distant light, up to --t-max\n"
    "  --t-min T --t-max T   march interval along each ray (world units; t-max > t-min)\n"
    "  --max-steps N         distance evaluations per ray, >= 1 (default 256 with --scene, else 128)\n"
    "  --hit-epsilon E       > 0: a distance below E is a hit (classic, improved); the least step (inner)\n"
    "  --normal-offset O     lift receivers along N by O >= 0 (needs N.x, N.y, N.z)\n"
    "  --steps               also write channel `steps`\n"
    "  --backend B           auto (default), simd, opencl or scalar\n"
    "With --scene the defaults are sdf_options_for(scene): epsilon 1e-5 D, t-min and normal offset 4e-5 D,\n"
    "D the light's distance to the ground on its axis (docs/sdf.md).\n";

const char* kBakeHelp =
    "usage: penumbra sdf-bake --scene NAME|SCENE.json --out GRID.pnsdf [--voxel V [--margin M]]\n"
    "  samples the scene's signed distance on a grid over its bounded primitives (grown by M, default\n"
    "  2% of the light's distance) every V world units (default: the finest within 8 Mi nodes).\n";

float positive(const Args& args, const std::string& name, float fallback, bool allow_zero = false)
{
    const float v = args.number(name, fallback);
    if (!(v > 0.0f || (allow_zero && v == 0.0f)))
        throw UsageError{"option " + name + ": must be " + (allow_zero ? ">= 0" : "> 0") + " (got " +
                         std::to_string(v) + ")"};
    return v;
}

reference::Vec3 triple(const Args& args, const std::string& name)
{
    const std::string text = *args.get(name);
    std::stringstream in(text);
    double v[3];
    char comma1 = 0, comma2 = 0;
    in >> v[0] >> comma1 >> v[1] >> comma2 >> v[2];
    if (!in || comma1 != ',' || comma2 != ',' || !(in >> std::ws).eof() || !std::isfinite(v[0]) ||
        !std::isfinite(v[1]) || !std::isfinite(v[2]))
        throw UsageError{"option " + name + ": '" + text + "' is not X,Y,Z (three finite numbers)"};
    return {v[0], v[1], v[2]};
}

// Names the file, the channel and the first NaN or infinite pixel.
void check_finite(const Image& image, const std::string& path, const std::vector<std::string>& names)
{
    for (int c = 0; c < image.channels(); ++c)
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
                if (!std::isfinite(image.at(c, x, y)))
                    throw Error(ErrorCategory::InvalidData, "sdf-shade",
                                path + ": channel " + names[c] + " at pixel (" + std::to_string(x) + ", " +
                                    std::to_string(y) + ") is " + std::to_string(image.at(c, x, y)) +
                                    "; NaN and infinite values are not accepted");
}

Image read_channels(const std::string& path, const std::vector<std::string>& names)
{
    Image image = read_exr(path, names, exr_limits());
    if (image.empty()) throw Error(ErrorCategory::InvalidData, "sdf-shade", path + ": the receivers image is empty");
    check_finite(image, path, names);
    return image;
}

bool has_normals(const std::string& path)
{
    const std::vector<std::string> names = exr_channel_names(path, exr_limits());
    auto has = [&](const char* n) { return std::find(names.begin(), names.end(), n) != names.end(); };
    return has("N.x") && has("N.y") && has("N.z");
}

// The options: the scene's (sdf_options_for) when there is one, then each
// option given on the command line.
SdfOptions options_from(const Args& args, const std::optional<reference::Scene>& scene, SdfEstimate estimate)
{
    SdfOptions o = scene ? sdf_options_for(*scene, estimate) : SdfOptions{};
    o.estimate = estimate;
    if (!scene && !args.get("--k")) throw UsageError{"option --k is required with --grid (there is no scene light)"};
    if (!scene && !args.get("--light-position") && !args.get("--light-direction"))
        throw UsageError{"option --light-position or --light-direction is required with --grid"};
    if (args.get("--light-position") && args.get("--light-direction"))
        throw UsageError{"options --light-position and --light-direction exclude each other"};
    if (args.get("--light-position")) o.light = SdfLight::at(reference::to_sdf(triple(args, "--light-position")));
    if (args.get("--light-direction")) {
        const reference::Vec3 direction = triple(args, "--light-direction");
        if (reference::length(direction) == 0.0) throw UsageError{"option --light-direction: must not be 0,0,0"};
        o.light = SdfLight::towards(reference::to_sdf(direction));
        o.light_width = 0.0f;
    }
    o.k = positive(args, "--k", o.k);
    o.light_width = positive(args, "--light-width", o.light_width, true);
    if (o.light_width > 0.0f && o.light.directional)
        throw UsageError{"option --light-width: applies to a light position, not --light-direction"};
    o.t_min = positive(args, "--t-min", o.t_min, true);
    o.t_max = positive(args, "--t-max", o.t_max);
    if (!(o.t_max > o.t_min)) throw UsageError{"option --t-max: must be > --t-min"};
    o.max_steps = args.integer("--max-steps", o.max_steps);
    if (o.max_steps < 1 || o.max_steps > 1000000) throw UsageError{"option --max-steps: must be in [1, 1000000]"};
    o.hit_epsilon = positive(args, "--hit-epsilon", o.hit_epsilon);
    o.normal_offset = positive(args, "--normal-offset", o.normal_offset, true);
    return o;
}

SdfEstimate parse_estimate(const std::string& text)
{
    if (text == "classic") return SdfEstimate::Classic;
    if (text == "improved") return SdfEstimate::Improved;
    if (text == "inner") return SdfEstimate::InnerPenumbra;
    throw UsageError{"option --estimate: '" + text + "' is not classic, improved or inner"};
}

Backend backend_from(const Args& args)
{
    try {
        return parse_backend(args.text("--backend", "auto"));
    } catch (const Error& e) {
        throw UsageError{std::string(e.what())};
    }
}

}  // namespace

int sdf_shade_command(const std::vector<std::string>& argv)
{
    const Args args(argv,
                    {"--scene", "--grid", "--source", "--voxel", "--receivers", "--out", "--estimate", "--k",
                     "--light-width", "--light-position", "--light-direction", "--t-min", "--t-max", "--max-steps",
                     "--hit-epsilon", "--normal-offset", "--backend"},
                    {"--help", "--steps"});
    if (args.flag("--help")) {
        std::cout << kShadeHelp;
        return 0;
    }
    if (args.get("--scene").has_value() == args.get("--grid").has_value())
        throw UsageError{"give exactly one of --scene and --grid"};
    const std::string rx_path = args.required("--receivers");
    const std::string out_path = args.required("--out");
    require_safe_outputs({out_path}, {rx_path, args.text("--scene", ""), args.text("--grid", "")}, "sdf-shade");
    const std::string source = args.text("--source", "analytic");
    if (source != "analytic" && source != "grid") throw UsageError{"option --source: '" + source + "' is not analytic or grid"};
    if (args.get("--grid") && args.get("--source")) throw UsageError{"option --source: only with --scene"};
    if (args.get("--voxel") && !(args.get("--scene") && source == "grid"))
        throw UsageError{"option --voxel: only with --scene and --source grid"};
    const SdfEstimate estimate = parse_estimate(args.text("--estimate", "inner"));
    const Backend backend = backend_from(args);

    // The backend starts while the scene and the receivers are read (OpenCL: tens of ms; docs/opencl_startup.md).
    std::future<Context> starting = start_context(ContextOptions{backend, {}});
    std::optional<reference::Scene> scene;
    if (args.get("--scene")) scene = resolve_scene(*args.get("--scene"));
    const SdfOptions options = options_from(args, scene, estimate);
    const float voxel = args.get("--voxel") ? positive(args, "--voxel", 0.0f) : 0.0f;

    const Image positions = read_channels(rx_path, {"P.x", "P.y", "P.z"});
    std::optional<Image> normals;
    if (options.normal_offset > 0.0f) {
        if (!has_normals(rx_path))
            throw Error(ErrorCategory::Io, "sdf-shade",
                        rx_path + ": no channels N.x, N.y, N.z, which --normal-offset needs (give --normal-offset 0)");
        normals = read_channels(rx_path, {"N.x", "N.y", "N.z"});
    }

    Context context = starting.get();
    for (const std::string& warning : context.warnings()) std::cerr << "penumbra sdf-shade: warning: " << warning << "\n";
    Image out(positions.width(), positions.height(), args.flag("--steps") ? 2 : 1);
    const Image* n = normals ? &*normals : nullptr;
    if (args.get("--grid")) {
        sdf_shadows(context, read_distance_grid(*args.get("--grid")), positions, n, options, out);
    } else if (source == "grid") {
        const DistanceGrid grid = voxel > 0.0f ? bake_distance_grid(*scene, distance_grid_box(*scene), voxel)
                                               : bake_distance_grid(*scene);
        sdf_shadows(context, grid, positions, n, options, out);
    } else {
        sdf_shadows(context, reference::analytic_scene(scene->primitives), positions, n, options, out);
    }
    if (out.channels() == 2) write_exr(out_path, out, {"Y", "steps"});
    else write_exr(out_path, out, {"Y"});
    return 0;
}

int sdf_bake_command(const std::vector<std::string>& argv)
{
    const Args args(argv, {"--scene", "--out", "--voxel", "--margin"}, {"--help"});
    if (args.flag("--help")) {
        std::cout << kBakeHelp;
        return 0;
    }
    const std::string out_path = args.required("--out");
    require_safe_outputs({out_path}, {args.required("--scene")}, "sdf-bake");
    const reference::Scene scene = resolve_scene(args.required("--scene"));
    if (args.get("--margin") && !args.get("--voxel")) throw UsageError{"option --margin: only with --voxel"};
    DistanceGrid grid;
    if (args.get("--voxel")) {
        const reference::GridBox box = args.get("--margin") ? distance_grid_box(scene, positive(args, "--margin", 0.0f, true))
                                                 : distance_grid_box(scene);
        grid = bake_distance_grid(scene, box, positive(args, "--voxel", 0.0f));
    } else {
        grid = bake_distance_grid(scene);
    }
    write_distance_grid(out_path, grid);
    std::cout << "wrote " << out_path << " (" << grid.nx() << "x" << grid.ny() << "x" << grid.nz() << " nodes, voxel "
              << grid.voxel_size() << ")\n";
    return 0;
}

}  // namespace penumbra::cli
