// The options of the method table (penumbra/methods.h): each declared once,
// with its parser and its help; the ranges are parameter_range.h's.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "penumbra/error.h"
#include "penumbra/methods.h"

namespace penumbra {
namespace {

Error bad_value(const Method& m, std::string_view parameter, const std::string& message)
{
    return Error(ErrorCategory::InvalidArgument, m.name, parameter, message);
}

float parse_float(const Method& m, std::string_view parameter, const std::string& text)
{
    char* end = nullptr;
    errno = 0;
    const float value = std::strtof(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value))
        throw bad_value(m, parameter, "'" + text + "' is not a finite number");
    return value;
}

// Integers beyond +-1e9 are no window anyone means; the range check names the limit.
int parse_int(const Method& m, std::string_view parameter, const std::string& text)
{
    char* end = nullptr;
    const long value = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || value < -1000000000L || value > 1000000000L)
        throw bad_value(m, parameter, "'" + text + "' is not an integer");
    return int(value);
}

template <int MethodSettings::*Field, const ParameterRange& Range>
void set_int(const Method& m, const std::string& text, MethodSettings& s)
{
    const int value = parse_int(m, Range.name, text);
    check(Range, value, m.name);
    s.*Field = value;
}

template <auto Field, const ParameterRange& Range>
void set_float(const Method& m, const std::string& text, MethodSettings& s)
{
    const float value = parse_float(m, Range.name, text);
    check(Range, value, m.name);
    s.*Field = value;
}

// One option for every window: the box of pcf has its own reason for the limit.
void set_radius(const Method& m, const std::string& text, MethodSettings& s)
{
    const std::string_view name = m.name;
    const ParameterRange& range = name == "pcf" ? kPcfRadiusRange : name == "dsm" ? kDeepRadiusRange : kRadiusRange;
    const int value = parse_int(m, range.name, text);
    check(range, value, m.name);
    s.radius = value;
}

void set_quantization(const Method& m, const std::string& text, MethodSettings& s)
{
    if (text != "16") throw bad_value(m, "quantize", "'" + text + "' is not 16 (the only opt-in storage)");
    s.quantization = Quantization::Bits16;
}

// "P,N" for evsm4; "P" for evsm2, which has no negative warp.
void set_exponents(const Method& m, const std::string& text, MethodSettings& s)
{
    const std::size_t comma = text.find(',');
    const bool two = std::string_view(m.name) == "evsm4";
    if (!two && comma != std::string::npos)
        throw bad_value(m, "exponents", std::string(m.name) + " has only the positive warp; give one exponent P");
    if (two && comma == std::string::npos)
        throw bad_value(m, "exponents", std::string(m.name) + " needs two exponents, P,N (got '" + text + "')");
    auto exponent = [&](const std::string& part, const ParameterRange& range) {
        char* end = nullptr;
        const float value = std::strtof(part.c_str(), &end);
        if (part.empty() || *end != '\0' || !(value > 0.0f) || value > 1e30f)
            throw bad_value(m, "exponents", "'" + text + "' is not P,N with positive exponents P and N");
        check(range, value, m.name);
        return value;
    };
    s.positive_exponent = exponent(text.substr(0, comma), kPositiveExponentRange);
    if (two) s.negative_exponent = exponent(text.substr(comma + 1), kNegativeExponentRange);
}

// A named pair of PCSS sample counts (penumbra/soft_pcf.h, kPcssPresets).
void set_preset(const Method& m, const std::string& text, MethodSettings& s)
{
    std::string names;
    for (const PcssPreset& preset : kPcssPresets) {
        if (text == preset.name) {
            s.blocker_samples = preset.blocker_samples;
            s.filter_samples = preset.filter_samples;
            return;
        }
        names += (names.empty() ? "" : ", ") + std::string(preset.name);
    }
    throw bad_value(m, "preset", "'" + text + "' is not a preset (" + names + ")");
}

// One of a list of words: its index in `words`.
template <std::size_t N>
int parse_word(const Method& m, std::string_view parameter, const std::string& text, const char* const (&words)[N])
{
    std::string names;
    for (std::size_t i = 0; i < N; ++i) {
        if (text == words[i]) return int(i);
        names += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(words[i]);
    }
    throw bad_value(m, parameter, "'" + text + "' is not " + names);
}

