// The demo's method list. The shading methods are the library's method table
// (penumbra/methods.h) at a sweep of the setting that trades time or blur for
// error: the window radius of the box methods, the light size of the soft
// ones (around the scene's own, from reference::light_size). The rows that
// are no shading method (distance fields, the +blur variants) are the demo's.
#include "demo_methods.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <optional>

#include "penumbra/bilateral.h"
#include "penumbra/methods.h"
#include "penumbra/reference/cascades.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/sdf_scene.h"
#include "penumbra/sdf.h"
#include "penumbra/ssao.h"

namespace penumbra::cli {
namespace {

std::string format(const char* pattern, double value)
{
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

// The setting whose images the demo writes: the middle of a three-point
// sweep, the first of the others (the estimate k, the one blurred variant).
constexpr int kMiddleSetting = 1;
constexpr int kFirstSetting = 0;

struct SweepPoint {
    std::string label;
    MethodSettings settings;
};

// One setting of a method of the library's method table: its build step on
// what the method reads from the frame (the shadow map, the deep map or the
// Pismo maps), its shade step on the receivers' light-space (u, v, z) or, for
// Pismo, their world positions.
DemoSetting table_setting(const Method& method, std::string label, MethodSettings s)
{
    const auto prepare = [&method, s](Context& ctx, const DemoFrame& f) -> PreparedMap {
        switch (method.input) {
        case MethodInput::DeepMap: return method.prepare_deep(ctx, *f.deep_map, s);
        case MethodInput::PismoMapSet: return method.prepare_pismo(ctx, *f.pismo_maps, s);
        default: return method.prepare(ctx, f.shadow_map, s);
        }
    };
    return {.label = std::move(label),
            .prepare = [prepare](Context& ctx, const DemoFrame& f) -> DemoPrepared {
                return std::make_shared<const PreparedMap>(prepare(ctx, f));
            },
            .shade = [&method, s](Context& ctx, const DemoFrame&, const reference::Receivers& rx,
                                  const DemoPrepared& prepared) {
                // Pismo reads positions, normals and surface ids (the receiver's own surface counts, and
                // with the maps' ids no layer of it occludes); stacking the seven planes is one pass over
                // the view, under 1% of Pismo's own time at the demo's sizes.
                const Image receivers =
                    method.input == MethodInput::PismoMapSet ? rx.positions_normals_and_surface() : rx.light_uvz;
                Image out(receivers.width(), receivers.height(), 1);
                method.shade(ctx, *std::static_pointer_cast<const PreparedMap>(prepared), receivers, s, out);
                return out;
            }};
}

// A method of the library's method table at the settings of `sweep`.
DemoMethod table_method(const char* name, const std::vector<SweepPoint>& sweep, int preview = kMiddleSetting)
{
    const Method& method = find_method(name);
    DemoMethod m{.name = method.name, .settings = {}, .preview_setting = preview, .input = method.input};
    for (const SweepPoint& point : sweep) m.settings.push_back(table_setting(method, point.label, point.settings));
    return m;
}

// Moment shadow maps on the exact limb table. The default depth bias leaves
// acne on sloped receivers; 3e-4 (about 20 16-bit depth steps) removes it on
// the reference scenes (docs/moments.md).
constexpr float kDemoMsmDepthBias = 3e-4f;
// msm-soft's receiver-plane share (kernels/msm_soft.h): on contact's frame
// 0.5 keeps 99.67% of lit receivers above 0.98 at RMSE 0.0313, 1 99.82% at
// 0.0321, 0 (off) 99.21% at 0.0310 (docs/moments.md, "The msm-soft halo").
constexpr float kDemoMsmSoftPlaneBias = 0.5f;

// A point light (the deep scenes') has no size, and the soft methods need
// one: PCSS refuses light_size 0 and a distance field's k would be infinite.
// They shade it as the smallest square light the map can show: one whose
// penumbra, from a blocker to the receiver at the scene's reference depths,
// is one texel wide. Their sweeps (0.5x, 1x, 2x) then span a half to two
// texels, the hard-shadow limit each method reaches at this resolution; the
// truth stays the point light's, exact per receiver (docs/deep_shadow_maps.md,
// "The demo on the deep scenes").
reference::Scene with_light_of_side(reference::Scene scene, double side)
{
    scene.light.shape = reference::LightShape::Rectangle;
    scene.light.width = scene.light.height = side;
    return scene;
}

double one_texel_light_side(const reference::Scene& scene, int map_size)
{
    const reference::ReferenceDepths depths = reference::reference_depths(scene);
    // The penumbra width is linear in the light's side: measure a 1 m one
    // (> 0: the reference blocker always lies in front of the receiver).
    const double per_metre = reference::penumbra_width(with_light_of_side(scene, 1.0), depths.z_receiver,
                                                       depths.z_blocker);
    return 1.0 / (double(map_size) * per_metre);
}

// The scene the soft methods size their filters for: itself, or under a
// point light the one-texel stand-in (the side measured on frame 0, so the
// shifted frames keep it and no shade step pays for the measurement).
struct SoftLight {
    double side = 0;  // 0: the scene's own (area) light
    reference::Scene apply(const reference::Scene& scene) const
    {
        return side > 0 ? with_light_of_side(scene, side) : scene;
    }
};

SoftLight soft_light_for(const reference::Scene& scene, int map_size)
{
    if (scene.light.shape != reference::LightShape::Point) return {};
    return {one_texel_light_side(scene, map_size)};
}

// No per-map step: what the setting reads was rendered with the frame (or,
// for the distance fields, baked offline).
DemoPrepared nothing_prepared(Context&, const DemoFrame&) { return DemoPrepared(); }

// The box methods sweep the radius (EVSM with the exact table's default
// exponents).
std::vector<SweepPoint> radius_sweep(std::optional<float> depth_bias = std::nullopt)
{
    std::vector<SweepPoint> sweep;
    for (int radius : {1, 3, 6}) {
        MethodSettings s;
        s.radius = radius;
        s.depth_bias = depth_bias;
        sweep.push_back({"r=" + std::to_string(radius), s});
    }
    return sweep;
}

// The percentage-closer family, pcss and burley included, on the
// receiver-plane bias (the mode that needs no per-scene tuning, Toy Story 3;
// pcss's constant 5e-4 left it 0.15-0.49 over-dark from acne). The pcf
// filters sweep their footprint: the box radius, the Gaussian grid's sigma,
// the disc's tap count at 3 texels.
MethodSettings pcf_settings()
{
    MethodSettings s;
    s.bias_mode = BiasMode::ReceiverPlane;
    return s;
}

// The soft methods sweep the light size around the scene's own; the exact
// table keeps blocker searches up to 253 texels exact.
std::vector<SweepPoint> light_sweep(const reference::Scene& scene, int map_size, MethodSettings base = {})
{
    const double physical = reference::light_size(scene);
    const double largest = 252.0 / map_size;
    std::vector<SweepPoint> sweep;
    for (double scale : {0.5, 1.0, 2.0}) {
        MethodSettings s = base;
        s.light_size = float(std::min(physical * scale, largest));
        sweep.push_back({format("L=%.3g", s.light_size), s});
    }
    return sweep;
}

// Burley sweeps its widest radius with the scene's light: R = light_size x
// {0.5, 1, 2}; at scale 1 that is the filter radius PCSS gives a blocker at
// a third of the receiver's depth (w / 2 = L (z - z/3) / (z/3) / 2 = L);
// the contact radius is half a texel.
std::vector<SweepPoint> burley_sweep(const reference::Scene& scene, int map_size)
{
    const double physical = reference::light_size(scene);
    std::vector<SweepPoint> sweep;
    for (double scale : {0.5, 1.0, 2.0}) {
        MethodSettings s = pcf_settings();
        s.max_radius = float(std::min(physical * scale, 0.5));
        s.min_radius = std::min(0.5f / float(map_size), s.max_radius);
        sweep.push_back({format("R=%.3g", s.max_radius), s});
    }
    return sweep;
}

std::vector<SweepPoint> pcf_sweep()
{
    std::vector<SweepPoint> sweep;
    for (int radius : {1, 3, 6}) {
        MethodSettings s = pcf_settings();
        s.radius = radius;
        sweep.push_back({"r=" + std::to_string(radius), s});
    }
    return sweep;
}

std::vector<SweepPoint> pcf_gauss_sweep()
{
    std::vector<SweepPoint> sweep;
    for (float sigma : {0.5f, 1.0f, 2.0f}) {
        MethodSettings s = pcf_settings();
        s.sigma = sigma;
        sweep.push_back({format("4x4 s=%.2g", sigma), s});
    }
    return sweep;
}

std::vector<SweepPoint> pcf_disc_sweep()
{
    std::vector<SweepPoint> sweep;
    for (int taps : {8, 16, 32}) {
        MethodSettings s = pcf_settings();
        s.taps = taps;
        s.disc_radius = 3.0f;
        sweep.push_back({"N=" + std::to_string(taps), s});
    }
    return sweep;
}

// Distance-field shadows trace the scene itself, not the shadow map: the
// grid is what an engine bakes offline, so it is baked once per scene (not
// timed) at a node budget that grows with the demo's map size; the analytic
// form evaluates the primitives in the kernel. k comes from the light's size
// (sdf_options_for); the sweep is the estimate (the inner-penumbra one
// first, the preview) and half / double the classic k.
// A scene's distance grid, baked once, when first asked for.
class LazyGrid {
public:
    LazyGrid(const reference::Scene& scene, std::size_t nodes) : scene_(scene), nodes_(nodes) {}
    const DistanceGrid& get()
    {
        std::call_once(once_, [this] { grid_ = bake_distance_grid(scene_, nodes_); });
        return grid_;
    }

private:
    reference::Scene scene_;
    std::size_t nodes_;
    std::once_flag once_;
    DistanceGrid grid_;
};

// What the distance-field rows trace: the baked grid or the primitives.
enum class SdfSource { Grid, Analytic };

DemoMethod sdf_method(const reference::Scene& scene, int map_size, const SoftLight& light, SdfSource source)
{
    const bool analytic = source == SdfSource::Analytic;
    DemoMethod m{.name = analytic ? "sdf-analytic" : "sdf", .settings = {}, .preview_setting = kFirstSetting};
    const std::size_t nodes = map_size >= 1024 ? reference::kSdfGridNodes : reference::kSdfGridNodes / 8;
    // Baked on first use: listing the methods (to check --method, to count the
    // work) must not cost a bake per scene, seconds each.
    auto grid = analytic ? nullptr : std::make_shared<LazyGrid>(scene, nodes);
    auto primitives = std::make_shared<AnalyticScene>(reference::analytic_scene(scene.primitives));
    struct Variant {
        const char* label;
        SdfEstimate estimate;
        float k_scale;
    };
    for (Variant v : {Variant{"inner", SdfEstimate::InnerPenumbra, 1.0f}, Variant{"classic", SdfEstimate::Classic, 1.0f},
                      Variant{"improved", SdfEstimate::Improved, 1.0f},
                      Variant{"classic k/2", SdfEstimate::Classic, 0.5f},
                      Variant{"classic 2k", SdfEstimate::Classic, 2.0f}}) {
        m.settings.push_back({.label = v.label,
                              .prepare = nothing_prepared,
                              .shade = [grid, primitives, v, light](Context& ctx, const DemoFrame& f,
                                                                    const reference::Receivers& r,
                                                                    const DemoPrepared&) {
                                  SdfOptions o = sdf_options_for(light.apply(f.scene), v.estimate);
                                  o.k *= v.k_scale;
                                  return grid ? sdf_shadows(ctx, grid->get(), r.world_position, &r.normal, o)
                                              : sdf_shadows(ctx, *primitives, r.world_position, &r.normal, o);
                              }});
    }
    return m;
}

// The screen-space cross-bilateral blur of a deferred renderer, guided by
// the view depth (relative differences suit perspective depth), applied to
// the noisiest estimates: small VSM windows alias, and distance-field
// shadows band. The blur's cost is in the time; the chart shows what it buys.
BilateralOptions shadow_blur_options()
{
    BilateralOptions o;
    o.relative = true;
    o.depth_sigma = 0.02f;
    o.separable = true;
    return o;
}

// `source` at the settings numbered `blurred_settings`, each followed by the
// blur (ssao-vo's rows take the notes' own 5x5, ssao_blur_options).
DemoMethod blurred_method(DemoMethod source, const std::string& name, std::vector<int> blurred_settings,
                          BilateralOptions blur = shadow_blur_options())
{
    DemoMethod m{.name = name, .settings = {}, .preview_setting = kFirstSetting, .input = source.input,
                 .truth = source.truth};
    for (int index : blurred_settings) {
        DemoSetting inner = source.settings[std::size_t(index)];
        m.settings.push_back({.label = inner.label + " +blur",
                              .prepare = inner.prepare,
                              .shade = [inner, blur](Context& ctx, const DemoFrame& f, const reference::Receivers& rx,
                                                     const DemoPrepared& prepared) {
                                  return cross_bilateral(ctx, inner.shade(ctx, f, rx, prepared), rx.view_depth, blur);
                              }});
    }
    return m;
}

// ssao-vo (penumbra/ssao.h) on the view depth, one setting per rule for an
// unusable sample, its output o scored against the volumetric-obscurance
// truth of the same radius. The screen cap is off (1, the whole height) so
// that the kernel's ball is the truth's at every depth, as in docs/ssao.md's
// accuracy table; the notes' cap (0.07) would score the cap, not the rule.
DemoMethod ssao_method()
{
    struct Rule {
        const char* label;
        SsaoUnusable unusable;
    };
    DemoMethod m{.name = "ssao-vo", .settings = {}, .preview_setting = kFirstSetting, .truth = DemoTruth::Obscurance};
    for (Rule rule : {Rule{"paired", SsaoUnusable::Paired}, Rule{"zero", SsaoUnusable::Zero},
                      Rule{"half", SsaoUnusable::Half}, Rule{"renormalise", SsaoUnusable::Renormalise}}) {
        SsaoOptions o;
        o.unusable = rule.unusable;
        o.output = SsaoOutput::Obscurance;
        o.max_screen_radius = 1.0;
        m.settings.push_back({.label = rule.label,
                              .prepare = nothing_prepared,
                              .shade = [o](Context& ctx, const DemoFrame& f, const reference::Receivers& rx,
                                           const DemoPrepared&) {
                                  return ssao_obscurance(ctx, rx.view_depth, f.scene.view.fov_degrees, o);
                              }});
    }
    return m;
}

// The sun's cascaded mask (penumbra/cascades.h) at the library's defaults,
// the cascade chosen by box (Zhang 2009, the notes') or by split depth.
DemoMethod cascades_method()
{
    struct Selection {
        const char* label;
        CascadeSelection selection;
    };
    DemoMethod m{.name = "cascades", .settings = {}, .preview_setting = kFirstSetting, .truth = DemoTruth::Sun};
    const std::string k = "k=" + std::to_string(kDemoCascades) + " ";
    for (Selection sel : {Selection{"box", CascadeSelection::BoundingBox},
                          Selection{"split", CascadeSelection::SplitDepth}}) {
        CascadeOptions o;
        o.selection = sel.selection;
        m.settings.push_back({.label = k + sel.label,
                              .prepare = nothing_prepared,
                              .shade = [o](Context& ctx, const DemoFrame& f, const reference::Receivers& rx,
                                           const DemoPrepared&) {
                                  const Image mask = cascade_mask(ctx, f.sun->cascades, f.sun->cascade_receivers(rx), o);
                                  Image visibility(mask.width(), mask.height(), 1);  // channel 1 is the cascade used
                                  for (int y = 0; y < mask.height(); ++y)
                                      for (int x = 0; x < mask.width(); ++x) visibility.at(0, x, y) = mask.at(0, x, y);
                                  return visibility;
                              }});
    }
    return m;
}

// A shadow-map method's settings on the sun's single map of the cascades'
// texels (SunInputs::single_map_frame), its receivers in that map's frame.
DemoMethod single_map_method(const DemoMethod& source)
{
    DemoMethod m{.name = "single-" + source.name, .settings = {}, .preview_setting = source.preview_setting,
                 .input = source.input, .truth = DemoTruth::Sun};
    for (const DemoSetting& inner : source.settings)
        m.settings.push_back({.label = inner.label,
                              .prepare = [inner](Context& ctx, const DemoFrame& f) {
                                  return inner.prepare(ctx, *f.sun->single_map_frame);
                              },
                              .shade = [inner](Context& ctx, const DemoFrame& f, const reference::Receivers& rx,
                                               const DemoPrepared& prepared) {
                                  return inner.shade(ctx, *f.sun->single_map_frame,
                                                     f.sun->single_map_receivers(rx), prepared);
                              }});
    return m;
}

// Deep shadow maps, by the method table's `dsm` entry, on the frame's deep
// map: the bilinear (tent r = 0) lookup, the paper's texture-like filter,
// then one texel wider (tent r = 1) and the box of 3 x 3 pixels, at the
// lookup's default depth bias.
DemoMethod deep_method()
{
    struct Point {
        const char* label;
        DeepFilter filter;
        int radius;
    };
    std::vector<SweepPoint> sweep;
    for (Point point : {Point{"tent r=0", DeepFilter::Tent, 0}, Point{"tent r=1", DeepFilter::Tent, 1},
                        Point{"box r=1", DeepFilter::Box, 1}}) {
        MethodSettings s;
        s.deep_filter = point.filter;
        s.radius = point.radius;
        sweep.push_back({point.label, s});
    }
    return table_method("dsm", sweep, kFirstSetting);
}

// Pismo, by the method table's `pismo` and `pismo-maxdepth` entries, on the
// frame's maps (demo_pismo_maps). The kernel casts n x n rays per triangle,
// n = round(sqrt(rays x the triangle's share)): on the 32 triangles of a
// rectangle at level 2, 32 and 128 rays are 1 and 2 x 2 per triangle (a
// count between them rounds to one of the two). pismo sweeps both, the
// variant, which is there to show its failure, takes the first.
DemoMethod pismo_method(const char* name, const std::vector<int>& ray_counts)
{
    std::vector<SweepPoint> sweep;
    for (int rays : ray_counts) {
        MethodSettings s;
        s.rays = rays;
        sweep.push_back({std::to_string(rays) + " rays", s});
    }
    return table_method(name, sweep, kFirstSetting);
}

}  // namespace

const char* truth_name(DemoTruth truth)
{
    switch (truth) {
    case DemoTruth::Obscurance: return "obscurance";
    case DemoTruth::Sun: return "sun";
    default: return "shadow";
    }
}

int demo_cascade_size(int map_size) { return std::min(reference::CascadeSetup{}.map_size, map_size); }

std::shared_ptr<const SunInputs> render_sun_inputs(const reference::Scene& scene, int map_size,
                                                   const reference::Receivers& view)
{
    auto sun = std::make_shared<SunInputs>();
    reference::CascadeSetup setup;
    setup.count = kDemoCascades;
    setup.map_size = demo_cascade_size(map_size);
    sun->cascades = reference::render_cascades(scene, 0, view, setup);
    setup.count = 1;
    setup.map_size = int(std::lround(setup.map_size * std::sqrt(double(kDemoCascades))));
    CascadeShadows single = reference::render_cascades(scene, 0, view, setup);
    sun->single = single.cascades[0];
    sun->single_map_frame = std::make_shared<const DemoFrame>(
        DemoFrame{scene, std::move(single.maps), {}, Image(), nullptr, nullptr, nullptr, nullptr});
    sun->truth = reference::directional_truth(scene, 0, view);
    return sun;
}

const Image& SunInputs::cascade_receivers(const reference::Receivers& rx) const
{
    const std::lock_guard<std::mutex> lock(mutex_);
    auto found = cascade_rx_.find(&rx);
    if (found == cascade_rx_.end()) found = cascade_rx_.emplace(&rx, reference::cascade_receivers(rx)).first;
    return found->second;
}

// light_uvz in the single map's frame: u = dot(p, axis_u) u_scale + u_offset,
// v and z alike (penumbra/cascades.h).
const reference::Receivers& SunInputs::single_map_receivers(const reference::Receivers& rx) const
{
    const std::lock_guard<std::mutex> lock(mutex_);
    auto found = single_rx_.find(&rx);
    if (found != single_rx_.end()) return found->second;
    reference::Receivers out;
    out.light_uvz = Image(rx.width(), rx.height(), 3);
    const auto project = [&](const std::array<float, 3>& axis, float scale, float offset, int x, int y) {
        const double along = axis[0] * rx.world_position.at(0, x, y) + axis[1] * rx.world_position.at(1, x, y) +
                             axis[2] * rx.world_position.at(2, x, y);
        return float(along * scale + offset);
    };
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            out.light_uvz.at(0, x, y) = project(cascades.axis_u, single.u_scale, single.u_offset, x, y);
            out.light_uvz.at(1, x, y) = project(cascades.axis_v, single.v_scale, single.v_offset, x, y);
            out.light_uvz.at(2, x, y) = project(cascades.axis_z, single.z_scale, single.z_offset, x, y);
        }
    return single_rx_.emplace(&rx, std::move(out)).first->second;
}

int demo_deep_map_size(int map_size) { return std::clamp(map_size / 2, 1, 512); }

int demo_pismo_map_size(int map_size) { return std::clamp(map_size / 2, 64, 512); }

std::shared_ptr<const PismoMapSet> demo_pismo_maps(const reference::Scene& scene, int map_size,
                                                   const reference::Receivers& receivers)
{
    reference::LayeredMapOptions options;
    options.size = demo_pismo_map_size(map_size);
    const reference::Scene lit = soft_light_for(scene, map_size).apply(scene);
    return std::make_shared<const PismoMapSet>(reference::render_pismo_map_set(
        lit, kDemoPismoLevel, options, reference::receiver_region(receivers)));
}

Image run_setting(Context& context, const DemoSetting& setting, const DemoFrame& frame)
{
    return setting.shade(context, frame, frame.receivers, setting.prepare(context, frame));
}

std::vector<DemoMethod> demo_methods(const reference::Scene& scene, int map_size)
{
    // The soft methods' sizes come from the light they shade (SoftLight).
    const SoftLight light = soft_light_for(scene, map_size);
    const reference::Scene sized = light.apply(scene);
    DemoMethod sdf_grid = sdf_method(scene, map_size, light, SdfSource::Grid);
    const DemoMethod vsm = table_method("vsm", radius_sweep());
    const DemoMethod pcf_disc = table_method("pcf-disc", pcf_disc_sweep());
    const std::vector<int> vsm_small_radii = {0, 1}, sdf_inner = {0};  // blurred: the noisiest settings
    const std::vector<int> disc_few_taps = {0, 1};  // Toy Story 3's noisy PCF, then the cross-bilateral
    MethodSettings msm_soft_base;
    msm_soft_base.depth_bias = kDemoMsmDepthBias;
    msm_soft_base.plane_bias = kDemoMsmSoftPlaneBias;
    const DemoMethod pcf = table_method("pcf", pcf_sweep()), pcf_gauss = table_method("pcf-gauss", pcf_gauss_sweep());
    std::vector<DemoMethod> methods{vsm,
            blurred_method(vsm, "vsm+blur", vsm_small_radii),
            table_method("vssm", light_sweep(sized, map_size)),
            table_method("msm", radius_sweep(kDemoMsmDepthBias)),
            table_method("msm-soft", light_sweep(sized, map_size, msm_soft_base)),
            table_method("evsm2", radius_sweep()),
            table_method("evsm4", radius_sweep()),
            table_method("pcss", light_sweep(sized, map_size, pcf_settings())),
            table_method("burley", burley_sweep(sized, map_size)),
            sdf_grid,
            blurred_method(sdf_grid, "sdf+blur", sdf_inner),
            sdf_method(scene, map_size, light, SdfSource::Analytic),
            pcf,
            pcf_gauss,
            pcf_disc,
            blurred_method(pcf_disc, "pcf-disc+blur", disc_few_taps),
            deep_method(),
            pismo_method("pismo", {32, 128}),
            pismo_method("pismo-maxdepth", {32})};
    // ssao-vo's truth takes the primitives as solids: the opaque scenes only
    // (a fog box or a sheet of opacity 0.3 is no solid).
    const std::vector<std::string> opaque = reference::builtin_scene_names(reference::SceneSet::Opaque);
    if (std::find(opaque.begin(), opaque.end(), scene.name) != opaque.end()) {
        const DemoMethod ssao = ssao_method();
        methods.push_back(ssao);
        methods.push_back(blurred_method(ssao, "ssao-vo+blur", {0, 1, 2, 3}, ssao_blur_options()));
    }
    // The cascaded pipeline against one map of the same light (the sun),
    // shaded by the percentage-closer rows, where the scene has a sun.
    if (!scene.directional_lights.empty()) {
        methods.push_back(cascades_method());
        for (const DemoMethod* source : {&pcf, &pcf_gauss, &pcf_disc}) methods.push_back(single_map_method(*source));
    }
    return methods;
}

}  // namespace penumbra::cli
