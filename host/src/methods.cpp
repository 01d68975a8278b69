// The method table (penumbra/methods.h): one entry per shading method, its
// build step (the method's own table) and its shade step; the options'
// parsing and help are in method_options.cpp.
#include "penumbra/methods.h"

#include <algorithm>

#include "penumbra/error.h"
#include "visibility_output.h"

namespace penumbra {
namespace {

// Box methods at small radii in the default storage: no table; the shade
// step sums each window from the map (the `_direct` entries,
// kernels/box_window.h), which is faster there than a table's lookup and
// computes the same method (docs/moment_table.md, "Direct sums for small
// windows", has the measured cuts). The shade steps read the table when the
// build step made one.
bool direct_window(const MethodSettings& s, int max_radius)
{
    return s.radius <= max_radius && s.precision == Precision::Exact && s.quantization == Quantization::None;
}

// Chebyshev methods: the two-moment table (exact, the default).
PreparedMap prepare_moment_table(Context& context, const Image& map, const MethodSettings& s)
{
    return PreparedMap(map, build_moment_table(context, map, 2, s.precision, s.depth_convention));
}

PreparedMap prepare_vsm(Context& context, const Image& map, const MethodSettings& s)
{
    if (direct_window(s, kVsmDirectMaxRadius)) return PreparedMap(map);
    return prepare_moment_table(context, map, s);
}

void shade_vsm(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
               Image& out)
{
    const VsmOptions options{s.radius, s.min_variance, s.bleed, s.depth_convention};
    if (!prepared.has_table()) return vsm(context, prepared.map(), receivers, options, out);
    vsm(context, prepared.table<MomentTable>(), receivers, options, out);
}

void shade_vssm(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
                Image& out)
{
    vssm(context, prepared.table<MomentTable>(), receivers,
         VssmOptions{s.light_size, s.min_variance, s.bleed, s.depth_convention}, out);
}

PreparedMap prepare_msm_table(Context& context, const Image& map, const MethodSettings& s)
{
    return PreparedMap(map, build_msm_table(context, map, s.quantization, s.precision, s.depth_convention));
}

PreparedMap prepare_msm(Context& context, const Image& map, const MethodSettings& s)
{
    if (direct_window(s, kMsmDirectMaxRadius)) return PreparedMap(map);
    return prepare_msm_table(context, map, s);
}

void shade_msm(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
               Image& out)
{
    const MsmOptions options{s.radius, s.moment_bias, s.depth_bias, s.depth_convention};
    if (!prepared.has_table()) return msm(context, prepared.map(), receivers, options, out);
    msm(context, prepared.table<MsmTable>(), receivers, options, out);
}

void shade_msm_soft(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
                    Image& out)
{
    const MsmSoftOptions options{s.light_size,     s.moment_bias, s.depth_bias,       s.plane_bias,
                                 s.plane_bias_max, s.derivatives, s.depth_convention};
    msm_soft(context, prepared.table<MsmTable>(), receivers, options, out);
}

// EVSM2 keeps the positive warp only (2 channels), EVSM4 both (4).
template <int Channels>
EvsmWarp evsm_warp(const MethodSettings& s)
{
    return EvsmWarp{Channels, s.positive_exponent, s.negative_exponent, s.quantization};
}

template <int Channels>
PreparedMap prepare_evsm(Context& context, const Image& map, const MethodSettings& s)
{
    if (direct_window(s, kEvsmDirectMaxRadius)) return PreparedMap(map);
    return PreparedMap(map, build_evsm_table(context, map, evsm_warp<Channels>(s), s.precision, s.depth_convention));
}

template <int Channels>
void shade_evsm(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
                Image& out)
{
    const EvsmOptions options{s.radius, s.min_variance, s.bleed, s.depth_bias.value_or(0.0f), s.depth_convention};
    if (!prepared.has_table()) return evsm(context, prepared.map(), evsm_warp<Channels>(s), receivers, options, out);
    evsm(context, prepared.table<EvsmTable>(), receivers, options, out);
}

// The percentage-closer family reads the map itself (prepare_map).
DepthBias depth_bias_of(const MethodSettings& s)
{
    return DepthBias{s.bias_mode, s.depth_bias.value_or(kPcfDefaultDepthBias), s.slope_scale, s.bias_min,
                     s.bias_max, s.derivatives};
}

void shade_pcf(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
               Image& out)
{
    pcf(context, prepared.map(), receivers, PcfOptions{s.radius, depth_bias_of(s), s.depth_convention}, out);
}

void shade_pcf_gauss(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
                     Image& out)
{
    pcf_gauss(context, prepared.map(), receivers,
              PcfGaussOptions{s.grid, s.sigma, depth_bias_of(s), s.depth_convention}, out);
}

void shade_pcf_disc(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
                    Image& out)
{
    pcf_disc(context, prepared.map(), receivers,
             PcfDiscOptions{s.taps, s.disc_radius, s.rotate, depth_bias_of(s), s.depth_convention}, out);
}

// The soft members of the percentage-closer family read the map itself,
// under the family's bias options with their own default constant.
DepthBias family_bias(const MethodSettings& s, float default_constant)
{
    DepthBias b = depth_bias_of(s);
    b.constant = s.depth_bias.value_or(default_constant);
    return b;
}

void shade_pcss(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
                Image& out)
{
    PcssOptions options{s.light_size, s.blocker_samples, s.filter_samples};
    options.bias = family_bias(s, options.bias.constant);
    options.depth_convention = s.depth_convention;
    pcss(context, prepared.map(), receivers, options, out);
}

void shade_burley(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
                  Image& out)
{
    BurleyOptions options{.min_radius = s.min_radius,
                          .max_radius = s.max_radius,
                          .bias_slope = s.bias_slope,
                          .bias_slope_per_depth = s.bias_slope_per_depth,
                          .falloff = s.falloff,
                          .blocker_samples = s.blocker_samples,
                          .filter_samples = s.filter_samples};
    options.bias = family_bias(s, options.bias.constant);
    options.depth_convention = s.depth_convention;
    burley(context, prepared.map(), receivers, options, out);
}

// Deep shadow maps: the map is the prepared input itself (no table).
PreparedMap prepare_deep_map(Context&, const DeepShadowMap& map, const MethodSettings&) { return PreparedMap(map); }

void shade_dsm(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
               Image& out)
{
    const DeepLookupOptions options{s.deep_filter, s.radius, s.deep_search, s.depth_bias.value_or(kDeepDefaultBias)};
    deep_lookup(context, prepared.deep_map(), receivers, options, out);
}

// Pismo: the build step bleeds the stored maps (and derives the maximum-depth
// variant); the shade step casts the rays (penumbra/pismo.h).
template <PismoDepths Depths>
PreparedMap prepare_pismo(Context&, const PismoMapSet& set, const MethodSettings&)
{
    // The maximum-depth maps keep no surface's crossing: their layers carry no id.
    return PreparedMap(set, PismoMaps(set.vertices, set.triangles, set.maps, Depths,
                                      Depths == PismoDepths::Layered ? set.surface_ids
                                                                     : std::vector<std::vector<std::int32_t>>{}));
}

void shade_pismo(Context& context, const PreparedMap& prepared, const Image& receivers, const MethodSettings& s,
                 Image& out)
{
    PismoOptions options;
    options.rays = s.rays;
    pismo_shade(context, prepared.table<PismoMaps>(), receivers, options, out);
}

// The smallest set the shadow-ray test takes, for the warm-up: one triangle
// of 1 x 1 maps, each camera at its vertex looking along +z.
PismoMapSet one_triangle_set()
{
    PismoMapSet set;
    set.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    set.triangles = {{0, 1, 2}};
    for (const auto& v : set.vertices) {
        MapCamera camera;
        camera.position = v;
        set.maps.emplace_back(1, 1, camera, std::vector<std::uint32_t>{0, 1}, std::vector<float>{1.0f});
    }
    return set;
}

void require_input(const Method& m, MethodInput given)
{
    if (m.input == given) return;
    throw Error(ErrorCategory::InvalidArgument, m.name, "method",
                std::string(m.name) + " reads a " + input_info(m.input).what + ", not a " + input_info(given).what);
}

}  // namespace

const std::vector<MethodInputInfo>& method_inputs()
{
    static const std::vector<MethodInputInfo> inputs = {
        {MethodInput::ShadowMap, "depth", "shadow-map", "shadow map"},
        {MethodInput::DeepMap, "deep-map", "deep-map", "deep shadow map"},
        {MethodInput::PismoMapSet, "maps", "pismo-maps", "set of Pismo maps"},
    };
    return inputs;
}

const MethodInputInfo& input_info(MethodInput input)
{
    for (const MethodInputInfo& info : method_inputs())
        if (info.input == input) return info;
    throw Error(ErrorCategory::InvalidArgument, "shade", "method", "an input no method table entry knows");
}

std::vector<std::string> receiver_channels(const MethodSettings& s)
{
    // The receiver's plane is read by the family's slope and receiver-plane
    // biases, and by msm-soft's plane bias; each option is left at its
    // default (off) by the methods that do not read it.
    const bool reads_plane = s.bias_mode != BiasMode::Constant || s.plane_bias > 0.0f;
    if (reads_plane && s.derivatives == DerivativeSource::Channels)
        return {"u", "v", "z", "dzdu", "dzdv"};
    return {"u", "v", "z"};
}

std::vector<std::string> receiver_channels(const Method& method, const MethodSettings& s)
{
    if (method.input == MethodInput::PismoMapSet) return {"P.x", "P.y", "P.z"};
    return receiver_channels(s);
}

PreparedMap prepare_map(Context&, const Image& map, const MethodSettings&) { return PreparedMap(map); }

Image Method::run(Context& context, const Image& map, const Image& receivers, const MethodSettings& settings) const
{
    require_input(*this, MethodInput::ShadowMap);
    const PreparedMap prepared = prepare(context, map, settings);
    return detail::visibility_output(receivers, [&](Image& out) { shade(context, prepared, receivers, settings, out); });
}

Image Method::run(Context& context, const DeepShadowMap& map, const Image& receivers,
                  const MethodSettings& settings) const
{
    require_input(*this, MethodInput::DeepMap);
    const PreparedMap prepared = prepare_deep(context, map, settings);
    return detail::visibility_output(receivers, [&](Image& out) { shade(context, prepared, receivers, settings, out); });
}

PreparedMap Method::prepare_view(Context& context, const ImageView& map, const MethodSettings& settings) const
{
    require_input(*this, MethodInput::ShadowMap);
    auto input = std::make_shared<const InputImage>(map, name, input_info(MethodInput::ShadowMap).parameter);
    PreparedMap prepared = prepare(context, input->image(), settings);
    prepared.hold(std::move(input));
    return prepared;
}

void Method::shade_view(Context& context, const PreparedMap& prepared, const ImageView& receivers,
                        const MethodSettings& settings, const MutableImageView& out) const
{
    const InputImage input(receivers, name, "receivers");
    OutputImage output(out, name, "out");
    require_disjoint(receivers, out, name, "out");
    shade(context, prepared, input.image(), settings, output.image());
    output.commit();
}

void Method::run(Context& context, const ImageView& map, const ImageView& receivers, const MethodSettings& settings,
                 const MutableImageView& out) const
{
    shade_view(context, prepare_view(context, map, settings), receivers, settings, out);
}

Image Method::run(Context& context, const PismoMapSet& set, const Image& receivers,
                  const MethodSettings& settings) const
{
    require_input(*this, MethodInput::PismoMapSet);
    const PreparedMap prepared = prepare_pismo(context, set, settings);
    return detail::visibility_output(receivers, [&](Image& out) { shade(context, prepared, receivers, settings, out); });
}

void Method::warm_up(Context& context, const MethodSettings& settings) const
{
    if (context.backend() != Backend::OpenCL) return;
    if (input == MethodInput::PismoMapSet) {
        Image receivers(1, 1, 3);
        for (int c = 0; c < 3; ++c) receivers.fill(c, c < 2 ? 0.2f : 2.0f);  // in front of every map
        (void)run(context, one_triangle_set(), receivers, settings);
        return;
    }
    // u, v, z (mid-range in the settings' depth convention); dzdu, dzdv.
    const StoredDepthRange depths = stored_depth_range(settings.depth_convention);
    const float middle = 0.5f * depths.low + 0.5f * depths.high;
    Image receivers(1, 1, int(receiver_channels(settings).size()));
    for (int c = 0; c < receivers.channels(); ++c) receivers.fill(c, c < 2 ? 0.5f : c == 2 ? middle : 0.0f);
    if (input == MethodInput::DeepMap) {
        (void)run(context, DeepShadowMap(1, 1, {0, 0}, {}, {}), receivers, settings);  // one empty pixel
        return;
    }
    Image map(1, 1, 1);
    map.fill(0, middle);
    (void)run(context, map, receivers, settings);
}

// The options of a method that reads a shadow map, and its depth convention's.
std::vector<std::string_view> reading_a_map(std::vector<std::string_view> options)
{
    options.insert(options.end(), {"depth-convention", "near", "far"});
    return options;
}

const std::vector<Method>& methods()
{
    static const std::vector<Method> table = {
        {"vsm", "variance shadow maps: Chebyshev bound over a box window (Donnelly & Lauritzen 2006)",
         reading_a_map({"radius", "min-variance", "bleed"}), prepare_vsm, shade_vsm},
        {"vssm", "variance soft shadow maps: blocker search sized by the light (Yang et al. 2010)",
         reading_a_map({"light-size", "min-variance", "bleed"}), prepare_moment_table, shade_vssm},
        {"msm", "moment shadow maps: four moments, Hamburger bound (Peters & Klein 2015)",
         reading_a_map({"radius", "moment-bias", "depth-bias", "quantize"}), prepare_msm, shade_msm},
        {"msm-soft", "moment soft shadows: blocker search on four moments (Peters et al. 2016)",
         reading_a_map({"light-size", "moment-bias", "depth-bias", "plane-bias", "plane-bias-max", "bias-derivatives",
                        "quantize"}),
         prepare_msm_table, shade_msm_soft},
        {"evsm2", "exponential variance shadow maps, positive warp (Lauritzen & McCool 2008)",
         reading_a_map({"radius", "min-variance", "bleed", "depth-bias", "exponents"}), prepare_evsm<2>, shade_evsm<2>},
        {"evsm4", "exponential variance shadow maps, both warps (Lauritzen & McCool 2008)",
         reading_a_map({"radius", "min-variance", "bleed", "depth-bias", "exponents"}), prepare_evsm<4>, shade_evsm<4>},
        {"pcf", "percentage-closer filtering over a box window (Reeves et al. 1987)",
         reading_a_map(
             {"radius", "depth-bias", "bias-mode", "bias-min", "bias-max", "slope-scale", "bias-derivatives"}),
         prepare_map, shade_pcf},
        {"pcf-gauss", "PCF on an NxN grid of Gaussian-weighted bilinear taps (Toy Story 3, 2010)",
         reading_a_map({"grid", "sigma", "depth-bias", "bias-mode", "bias-min", "bias-max", "slope-scale",
                        "bias-derivatives"}),
         prepare_map, shade_pcf_gauss},
        {"pcf-disc", "PCF over a Vogel-spiral disc rotated per receiver from a 4x4 tile (Toy Story 3)",
         reading_a_map({"taps", "disc-radius", "rotation", "depth-bias", "bias-mode", "bias-min", "bias-max",
                        "slope-scale", "bias-derivatives"}),
         prepare_map, shade_pcf_disc},
        {"pcss", "percentage-closer soft shadows: blocker search, width, PCF on a disc (Fernando 2005)",
         reading_a_map({"light-size", "depth-bias", "bias-mode", "bias-min", "bias-max", "slope-scale",
                        "bias-derivatives", "blocker-samples", "filter-samples", "preset"}),
         prepare_map, shade_pcss},
        {"burley", "soft shadows on the bias cone, weighted blocker depth (Burley, Disney)",
         reading_a_map({"min-radius", "max-radius", "depth-bias", "bias-mode", "bias-min", "bias-max", "slope-scale",
                        "bias-derivatives", "bias-slope", "bias-slope-per-depth", "falloff", "blocker-samples",
                        "filter-samples"}),
         prepare_map, shade_burley},
        {"dsm", "deep shadow maps: filtered lookup of per-pixel transmittance functions (Lokovic & Veach 2000)",
         {"radius", "depth-bias", "filter", "search"}, nullptr, shade_dsm, MethodInput::DeepMap, prepare_deep_map},
        {"pismo", "Pismo: area light from layered depth maps at a light mesh's vertices, parallax-interpolated (Neulander)",
         {"rays"}, nullptr, shade_pismo, MethodInput::PismoMapSet, nullptr, prepare_pismo<PismoDepths::Layered>},
        {"pismo-maxdepth", "Pismo on single-channel maximum-depth maps: right only outside the casters' hull",
         {"rays"}, nullptr, shade_pismo, MethodInput::PismoMapSet, nullptr, prepare_pismo<PismoDepths::MaximumDepth>},
    };
    return table;
}

const Method& find_method(std::string_view name)
{
    for (const Method& m : methods())
        if (name == m.name) return m;
    // append, not "'" + std::string: GCC 12 warns falsely on that (-Wrestrict, bug 105329).
    std::string message(1, '\'');
    message.append(name).append("' is not a shading method (").append(method_names(", ")).append(")");
    throw Error(ErrorCategory::InvalidArgument, "shade", "method", message);
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
        line.resize(std::max<std::size_t>(13, line.size() + 1), ' ');  // a long name keeps a space
        text += line + m.summary + "\n";
    }
    return text;
}

}  // namespace penumbra