void set_bias_mode(const Method& m, const std::string& text, MethodSettings& s)
{
    static const char* const kModes[] = {"constant", "slope", "receiver-plane"};  // BiasMode's order
    s.bias_mode = BiasMode(parse_word(m, "bias-mode", text, kModes));
}

void set_derivatives(const Method& m, const std::string& text, MethodSettings& s)
{
    static const char* const kSources[] = {"differences", "channels"};  // DerivativeSource's order
    s.derivatives = DerivativeSource(parse_word(m, "bias-derivatives", text, kSources));
}

void set_rotation(const Method& m, const std::string& text, MethodSettings& s)
{
    static const char* const kRotations[] = {"none", "tile"};
    s.rotate = parse_word(m, "rotation", text, kRotations) == 1;
}

void set_deep_filter(const Method& m, const std::string& text, MethodSettings& s)
{
    static const char* const kFilters[] = {"box", "tent"};  // DeepFilter's order
    s.deep_filter = DeepFilter(parse_word(m, "filter", text, kFilters));
}

void set_deep_search(const Method& m, const std::string& text, MethodSettings& s)
{
    static const char* const kSearches[] = {"binary", "linear"};  // DeepSearch's order
    s.deep_search = DeepSearch(parse_word(m, "search", text, kSearches));
}

void set_depth_convention(const Method& m, const std::string& text, MethodSettings& s)
{
    try {
        s.depth_convention.kind = parse_depth_convention(text);
    } catch (const Error& e) {
        throw e.as_operation(m.name);
    }
}

void set_near(const Method& m, const std::string& text, MethodSettings& s)
{
    s.depth_convention.near = parse_float(m, "near", text);
}

void set_far(const Method& m, const std::string& text, MethodSettings& s)
{
    s.depth_convention.far = parse_float(m, "far", text);
}

// near and far belong to the conventions that read them; those need both.
void check_convention_options(const Method& m, const std::vector<std::pair<std::string, std::string>>& given,
                              const MethodSettings& s)
{
    if (s.depth_convention.kind != DepthConventionKind::Normalized)
        return check_depth_convention(s.depth_convention, m.name);
    for (const auto& [name, text] : given)
        if (name == "near" || name == "far")
            throw bad_value(m, name,
                            name + " applies to the linear, perspective and reversed depth conventions, not to "
                                   "normalized depth (the default); give the convention too");
}

const MethodOption* find_option(std::string_view name)
{
    for (const MethodOption& o : method_options())
        if (name == o.name) return &o;
    return nullptr;
}

bool reads(const Method& m, std::string_view option)
{
    for (std::string_view name : m.reads)
        if (name == option) return true;
    return false;
}

// "msm and msm-soft", "msm, msm-soft, evsm2 and evsm4".
std::string readers(std::string_view option)
{
    std::vector<std::string> names;
    for (const Method& m : methods())
        if (reads(m, option)) names.emplace_back(m.name);
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i)
        text += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
    return text;
}

}  // namespace

// The option reads any light size >= 0; each operation checks its own range
// (vssm and msm-soft need L > 0, pcss takes 0: a hard shadow equal to pcf r=0).
constexpr ParameterRange kLightSizeOptionRange{"light-size", "light-size", 0, kNoUpperBound, false, true};

