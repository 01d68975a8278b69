// `penumbra shade --method msm|msm-soft|evsm2|evsm4`: the moment family on the
// shade contract (SM.exr -> RX.exr -> OUT.exr, host/cli/shade_command.cpp).
// The option checks here catch the mistakes a user types; the library checks
// the rest (an exponent beyond the storage's limit, a window too large for an
// exact table) with a message naming the parameter.
#include "moments_command.h"

#include <cstdlib>

namespace penumbra::cli {
namespace {

bool is_evsm(const std::string& method) { return method == "evsm2" || method == "evsm4"; }

// Rejects an option the method cannot use.
void reject_unless(const Args& args, const std::string& name, bool applies, const std::string& methods)
{
    if (!applies && args.get(name)) throw UsageError{"option " + name + ": applies to " + methods + " only"};
}

std::optional<float> bias_option(const Args& args, const std::string& name)
{
    if (!args.get(name)) return std::nullopt;
    const float value = args.number(name, 0.0f);
    if (value < 0.0f || value >= 1.0f)
        throw UsageError{"option " + name + ": must be in [0, 1) (got " + *args.get(name) + ")"};
    return value;
}

float exponent_value(const std::string& text, const std::string& whole)
{
    char* end = nullptr;
    const float value = std::strtof(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !(value > 0.0f) || value > 1e30f)
        throw UsageError{"option --exponents: '" + whole + "' is not P,N with positive exponents P and N"};
    return value;
}

// "P,N" for evsm4; "P" for evsm2, which has no negative warp.
void parse_exponents(const Args& args, const std::string& method, EvsmWarp& warp)
{
    const auto text = args.get("--exponents");
    if (!text) return;
    const std::size_t comma = text->find(',');
    if (method == "evsm2") {
        if (comma != std::string::npos)
            throw UsageError{"option --exponents: evsm2 has only the positive warp; give one exponent P"};
        warp.positive = exponent_value(*text, *text);
        return;
    }
    if (comma == std::string::npos)
        throw UsageError{"option --exponents: evsm4 needs two exponents, P,N (got '" + *text + "')"};
    warp.positive = exponent_value(text->substr(0, comma), *text);
    warp.negative = exponent_value(text->substr(comma + 1), *text);
}

// No option: the exact default. "16": MSM's optimized 16-bit storage (opt-in).
Quantization quantization_option(const Args& args, const std::string& method)
{
    const auto bits = args.get("--quantize");
    if (!bits) return Quantization::None;
    if (*bits != "16") throw UsageError{"option --quantize: '" + *bits + "' is not 16 (the only opt-in storage)"};
    if (is_evsm(method)) throw UsageError{"option --quantize: applies to msm and msm-soft only"};
    return Quantization::Bits16;
}

}  // namespace

bool is_moment_method(const std::string& method)
{
    return method == "msm" || method == "msm-soft" || is_evsm(method);
}

MomentShadeSettings parse_moment_settings(const std::string& method, const Args& args)
{
    MomentShadeSettings s;
    s.method = method;
    s.quantization = quantization_option(args, method);
    const bool msm_family = !is_evsm(method);
    // The shared options a method does not read are ignored, as vsm and vssm
    // do; the family's own options are rejected where they mean nothing.
    reject_unless(args, "--moment-bias", msm_family, "msm and msm-soft");
    reject_unless(args, "--exponents", !msm_family, "evsm2 and evsm4");

    const std::optional<float> moment_bias = bias_option(args, "--moment-bias");
    const std::optional<float> depth_bias = bias_option(args, "--depth-bias");
    const int radius = args.integer("--radius", MsmOptions{}.radius);
    if (radius < 0) throw UsageError{"option --radius: must be >= 0 (got " + std::to_string(radius) + ")"};
    s.msm = MsmOptions{radius, moment_bias, depth_bias};
    s.soft = MsmSoftOptions{args.number("--light-size", MsmSoftOptions{}.light_size), moment_bias, depth_bias};
    if (s.soft.light_size <= 0.0f) throw UsageError{"option --light-size: must be > 0"};

    s.warp.channels = method == "evsm2" ? 2 : 4;
    s.warp.quantization = s.quantization;
    parse_exponents(args, method, s.warp);
    s.evsm.radius = radius;
    s.evsm.min_variance = args.number("--min-variance", EvsmOptions{}.min_variance);
    s.evsm.bleed = args.number("--bleed", 0.0f);
    s.evsm.depth_bias = depth_bias.value_or(0.0f);
    return s;
}

Image shade_moments(Context& context, const MomentShadeSettings& s, const Image& map, const Image& receivers)
{
    if (is_evsm(s.method)) {
        const EvsmTable table = build_evsm_table(context, map, s.warp);
        return evsm(context, table, receivers, s.evsm);
    }
    const MsmTable table = build_msm_table(context, map, s.quantization);
    return s.method == "msm" ? msm(context, table, receivers, s.msm) : msm_soft(context, table, receivers, s.soft);
}

}  // namespace penumbra::cli
