// penumbra shade: the file contract of issue 2.
//   SM.exr  one float channel Z (or --depth-channel NAME): light-space depth
//           per texel, in [0, 1] or in the --depth-convention given
//           (or, for a method that reads a deep shadow map, DSM.exr: a deep
//           OpenEXR file, penumbra/deep_exr.h; for pismo, the maps rendered
//           from --scene with cameras fitted to the receivers, or a directory
//           from pismo-build, penumbra/pismo_files.h)
//   RX.exr  float channels u, v, z: receivers' texture coordinates and depth
//           (pismo: P.x, P.y, P.z, world positions, and N.x, N.y, N.z and surface if present, as
//           render-scene writes them)
//   OUT.exr one float channel Y: visibility in [0, 1] on the receivers' grid
// Output is written atomically: a failed run leaves no partial file and an
// existing OUT.exr untouched.
//
// Methods, their options and every check of an option's value are the
// library's method table (penumbra/methods.h); this file reads the files,
// runs the entry and names, for an error, the flag or file at fault.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <future>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>

#include "args.h"
#include "commands.h"
#include "input_limits.h"
#include "penumbra/deep_exr.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/methods.h"
#include "penumbra/output_files.h"
#include "penumbra/pismo_files.h"
#include "penumbra/reference/scene.h"
#include "pismo_input.h"
#include "scene_input.h"