const std::vector<MethodOption>& method_options()
{
    using S = MethodSettings;
    static const std::vector<MethodOption> options = {
        {"radius", "R", "box radius in texels, window (2R+1)^2", "2", &kRadiusRange, true, set_radius},
        {"min-variance", "V", "variance floor in depth^2", "2e-5", &kMinVarianceRange, true,
         set_float<&S::min_variance, kMinVarianceRange>},
        {"bleed", "B", "light-bleeding reduction (0 = off)", "0", &kBleedRange, true,
         set_float<&S::bleed, kBleedRange>},
        {"light-size", "L", "light size L in texture units: the blocker search's width and L in the penumbra w = L (z - z_b) / z_b (docs/reference.md; vssm, msm-soft: > 0; pcss: 0 = hard)",
         "0.02", &kLightSizeOptionRange, true, set_float<&S::light_size, kLightSizeOptionRange>},
        {"moment-bias", "A", "share of each window moved to depths 0 and 1", "6e-5", &kMomentBiasRange, false,
         set_float<&S::moment_bias, kMomentBiasRange>},
        {"depth-bias", "D",
         "subtracted from receiver depth (sloped ones need about half a texel's depth change more)",
         "3.05e-5 = two 16-bit steps (msm*), 0 (evsm*), 1e-3 (pcf*), 5e-4 (pcss), 0 = the cone's tip (burley), "
         "3e-3 (dsm)",
         &kDepthBiasRange, false,
         set_float<&S::depth_bias, kDepthBiasRange>},
        {"plane-bias", "S",
         "msm-soft: each window's depth lowered by S x the receiver plane's drop inside it (1: a planar receiver "
         "never shadows itself in a wide window; 0 = off)",
         "0", &kPlaneBiasRange, false, set_float<&S::plane_bias, kPlaneBiasRange>},
        {"plane-bias-max", "B", "msm-soft: the largest plane bias, depth units", "0.02", &kPlaneBiasMaxRange, false,
         set_float<&S::plane_bias_max, kPlaneBiasMaxRange>},
        {"quantize", "16",
         "MSM's optimized 16-bit storage (I3D 2015; 16 B/texel, not 48): moves visibility by up to 0.56",
         "none (exact 48-bit tables)", nullptr, false, set_quantization},
        {"exponents", "P,N", "warp exponents c+,c- (evsm2: P only); above 10 exact storage could not keep 2e-4",
         "10,5", &kPositiveExponentRange, false, set_exponents, {"positive-exponent", "negative-exponent"}},
        {"blocker-samples", "N", "taps of the blocker search (Hammersley disc)", "16", &kBlockerSamplesRange, false,
         set_int<&S::blocker_samples, kBlockerSamplesRange>},
        {"filter-samples", "N", "taps of the percentage-closer filter (Hammersley disc)", "24",
         &kFilterSamplesRange, false, set_int<&S::filter_samples, kFilterSamplesRange>},
        {"preset", "NAME", "blocker/filter taps: hdrp = 16/24, godot-ultra = 32/32", "none", nullptr, false,
         set_preset, {"blocker-samples", "filter-samples"}},
        {"min-radius", "R", "filter radius at contact, texture units", "0.0005", &kMinRadiusRange, false,
         set_float<&S::min_radius, kMinRadiusRange>},
        {"max-radius", "R", "blocker-search radius and widest filter, texture units", "0.01", &kMaxRadiusRange,
         false, set_float<&S::max_radius, kMaxRadiusRange>},
        {"bias-slope", "S", "the bias cone's slope: depth per texture unit of tap radius", "2 (Burley's)",
         &kBiasSlopeRange, false, set_float<&S::bias_slope, kBiasSlopeRange>},
        {"bias-slope-per-depth", "K", "added to the cone's slope per unit of receiver depth z (a perspective light: "
         "see world_cone in penumbra/soft_pcf.h)", "0", &kSlopePerDepthRange, false,
         set_float<&S::bias_slope_per_depth, kSlopePerDepthRange>},
        {"falloff", "D", "shadow opacity 1 - (z - z_blocker) / D, clamped (0 = off)", "0", &kFalloffRange, false,
         set_float<&S::falloff, kFalloffRange>},
        {"bias-mode", "M",
         "constant (depth >= z - depth-bias), slope (+ slope-scale x the depth step per texel) or receiver-plane "
         "(each tap on the receiver's plane, Isidoro 2006); slope and receiver-plane clamp to [bias-min, bias-max]",
         "constant", nullptr, false, set_bias_mode},
        {"bias-min", "B", "lower clamp of the slope and receiver-plane biases (Toy Story 3)", "0", &kBiasMinRange,
         false, set_float<&S::bias_min, kBiasMinRange>},
        {"bias-max", "B", "upper clamp of the slope and receiver-plane biases (Toy Story 3)", "0.02", &kBiasMaxRange,
         false, set_float<&S::bias_max, kBiasMaxRange>},
        {"slope-scale", "S", "slope bias per unit of the receiver's depth change across one texel", "1",
         &kSlopeScaleRange, false, set_float<&S::slope_scale, kSlopeScaleRange>},
        {"bias-derivatives", "D",
         "dz/du, dz/dv of slope, receiver-plane and msm-soft's plane-bias: differences (receivers' neighbours) or "
         "channels (RX.exr dzdu, dzdv)",
         "differences", nullptr, false, set_derivatives},
        {"grid", "N", "taps per side of the Gaussian grid (4: Toy Story 3's 4x4)", "4", &kPcfGridRange, false,
         set_int<&S::grid, kPcfGridRange>},
        {"sigma", "S", "the grid's Gaussian standard deviation, texels", "1", &kPcfSigmaRange, false,
         set_float<&S::sigma, kPcfSigmaRange>},
        {"taps", "N", "taps of the Vogel disc", "16", &kPcfTapsRange, false, set_int<&S::taps, kPcfTapsRange>},
        {"rays", "R", "shadow rays per receiver, stratified over the light mesh's triangles by area", "64",
         &kPismoRaysRange, false, set_int<&S::rays, kPismoRaysRange>},
        {"disc-radius", "R", "the disc's radius, texels", "2.5", &kPcfDiscRadiusRange, false,
         set_float<&S::disc_radius, kPcfDiscRadiusRange>},
        {"rotation", "tile|none", "the disc rotated per receiver from Toy Story 3's 4x4 tile, or not (bands)",
         "tile", nullptr, false, set_rotation},
        {"filter", "box|tent",
         "the deep map's lookup filter: box, (2R+1)^2 pixels around the receiver's; tent, bilinear of half-width "
         "R+1 texels, (2R+2)^2 pixels",
         "tent", nullptr, false, set_deep_filter},
        {"depth-convention", "C",
         "how the shadow map's depths and the receivers' z are stored: normalized ([0, 1]), linear (distance in "
         "[near, far]), perspective (D3D/Vulkan [0, 1] projected depth) or reversed (1 - perspective); biases stay "
         "in normalised depth (docs/integration.md)",
         "normalized", nullptr, false, set_depth_convention},
        {"near", "N", "the light's near distance (linear, perspective, reversed: required; > 0 but for linear)",
         "none", nullptr, false, set_near},
        {"far", "F", "the light's far distance, > near and finite (linear, perspective, reversed: required)", "none",
         nullptr, false, set_far},
        {"search", "linear|binary", "how a deep pixel's vertices are searched for the receiver's depth (one result)",
         "linear (measured faster, docs/deep_shadow_maps.md)", nullptr, false, set_deep_search},
    };
    return options;
}

