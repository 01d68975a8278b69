// penumbra blur: the cross-bilateral filter (issue 6) on files.
//   MASK.exr  1 to 4 float channels, any names: all are filtered
//   DEPTH.exr float channel Z: the guide depth, the mask's size
//   OUT.exr   the mask's channels, filtered, under the same names
// Output is written atomically: a failed run leaves no partial file and an
// existing OUT.exr untouched.
#include <cmath>
#include <future>
#include <iostream>
#include <string>
#include <vector>

#include "args.h"
#include "commands.h"
#include "input_limits.h"
#include "penumbra/bilateral.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/output_files.h"

namespace penumbra::cli {
namespace {

const char* kBlurHelp =
    "usage: penumbra blur --in MASK.exr --guide DEPTH.exr --out OUT.exr [options]\n"
    "  MASK.exr: 1 to 4 float channels, all filtered with the same weights;\n"
    "  DEPTH.exr: float channel Z, the guide depth (same size); OUT.exr: the mask's channels.\n"
    "options:\n"
    "  --radius R            taps per side, window (2R+1)^2, in [0, 32] (default 2: 5x5)\n"
    "  --spatial-sigma S     spatial Gaussian sigma in pixels, > 0 (default 1.5)\n"
    "  --depth-sigma D       Gaussian range weight on the depth difference, > 0 (default 0.05)\n"
    "  --depth-threshold T   instead: drop taps whose |depth difference| exceeds T, >= 0\n"
    "  --difference M        relative (default: difference / centre depth, for perspective\n"
    "                        depth) or absolute (in the guide's units, as OpenCV)\n"
    "  --window W            square (default) or disk (dx^2 + dy^2 <= R^2, as OpenCV)\n"
    "  --separable           horizontal then vertical pass: faster, approximate at edges\n"
    "  --backend B           auto (default), simd, opencl or scalar\n";

std::string channel_list(const std::vector<std::string>& names)
{
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    return list;
}

// Names the file, the channel and the first non-finite pixel.
void check_finite(const Image& image, const std::string& file, const std::vector<std::string>& names)
{
    const NonFinite bad = find_non_finite(image);
    if (!bad.found) return;
    throw Error(ErrorCategory::InvalidData, "blur",
                file + ": channel " + names[std::size_t(bad.channel)] + " at pixel (" + std::to_string(bad.x) +
                    ", " + std::to_string(bad.y) + ") is " + std::to_string(bad.value) +
                    "; NaN and infinite values are not accepted");
}

BilateralOptions parse_options(const Args& args)
{
    BilateralOptions o;
    o.radius = args.integer("--radius", o.radius);
    if (o.radius < 0 || o.radius > kBilateralMaxRadius)
        throw UsageError{"option --radius: must be in [0, 32] (got " + std::to_string(o.radius) + ")"};
    o.spatial_sigma = args.number("--spatial-sigma", o.spatial_sigma);
    if (o.spatial_sigma <= 0.0f) throw UsageError{"option --spatial-sigma: must be > 0"};
    if (args.get("--depth-sigma") && args.get("--depth-threshold"))
        throw UsageError{"options --depth-sigma and --depth-threshold exclude each other (Gaussian or threshold)"};
    o.depth_sigma = args.number("--depth-sigma", o.depth_sigma);
    if (o.depth_sigma <= 0.0f) throw UsageError{"option --depth-sigma: must be > 0"};
    if (args.get("--depth-threshold")) {
        o.range = BilateralRange::Threshold;
        o.depth_threshold = args.number("--depth-threshold", o.depth_threshold);
        if (o.depth_threshold < 0.0f) throw UsageError{"option --depth-threshold: must be >= 0"};
    }
    const std::string difference = args.text("--difference", "relative");
    if (difference != "relative" && difference != "absolute")
        throw UsageError{"option --difference: '" + difference + "' is not relative or absolute"};
    o.relative = difference == "relative";
    const std::string window = args.text("--window", "square");
    if (window != "square" && window != "disk")
        throw UsageError{"option --window: '" + window + "' is not square or disk"};
    o.window = window == "disk" ? BilateralWindow::Disk : BilateralWindow::Square;
    o.separable = args.flag("--separable");
    if (o.separable && o.window == BilateralWindow::Disk)
        throw UsageError{"option --separable: the separable schedule filters a square window, not --window disk"};
    return o;
}

Image read_mask(const std::string& path, std::vector<std::string>& names)
{
    names = exr_channel_names(path, exr_limits());
    if (names.empty() || names.size() > std::size_t(kBilateralMaxChannels))
        throw Error(ErrorCategory::InvalidData, "blur",
                    path + ": has " + std::to_string(names.size()) + " channels (" + channel_list(names) +
                        "); blur filters 1 to 4");
    Image mask = read_exr(path, names, exr_limits());
    if (mask.empty()) throw Error(ErrorCategory::InvalidData, "blur", path + ": the mask is empty");
    check_finite(mask, path, names);
    return mask;
}

Image read_guide(const std::string& path, const Image& mask, const std::string& mask_path)
{
    Image guide = read_exr(path, {"Z"}, exr_limits());
    if (guide.width() != mask.width() || guide.height() != mask.height())
        throw Error(ErrorCategory::InvalidData, "blur",
                    path + ": the guide is " + std::to_string(guide.width()) + "x" + std::to_string(guide.height()) +
                        " but " + mask_path + " is " + std::to_string(mask.width()) + "x" +
                        std::to_string(mask.height()) + "; they must have the same size");
    check_finite(guide, path, {"Z"});
    return guide;
}

}  // namespace

int blur_command(const std::vector<std::string>& argv)
{
    const Args args(argv,
                    {"--in", "--guide", "--out", "--backend", "--radius", "--spatial-sigma", "--depth-sigma",
                     "--depth-threshold", "--difference", "--window"},
                    {"--separable", "--help"});
    if (args.flag("--help")) {
        std::cout << kBlurHelp;
        return 0;
    }
    const std::string in_path = args.required("--in");
    const std::string guide_path = args.required("--guide");
    const std::string out_path = args.required("--out");
    require_safe_outputs({out_path}, {in_path, guide_path}, "blur");
    const BilateralOptions options = parse_options(args);
    Backend backend;
    try {
        backend = parse_backend(args.text("--backend", "auto"));
    } catch (const Error& e) {
        throw UsageError{std::string(e.what())};
    }

    // The backend starts while the inputs are read (OpenCL: tens of ms; docs/opencl_startup.md).
    std::future<Context> starting = start_context(ContextOptions{backend, {}});
    std::vector<std::string> names;
    const Image mask = read_mask(in_path, names);
    const Image guide = read_guide(guide_path, mask, in_path);
    Context context = starting.get();
    for (const std::string& warning : context.warnings()) std::cerr << "penumbra blur: warning: " << warning << "\n";
    const Image blurred = cross_bilateral(context, mask, guide, options);
    write_exr(out_path, blurred, names);
    return 0;
}

}  // namespace penumbra::cli
