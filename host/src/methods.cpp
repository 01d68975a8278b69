// The method table (penumbra/methods.h): one entry per shading method. Each
// run builds the method's own table and shades; the options' parsing and help
// are in method_options.cpp.
#include "penumbra/methods.h"

#include "penumbra/error.h"

namespace penumbra {
namespace {

Image run_vsm(Context& context, const Image& map, const Image& receivers, const MethodSettings& s)
{
    const MomentTable table = build_moment_table(context, map, 2);
    return vsm(context, table, receivers, VsmOptions{s.radius, s.min_variance, s.bleed});
}

Image run_vssm(Context& context, const Image& map, const Image& receivers, const MethodSettings& s)
{
    const MomentTable table = build_moment_table(context, map, 2);
    return vssm(context, table, receivers, VssmOptions{s.light_size, s.min_variance, s.bleed});
}

Image run_msm(Context& context, const Image& map, const Image& receivers, const MethodSettings& s)
{
    const MsmTable table = build_msm_table(context, map, s.quantization);
    return msm(context, table, receivers, MsmOptions{s.radius, s.moment_bias, s.depth_bias});
}

Image run_msm_soft(Context& context, const Image& map, const Image& receivers, const MethodSettings& s)
{
    const MsmTable table = build_msm_table(context, map, s.quantization);
    return msm_soft(context, table, receivers, MsmSoftOptions{s.light_size, s.moment_bias, s.depth_bias});
}

// EVSM2 keeps the positive warp only (2 channels), EVSM4 both (4).
template <int Channels>
Image run_evsm(Context& context, const Image& map, const Image& receivers, const MethodSettings& s)
{
    const EvsmWarp warp{Channels, s.positive_exponent, s.negative_exponent, Quantization::None};
    const EvsmTable table = build_evsm_table(context, map, warp);
    return evsm(context, table, receivers, EvsmOptions{s.radius, s.min_variance, s.bleed, s.depth_bias.value_or(0.0f)});
}

Image run_pcss(Context& context, const Image& map, const Image& receivers, const MethodSettings& s)
{
    PcssOptions options{s.light_size, s.blocker_samples, s.filter_samples};
    options.bias.constant = s.depth_bias.value_or(options.bias.constant);
    return pcss(context, map, receivers, options);
}

Image run_burley(Context& context, const Image& map, const Image& receivers, const MethodSettings& s)
{
    BurleyOptions options{s.min_radius, s.max_radius, s.bias_slope, s.falloff, s.blocker_samples, s.filter_samples};
    options.bias.constant = s.depth_bias.value_or(options.bias.constant);
    return burley(context, map, receivers, options);
}

}  // namespace

const std::vector<Method>& methods()
{
    static const std::vector<Method> table = {
        {"vsm", "variance shadow maps: Chebyshev bound over a box window (Donnelly & Lauritzen 2006)",
         {"radius", "min-variance", "bleed"}, run_vsm},
        {"vssm", "variance soft shadow maps: blocker search sized by the light (Yang et al. 2010)",
         {"light-size", "min-variance", "bleed"}, run_vssm},
        {"msm", "moment shadow maps: four moments, Hamburger bound (Peters & Klein 2015)",
         {"radius", "moment-bias", "depth-bias", "quantize"}, run_msm},
        {"msm-soft", "moment soft shadows: blocker search on four moments (Peters et al. 2016)",
         {"light-size", "moment-bias", "depth-bias", "quantize"}, run_msm_soft},
        {"evsm2", "exponential variance shadow maps, positive warp (Lauritzen & McCool 2008)",
         {"radius", "min-variance", "bleed", "depth-bias", "exponents"}, run_evsm<2>},
        {"evsm4", "exponential variance shadow maps, both warps (Lauritzen & McCool 2008)",
         {"radius", "min-variance", "bleed", "depth-bias", "exponents"}, run_evsm<4>},
        {"pcss", "percentage-closer soft shadows: blocker search, width, PCF on a disc (Fernando 2005)",
         {"light-size", "depth-bias", "blocker-samples", "filter-samples", "preset"}, run_pcss},
        {"burley", "soft shadows on the bias cone, weighted blocker depth (Burley, Disney)",
         {"min-radius", "max-radius", "depth-bias", "bias-slope", "falloff", "blocker-samples", "filter-samples"},
         run_burley},
    };
    return table;
}

const Method& find_method(std::string_view name)
{
    for (const Method& m : methods())
        if (name == m.name) return m;
    throw Error(ErrorCategory::InvalidArgument, "shade", "method",
                "'" + std::string(name) + "' is not a shading method (" + method_names(", ") + ")");
}

std::string method_names(std::string_view separator)
{
    std::string names;
    for (const Method& m : methods()) {
        if (!names.empty()) names += separator;
        names += m.name;
    }
    return names;
}

std::string methods_help()
{
    std::string text;
    for (const Method& m : methods()) {
        std::string line = "  " + std::string(m.name);
        line.resize(13, ' ');
        text += line + m.summary + "\n";
    }
    return text;
}

}  // namespace penumbra