const MethodOption* option_for_parameter(std::string_view parameter)
{
    for (const MethodOption& o : method_options()) {
        if (parameter == o.name) return &o;
        for (std::string_view p : o.parameters)
            if (p == parameter) return &o;
    }
    return nullptr;
}

MethodSettings parse_method_settings(const Method& method,
                                     const std::vector<std::pair<std::string, std::string>>& given)
{
    MethodSettings settings;
    for (const auto& [name, text] : given) {
        const MethodOption* option = find_option(name);
        if (!option) throw bad_value(method, name, "is not an option of the shading methods");
        if (!option->shared && !reads(method, name))
            throw bad_value(method, name, "applies to " + readers(name) + " only");
        option->parse(method, text, settings);
    }
    if (reads(method, "depth-convention")) check_convention_options(method, given, settings);
    return settings;
}

std::string method_options_help(std::string_view flag_prefix)
{
    std::string text;
    for (const MethodOption& o : method_options()) {
        std::string head = "  " + std::string(flag_prefix) + o.name + " " + o.value;
        head.resize(std::max<std::size_t>(head.size() + 1, 21), ' ');
        text += head + o.help + "\n";
        std::string facts;
        if (o.range) {
            const std::string range = describe(*o.range);
            facts = (range[0] == '[' || range[0] == '(' ? "in " : "") + range + "; ";
        }
        facts += "default " + std::string(o.fallback) + "; " + (o.shared ? "read by " : "for ") + readers(o.name);
        text += std::string(21, ' ') + facts + "\n";
    }
    return text;
}

}  // namespace penumbra
