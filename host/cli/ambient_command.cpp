// penumbra ambient: irradiance from SH ambient rigs (docs/ambient.md), file contract:
//   --rig RIG.json        the light rig (docs/ambient.md, "Rig files")
//   --dark-rig DARK.json  a dark rig, blended in per pixel by the volumes, or
//                         without --volumes by the receivers' channel `blend`
//   --volumes VOL.json    boxes and spheres (docs/ambient.md, "Volume files")
//   --scene S             instead: a scene's "ambient" field (rig, dark_rig, volumes)
//   RX.exr                float channels N.x, N.y, N.z (normals, any length
//                         > 0); P.x, P.y, P.z (world positions) with
//                         --volumes; `blend` for a dark rig without volumes.
//                         render-scene's receivers have N and P. Other
//                         channels are ignored.
//   --normals N.exr       the normals from another file instead (channels
//                         N.x, N.y, N.z, or else R, G, B)
//   OUT.exr               float channels R, G, B: irradiance, written atomically.
// Bad input exits with 2 and one line naming the file, field, pixel or option.
#include <algorithm>
#include <iostream>
#include <string>

#include "args.h"
#include "commands.h"
#include "input_limits.h"
#include "penumbra/ambient.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/output_files.h"
#include "penumbra/reference/ambient_json.h"
#include "scene_input.h"

namespace penumbra::cli {
namespace {

const char* kHelp =
    "usage: penumbra ambient --rig RIG.json [--dark-rig DARK.json [--volumes VOLUMES.json]] --receivers RX.exr\n"
    "                        --out OUT.exr [options]\n"
    "       penumbra ambient --scene S --receivers RX.exr --out OUT.exr [options]   (the scene's \"ambient\")\n"
    "  Irradiance (R, G, B) per pixel from ambient light rigs projected to spherical harmonics.\n"
    "  RX.exr: N.x, N.y, N.z; P.x, P.y, P.z with --volumes; `blend` in [0, 1] for a dark rig without volumes.\n"
    "  --normals N.exr        normals from this file (N.x, N.y, N.z or R, G, B) instead of RX.exr\n"
    "  --order 1|2            SH order: 4 or 9 coefficients per channel (default 2)\n"
    "  --window none|hanning|lanczos   windowing against ringing (default none)\n"
    "  --window-width W       the window's width, > the order (default 4)\n"
    "  --cheap-dark           the dark rig's first 4 coefficients only (Toy Story 3's shortcut)\n"
    "  --zero-normals error|black      a zero normal is an error (default), or a pixel that sees nothing\n"
    "  --backend auto|simd|opencl|scalar\n"
    "  Formats: docs/ambient.md.\n";

ShWindow parse_window(const std::string& text)
{
    if (text == "none") return ShWindow::None;
    if (text == "hanning") return ShWindow::Hanning;
    if (text == "lanczos") return ShWindow::Lanczos;
    throw UsageError{"option --window: '" + text + "' is not none, hanning or lanczos"};
}

ShOptions sh_options(const Args& args)
{
    ShOptions o;
    o.order = args.integer("--order", 2);
    if (o.order != 1 && o.order != 2) throw UsageError{"option --order: must be 1 or 2"};
    o.window = parse_window(args.text("--window", "none"));
    o.window_width = args.number("--window-width", 4.0f);
    if (!(o.window_width > o.order)) throw UsageError{"option --window-width: must be > the order"};
    return o;
}

ZeroNormals parse_zero_normals(const std::string& text)
{
    if (text == "error") return ZeroNormals::Error;
    if (text == "black") return ZeroNormals::Black;
    throw UsageError{"option --zero-normals: '" + text + "' is not error or black"};
}

// A rig projected; the library's complaint about a value names the file.
ShIrradiance projected(const AmbientRig& rig, const ShOptions& o, const std::string& path)
{
    try {
        return project_rig(rig, o);
    } catch (const Error& e) {
        throw Error(e.category(), "ambient", path + ": " + e.message());
    }
}

AmbientVolumes packed(const std::vector<AmbientVolume>& volumes, const std::string& path)
{
    try {
        return AmbientVolumes(volumes);
    } catch (const Error& e) {
        throw Error(e.category(), "ambient", path + ": " + e.message());
    }
}

bool has_channels(const std::string& path, const std::vector<std::string>& wanted)
{
    const std::vector<std::string> names = exr_channel_names(path, exr_limits());
    for (const std::string& w : wanted)
        if (std::find(names.begin(), names.end(), w) == names.end()) return false;
    return true;
}

// The receivers' channels, in the order the library takes them
// (ambient_receiver_channels): normals first.
std::vector<std::string> receiver_channels(const AmbientLighting& l)
{
    std::vector<std::string> names = {"N.x", "N.y", "N.z"};
    if (ambient_receiver_channels(l) == 4) names.push_back("blend");
    if (ambient_receiver_channels(l) == 6) names.insert(names.end(), {"P.x", "P.y", "P.z"});
    return names;
}

Image read_receivers(const std::string& rx_path, const std::string& normals_path, const AmbientLighting& l)
{
    const std::vector<std::string> names = receiver_channels(l);
    const std::vector<std::string> from_rx(normals_path.empty() ? names.begin() : names.begin() + 3, names.end());
    if (!from_rx.empty() && !has_channels(rx_path, from_rx))
        throw Error(ErrorCategory::Io, "ambient", rx_path + ": needs the channels " + [&] {
            std::string s;
            for (const std::string& n : from_rx) s += (s.empty() ? "" : ", ") + n;
            return s;
        }() + (l.dark && l.volumes.count() == 0 ? " (a dark rig without --volumes blends by `blend`)" : ""));
    Image rx = from_rx.empty() ? Image() : read_exr(rx_path, from_rx, exr_limits());
    if (normals_path.empty()) return rx;
    const std::vector<std::string> n_names = has_channels(normals_path, {"N.x", "N.y", "N.z"})
                                                 ? std::vector<std::string>{"N.x", "N.y", "N.z"}
                                                 : std::vector<std::string>{"R", "G", "B"};
    const Image n = read_exr(normals_path, n_names, exr_limits());
    if (rx.empty()) return n;
    if (n.width() != rx.width() || n.height() != rx.height())
        throw Error(ErrorCategory::InvalidArgument, "ambient",
                    normals_path + ": the normals' size differs from " + rx_path + "'s");
    Image all(rx.width(), rx.height(), int(names.size()));
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            for (int c = 0; c < 3; ++c) all.at(c, x, y) = n.at(c, x, y);
            for (int c = 0; c < rx.channels(); ++c) all.at(3 + c, x, y) = rx.at(c, x, y);
        }
    return all;
}

// A bad pixel as the user sees it: the file and, for a zero normal, the option.
Error reworded(const Error& e, const std::string& file)
{
    std::string message = e.message();
    const std::string hint = "zero_normals = Black";
    if (const auto at = message.find(hint); at != std::string::npos) message.replace(at, hint.size(), "--zero-normals black");
    return Error(e.category(), "ambient", file + ": " + message);
}

// The rig and volume readers name the file and the field; the line is the command's.
template <class Load>
auto read_as_command(Load&& load, const std::string& path)
{
    try {
        return load(path);
    } catch (const Error& e) {
        throw e.as_operation("ambient");
    }
}

}  // namespace

