// penumbra shade: the file contract of issue 2.
//   SM.exr  one float channel Z: light-space depth in [0, 1] per texel
//   RX.exr  float channels u, v, z: receivers' texture coordinates and depth
//   OUT.exr one float channel Y: visibility in [0, 1] on the receivers' grid
// Output is written atomically: a failed run leaves no partial file and an
// existing OUT.exr untouched.
#include <cmath>
#include <iostream>
#include <string>

#include "args.h"
#include "commands.h"
#include "input_limits.h"
#include "penumbra/chebyshev.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/moment_table.h"
#include "penumbra/output_files.h"
#include "moments_command.h"

namespace penumbra::cli {
namespace {

const char* kShadeHelp =
    "usage: penumbra shade --method vsm|vssm|msm|msm-soft|evsm2|evsm4 --shadow-map SM.exr --receivers RX.exr --out OUT.exr\n"
    "                      [--backend auto|simd|opencl|scalar] [method options]\n"
    "  SM.exr: float channel Z, light depth in [0, 1]; RX.exr: float channels u, v, z;\n"
    "  OUT.exr: float channel Y, visibility in [0, 1] on the receivers' grid.\n"
    "options:\n"
    "  --radius R         vsm box radius in texels, window (2R+1)^2 (default 2, at most 127)\n"
    "  --min-variance V   variance floor in depth^2 (default 2e-5), >= 0\n"
    "  --bleed B          light-bleeding reduction in [0, 1) (default 0 = off)\n"
    "  --light-size L     vssm: light width in texture units at the near plane (default 0.02), > 0\n"
    "  Every method computes its own mathematics on the float32 depths (exact window sums, moments in\n"
    "  double): within 2e-4 (vsm, vssm, evsm*) / 1e-3 (msm*) of its float64 evaluation (docs/moments.md).\n"
    "  --quantize 16      msm, msm-soft: store the I3D 2015 optimized 16-bit quantization (16 B/texel\n"
    "                     instead of 48); faithful to its dequantized moments, but the quantization\n"
    "                     itself moves visibility: worst 0.56, p99 up to 0.017, up to 5% of receivers\n"
    "                     beyond 1e-2 against the default (docs/moments.md, \"16-bit quantization\")\n"
    "  --moment-bias A    msm, msm-soft: share of each window moved to depths 0 and 1, in [0, 1) (6e-5)\n"
    "  --depth-bias D     msm*, evsm*: subtracted from receiver depth, in [0, 1); msm default: two 16-bit\n"
    "                     depth steps (3.05e-5); sloped receivers need about half a texel's depth change\n"
    "                     more; evsm default 0\n"
    "  --exponents P,N    evsm4 warp exponents (evsm2: P), each in (0, 10] (defaults 10,5; above 10 the\n"
    "                     exact 48-bit storage could not keep 2e-4). --radius, --min-variance and --bleed\n"
    "                     apply to evsm2/evsm4 too, --radius to msm, --light-size to msm-soft\n"
    "  --backend B        auto (default), simd, opencl or scalar\n";

// Names the file, the channel and the first bad pixel.
void check_channel(const Image& image, int c, const std::string& file, const std::string& channel, bool unit_range)
{
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const float v = image.at(c, x, y);
            const std::string where = file + ": channel " + channel + " at pixel (" + std::to_string(x) + ", " +
                                      std::to_string(y) + ")";
            if (!std::isfinite(v))
                throw Error(ErrorCategory::InvalidData, "shade", where + " is " + std::to_string(v) +
                                                                     "; NaN and infinite values are not accepted");
            if (unit_range && (v < 0.0f || v > 1.0f))
                throw Error(ErrorCategory::InvalidData, "shade",
                            where + " is " + std::to_string(v) + ", outside [0, 1]; depths must be normalised");
        }
}

Image read_shadow_map(const std::string& path)
{
    Image map = read_exr(path, {"Z"}, exr_limits());
    if (map.empty()) throw Error(ErrorCategory::InvalidData, "shade", path + ": the shadow map is empty");
    check_channel(map, 0, path, "Z", true);
    return map;
}

Image read_receivers(const std::string& path)
{
    Image rx = read_exr(path, {"u", "v", "z"}, exr_limits());
    if (rx.empty()) throw Error(ErrorCategory::InvalidData, "shade", path + ": the receivers image is empty");
    const char* names[] = {"u", "v", "z"};
    for (int c = 0; c < 3; ++c) check_channel(rx, c, path, names[c], false);
    return rx;
}

void check_options(const std::string& method, int radius, float min_variance, float bleed, float light_size)
{
    if (method != "vsm" && method != "vssm" && !is_moment_method(method))
        throw UsageError{"option --method: '" + method + "' is not vsm, vssm, msm, msm-soft, evsm2 or evsm4"};
    if (radius < 0) throw UsageError{"option --radius: must be >= 0 (got " + std::to_string(radius) + ")"};
    if (min_variance < 0.0f) throw UsageError{"option --min-variance: must be >= 0"};
    if (bleed < 0.0f || bleed >= 1.0f) throw UsageError{"option --bleed: must be in [0, 1)"};
    if (light_size <= 0.0f) throw UsageError{"option --light-size: must be > 0"};
}

}  // namespace

int shade_command(const std::vector<std::string>& argv)
{
    const Args args(argv,
                    {"--method", "--shadow-map", "--receivers", "--out", "--backend", "--radius", "--min-variance",
                     "--bleed", "--light-size", kMomentOptionNames[0], kMomentOptionNames[1],
                     kMomentOptionNames[2], kMomentOptionNames[3]},
                    {"--help"});
    if (args.flag("--help")) {
        std::cout << kShadeHelp;
        return 0;
    }
    const std::string method = args.required("--method");
    const std::string sm_path = args.required("--shadow-map");
    const std::string rx_path = args.required("--receivers");
    const std::string out_path = args.required("--out");
    require_safe_outputs({out_path}, {sm_path, rx_path}, "shade");
    const int radius = args.integer("--radius", VsmOptions{}.radius);
    const float min_variance = args.number("--min-variance", kDefaultMinVariance);
    const float bleed = args.number("--bleed", 0.0f);
    const float light_size = args.number("--light-size", VssmOptions{}.light_size);
    check_options(method, radius, min_variance, bleed, light_size);
    Backend backend;
    try {
        backend = parse_backend(args.text("--backend", "auto"));
    } catch (const Error& e) {
        throw UsageError{std::string(e.what())};
    }
    std::optional<MomentShadeSettings> moments;
    if (is_moment_method(method)) moments = parse_moment_settings(method, args);
    else if (args.get("--moment-bias") || args.get("--depth-bias") || args.get("--quantize") || args.get("--exponents"))
        throw UsageError{"options --moment-bias, --depth-bias, --quantize and --exponents apply to msm, msm-soft, "
                         "evsm2 and evsm4"};

    const Image map = read_shadow_map(sm_path);
    const Image receivers = read_receivers(rx_path);
    Context context(ContextOptions{backend, {}});
    for (const std::string& warning : context.warnings()) std::cerr << "penumbra shade: warning: " << warning << "\n";
    if (moments) {
        write_exr(out_path, shade_moments(context, *moments, map, receivers), {"Y"});
        return 0;
    }
    const MomentTable table = build_moment_table(context, map, 2);
    const Image visibility = method == "vsm" ? vsm(context, table, receivers, VsmOptions{radius, min_variance, bleed})
                                             : vssm(context, table, receivers, VssmOptions{light_size, min_variance, bleed});
    write_exr(out_path, visibility, {"Y"});
    return 0;
}

}  // namespace penumbra::cli