namespace penumbra::cli {
namespace {

// Pismo's maps are rendered from a scene (the reference tracer) when no
// directory of maps is given; the flags that shape them go with the scene.
constexpr const char* kSceneFlag = "--scene";
// SM.exr's depth channel, for files whose channel is not Z (depth.Z, R).
constexpr const char* kDepthChannelFlag = "--depth-channel";

std::string shade_help()
{
    return "usage: penumbra shade --method " + method_names("|") +
           " --shadow-map SM.exr --receivers RX.exr --out OUT.exr\n"
           "                      [--backend auto|simd|opencl|scalar] [method options]\n"
           "       penumbra shade --method dsm --deep-map DSM.exr --receivers RX.exr --out OUT.exr [--filter box|tent]\n"
           "       penumbra shade --method pismo|pismo-maxdepth (--scene S | --pismo-maps DIR) --receivers RX.exr\n"
           "                      --out OUT.exr [--rays R] [--light-level L] [--map-size N] [--layers K]\n"
           "  SM.exr: float channel Z (or --depth-channel NAME, e.g. depth.Z or R), light depth in [0, 1], or in\n"
           "  the convention that --depth-convention names (near, far: the light's); RX.exr's z is in the same one;\n"
           "  DSM.exr: a deep OpenEXR file (dsm-build writes one);\n"
           "  RX.exr: float channels u, v, z (pismo: P.x, P.y, P.z, world positions, and the normals N.x, N.y, N.z and\n"
           "  the surface ids, channel surface, if present: with maps that carry ids, a receiver's own surface never\n"
           "  shadows it and other surfaces with a 1-texel bias; -1 or an absent channel, shaded without ids);\n"
           "  pismo renders its maps from --scene, cameras fitted to the receivers, or reads pismo-build's DIR:\n" +
           pismo_map_options_help() +
           "  OUT.exr: float channel Y, visibility in [0, 1] on the receivers' grid.\n"
           "  Every method computes its own mathematics on the float32 depths (exact window sums, moments in\n"
           "  double): within 2e-4 (vsm, vssm, evsm*) / 1e-3 (msm*) of its float64 evaluation (docs/moments.md).\n"
           "methods:\n" +
           methods_help() + "options:\n" + method_options_help("--") +
           "  --depth-channel NAME  SM.exr's depth channel (default Z), for the methods that read a shadow map\n"
           "  --backend B        auto (default), simd, opencl or scalar\n";
}

std::set<std::string> shade_flags()
{
    std::set<std::string> flags = {"--method", "--receivers", "--out", "--backend", kSceneFlag, kDepthChannelFlag};
    flags.insert(kPismoMapFlags.begin(), kPismoMapFlags.end());
    for (const MethodInputInfo& i : method_inputs()) flags.insert(std::string("--") + i.flag);
    for (const MethodOption& o : method_options()) flags.insert(std::string("--") + o.name);
    return flags;
}

// The method options given, as (name, text) pairs for the method table.
std::vector<std::pair<std::string, std::string>> given_options(const Args& args)
{
    std::vector<std::pair<std::string, std::string>> given;
    for (const MethodOption& o : method_options())
        if (const auto text = args.get(std::string("--") + o.name)) given.emplace_back(o.name, *text);
    return given;
}

struct ShadeFiles {
    std::string map, receivers;  // map: the file of the method's input (method_inputs())
    MethodInput input;
    std::string depth_channel = "Z";  // a shadow map's
    std::vector<std::string> receiver_channels{};  // as read from the receivers' file
    DepthConvention convention{};     // a shadow map's, once the options are parsed
};

// --depth-channel: read by the methods that read a shadow map.
std::string depth_channel(const Args& args, const Method& method)
{
    const auto name = args.get(kDepthChannelFlag);
    if (!name) return "Z";
    if (method.input != MethodInput::ShadowMap)
        throw UsageError{std::string("option --depth-channel: ") + method.name + " reads a " +
                         input_info(method.input).what + ", not a shadow map's channel"};
    if (name->empty()) throw UsageError{"option --depth-channel: give a channel name (Z, depth.Z, R, ...)"};
    return *name;
}

bool renders_pismo_maps(const Args& args, const Method& method)
{
    return method.input == MethodInput::PismoMapSet && !args.get("--pismo-maps");
}

// The flags only a method that renders its maps from a scene reads.
void refuse_scene_flags(const Args& args, const Method& method)
{
    const bool rendering = renders_pismo_maps(args, method);
    if (rendering && !args.get(kSceneFlag))
        throw UsageError{std::string("option --scene or --pismo-maps is required: ") + method.name +
                         " renders its maps from a scene, or reads a directory from pismo-build"};
    if (method.input == MethodInput::PismoMapSet && !rendering && args.get(kSceneFlag))
        throw UsageError{"option --scene: give --scene or --pismo-maps, not both"};
    std::set<std::string> scene_flags = kPismoMapFlags;
    scene_flags.insert(kSceneFlag);
    for (const std::string& flag : scene_flags)
        if (!rendering && args.get(flag))
            throw UsageError{"option " + flag + ": only pismo and pismo-maxdepth read it, from a scene" +
                             std::string(method.input == MethodInput::PismoMapSet ? " (not with --pismo-maps)" : "")};
}

// The method's input file: its flag is required, another input's refused.
std::string input_path(const Args& args, const Method& method)
{
    const MethodInputInfo& wanted = input_info(method.input);
    for (const MethodInputInfo& i : method_inputs())
        if (i.input != method.input && args.get(std::string("--") + i.flag))
            throw UsageError{"option --" + std::string(i.flag) + ": " + method.name + " reads a " + wanted.what +
                             ": give --" + wanted.flag};
    refuse_scene_flags(args, method);
    if (renders_pismo_maps(args, method)) return args.required(kSceneFlag);
    return args.required(std::string("--") + wanted.flag);
}

std::string format_number(float value)
{
    std::ostringstream text;
    text << value;
    return text.str();
}

// The library names the parameter at fault; the user knows flags and files.
// A bad value in an image is named by file, channel and pixel.
[[noreturn]] void rethrow_naming_flag_or_file(const Error& e, const ShadeFiles& files)
{
    const bool is_map = e.parameter() == input_info(files.input).parameter,
               is_receivers = e.parameter() == "receivers";
    if (!is_map && !is_receivers) {
        if (e.parameter().empty()) throw e;
        const MethodOption* option = option_for_parameter(e.parameter());
        throw UsageError{"option --" + (option ? std::string(option->name) : e.parameter()) + ": " + e.message()};
    }
    const std::string& path = is_map ? files.map : files.receivers;
    if (!e.pixel()) throw Error(e.category(), "shade", path + ": " + e.message());
    static const char* const kReceiverChannels[] = {"u", "v", "z", "dzdu", "dzdv"};
    const BadPixel& bad = *e.pixel();
    const bool named = std::size_t(bad.channel) < files.receiver_channels.size();
    const std::string channel = is_map  ? files.depth_channel
                                : named ? files.receiver_channels[std::size_t(bad.channel)]
                                        : kReceiverChannels[bad.channel % 5];
    const std::string where = path + ": channel " + channel +
                              " at pixel (" + std::to_string(bad.x) + ", " + std::to_string(bad.y) + ") is " +
                              std::to_string(bad.value);
    const StoredDepthRange range = stored_depth_range(files.convention);
    const std::string outside = ", outside [" + format_number(range.low) + ", " + format_number(range.high) +
                                "], the range of " + describe(files.convention) +
                                "; give the map's --depth-convention (and --near, --far)";
    throw Error(ErrorCategory::InvalidData, "shade",
                where + (std::isfinite(bad.value) ? outside : "; NaN and infinite values are not accepted"));
}

// Sets `flag` when the scope is left by an exception.
struct SetOnUnwind {
    std::atomic<bool>& flag;
    const int uncaught = std::uncaught_exceptions();
    ~SetOnUnwind()
    {
        if (std::uncaught_exceptions() > uncaught) flag = true;
    }
};

Image read_input(const std::string& path, const std::vector<std::string>& channels, const char* what)
{
    Image image = read_exr(path, channels, exr_limits());
    if (image.empty()) throw Error(ErrorCategory::InvalidData, "shade", path + ": the " + what + " is empty");
    return image;
}

// The channels `shade` reads from RX.exr: the method's, and for Pismo the
// normals N.x, N.y, N.z and the surface ids when the file has them
// (render-scene writes them), so that the receiver's own surface takes part
// (docs/pismo.md).
std::vector<std::string> receiver_channels_in(const ShadeFiles& files, const Method& method, const MethodSettings& s)
{
    if (method.input != MethodInput::PismoMapSet) return receiver_channels(method, s);
    return pismo_receiver_channels(files.receivers, "shade");
}

// Receivers' surface ids are checked against the maps'; maps without ids
// (a set written without them, as before pismo-build's format version 2)
// shade them as unknown, and say so.
void check_pismo_receivers(const Image& receivers, const PismoMapSet& set, const ShadeFiles& files)
{
    check_receiver_surfaces(receivers, set, files.receivers, "shade");
    if (receivers.channels() == 7 && set.surface_ids.empty())
        std::cerr << "penumbra shade: warning: " << files.receivers << " has surface ids but the maps carry none "
                  << "(a set written without them, as before pismo-build's format version 2): shaded without ids\n";
}

// A deep map's reader names the file, the pixel and the sample; the line is the command's.
DeepShadowMap read_deep_map(const std::string& path)
{
    try {
        return read_deep_exr(path, exr_limits());
    } catch (const Error& e) {
        throw Error(e.category(), "shade", e.message());
    }
}

// Pismo's maps: pismo-build's directory, or rendered from the scene with the
// cameras fitted to the receivers (docs/pismo.md: their texels then land on
// what is shaded). The readers name the file; the line is the command's.
PismoMapSet pismo_maps_for(const Args& args, const Method& method, const ShadeFiles& files)
{
    try {
        if (!renders_pismo_maps(args, method)) return read_pismo_maps(files.map, exr_limits());
        const PismoBuild build = pismo_build_from(args);
        const reference::Scene scene = resolve_scene(files.map);
        return render_pismo_set(scene, build, receiver_region_from(files.receivers, "shade"));
    } catch (const Error& e) {
        if (e.operation() == "shade" || !e.parameter().empty()) throw;
        throw Error(e.category(), "shade", e.message());
    }
}

Context start(std::future<Context>& starting)
{
    Context context = starting.get();
    for (const std::string& warning : context.warnings()) std::cerr << "penumbra shade: warning: " << warning << "\n";
    return context;
}

}  // namespace

int shade_command(const std::vector<std::string>& argv)
{
    const Args args(argv, shade_flags(), {"--help"});
    if (args.flag("--help")) {
        std::cout << shade_help();
        return 0;
    }
    const std::string method_name = args.required("--method");
    const Method* method = nullptr;
    try {
        method = &find_method(method_name);
    } catch (const Error& e) {
        throw UsageError{"option --method: " + e.message()};
    }
    ShadeFiles files{input_path(args, *method), args.required("--receivers"), method->input,
                     depth_channel(args, *method)};
    const std::string out_path = args.required("--out");
    require_safe_outputs({out_path}, {files.map, files.receivers}, "shade");
    Backend backend;
    try {
        backend = parse_backend(args.text("--backend", "auto"));
    } catch (const Error& e) {
        throw UsageError{std::string(e.what())};
    }
    try {
        const MethodSettings settings = parse_method_settings(*method, given_options(args));
        files.convention = settings.depth_convention;
        // The backend starts, and loads the method's programs, while the inputs are read (OpenCL: tens of ms).
        // An input that fails to read skips the warm-up, so that its error does not wait for program
        // builds (seconds on a cold cache): the future's destructor waits for the thread.
        std::atomic<bool> inputs_failed{false};
        const auto warm_up = [method, settings, &inputs_failed](Context& c) {
            if (!inputs_failed) method->warm_up(c, settings);
        };
        std::future<Context> starting = start_context(ContextOptions{backend, {}}, warm_up);
        const SetOnUnwind on_unwind{inputs_failed};
        const auto shade_from = [&](const auto& map) {  // a shadow map or a deep map, read first
            files.receiver_channels = receiver_channels_in(files, *method, settings);
            const Image receivers = read_input(files.receivers, files.receiver_channels, "receivers image");
            if constexpr (std::is_same_v<std::decay_t<decltype(map)>, PismoMapSet>)
                check_pismo_receivers(receivers, map, files);
            Context context = start(starting);
            write_exr(out_path, method->run(context, map, receivers, settings), {"Y"});
        };
        if (method->input == MethodInput::DeepMap)
            shade_from(read_deep_map(files.map));
        else if (method->input == MethodInput::PismoMapSet)
            shade_from(pismo_maps_for(args, *method, files));
        else
            shade_from(read_input(files.map, {files.depth_channel}, "shadow map"));
    } catch (const Error& e) {
        rethrow_naming_flag_or_file(e, files);
    }
    return 0;
}

}  // namespace penumbra::cli