int ambient_command(const std::vector<std::string>& argv)
{
    const Args args(argv,
                    {"--rig", "--scene", "--dark-rig", "--volumes", "--receivers", "--normals", "--out", "--order", "--window",
                     "--window-width", "--zero-normals", "--backend"},
                    {"--help", "--cheap-dark"});
    if (args.flag("--help")) {
        std::cout << kHelp;
        return 0;
    }
    if (args.get("--scene").has_value() == args.get("--rig").has_value())
        throw UsageError{"give exactly one of --rig and --scene (a scene with an \"ambient\" field)"};
    if (args.get("--scene") && (args.get("--dark-rig") || args.get("--volumes")))
        throw UsageError{"options --dark-rig and --volumes: only with --rig (a scene carries its own)"};
    const std::string rig_path = args.text("--rig", "");
    const std::string rx_path = args.required("--receivers");
    const std::string out_path = args.required("--out");
    const std::string normals_path = args.text("--normals", "");
    if (args.get("--volumes") && !args.get("--dark-rig"))
        throw UsageError{"option --volumes: blends towards a dark rig; give --dark-rig too"};
    if (args.flag("--cheap-dark") && !args.get("--dark-rig")) throw UsageError{"option --cheap-dark: only with --dark-rig"};
    require_safe_outputs({out_path},
                         {rx_path, rig_path, args.text("--scene", ""), args.text("--dark-rig", ""), args.text("--volumes", ""), normals_path},
                         "ambient");
    const ShOptions o = sh_options(args);
    Backend backend;
    try {
        backend = parse_backend(args.text("--backend", "auto"));
    } catch (const Error& e) {
        throw UsageError{std::string(e.what())};
    }

    AmbientLighting lighting;
    if (args.get("--scene")) {
        const std::string name = *args.get("--scene");
        const reference::Scene scene = resolve_scene(name);
        if (!scene.ambient)
            throw Error(ErrorCategory::InvalidArgument, "ambient", name + ": the scene has no \"ambient\" field (docs/ambient.md)");
        lighting.light = projected(scene.ambient->rig, o, name);
        if (scene.ambient->dark_rig) lighting.dark = projected(*scene.ambient->dark_rig, o, name);
        lighting.volumes = packed(scene.ambient->volumes, name);
    } else {
        const auto rig = [](const std::string& path) { return reference::load_rig(path); };
        const auto volumes = [](const std::string& path) { return reference::load_volumes(path); };
        lighting.light = projected(read_as_command(rig, rig_path), o, rig_path);
        if (const auto dark = args.get("--dark-rig")) lighting.dark = projected(read_as_command(rig, *dark), o, *dark);
        if (const auto v = args.get("--volumes")) lighting.volumes = packed(read_as_command(volumes, *v), *v);
    }
    lighting.cheap_dark = args.flag("--cheap-dark");
    lighting.zero_normals = parse_zero_normals(args.text("--zero-normals", "error"));
    const Image receivers = read_receivers(rx_path, normals_path, lighting);

    Context context(ContextOptions{backend, {}});
    for (const std::string& warning : context.warnings()) std::cerr << "penumbra ambient: warning: " << warning << "\n";
    Image out(receivers.width(), receivers.height(), 3);
    try {
        ambient_irradiance(context, receivers, lighting, out);
    } catch (const Error& e) {
        if (e.parameter() != "receivers") throw;
        const bool normal = e.pixel() && e.pixel()->channel < 3;
        throw reworded(e, normal && !normals_path.empty() ? normals_path : rx_path);
    }
    write_exr(out_path, out, {"R", "G", "B"});
    return 0;
}

}  // namespace penumbra::cli
