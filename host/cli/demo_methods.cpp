// The demo's method list. Settings sweep the parameter that trades time or
// blur for error: the window radius of VSM, the light size of VSSM (around the
// scene's own, from reference::light_size).
#include "demo_methods.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <mutex>

#include "penumbra/bilateral.h"
#include "penumbra/chebyshev.h"
#include "penumbra/moment_table.h"
#include "penumbra/moments.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/sdf_scene.h"
#include "penumbra/sdf.h"

namespace penumbra::cli {
namespace {

std::string format(const char* pattern, double value)
{
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

DemoMethod vsm_method()
{
    DemoMethod m{"vsm", {}, 1};
    for (int radius : {1, 3, 6})
        m.settings.push_back({"r=" + std::to_string(radius), [radius](Context& ctx, const DemoFrame& f) {
                                  const MomentTable table = build_moment_table(ctx, f.shadow_map);
                                  return vsm(ctx, table, f.receivers.light_uvz, VsmOptions{radius});
                              }});
    return m;
}

DemoMethod vssm_method(const reference::Scene& scene, int map_size)
{
    DemoMethod m{"vssm", {}, 1};
    const double physical = reference::light_size(scene);
    // The exact table keeps blocker searches up to 253 texels exact.
    const double largest = 252.0 / map_size;
    for (double scale : {0.5, 1.0, 2.0}) {
        const float light = float(std::min(physical * scale, largest));
        m.settings.push_back({format("L=%.3g", light), [light](Context& ctx, const DemoFrame& f) {
                                  const MomentTable table = build_moment_table(ctx, f.shadow_map);
                                  return vssm(ctx, table, f.receivers.light_uvz, VssmOptions{light});
                              }});
    }
    return m;
}

// Moment shadow maps on the exact limb table. The default depth bias leaves
// acne on sloped receivers; 3e-4 (about 20 16-bit depth steps) removes it on
// the reference scenes (docs/moments.md).
constexpr float kDemoMsmDepthBias = 3e-4f;

DemoMethod msm_method()
{
    DemoMethod m{"msm", {}, 1};
    for (int radius : {1, 3, 6})
        m.settings.push_back({"r=" + std::to_string(radius), [radius](Context& ctx, const DemoFrame& f) {
                                  const MsmTable table = build_msm_table(ctx, f.shadow_map);
                                  return msm(ctx, table, f.receivers.light_uvz, {radius, {}, kDemoMsmDepthBias});
                              }});
    return m;
}

DemoMethod msm_soft_method(const reference::Scene& scene, int map_size)
{
    DemoMethod m{"msm-soft", {}, 1};
    const double physical = reference::light_size(scene);
    const double largest = 252.0 / map_size;  // exact tables: searches up to 253 texels
    for (double scale : {0.5, 1.0, 2.0}) {
        const float light = float(std::min(physical * scale, largest));
        m.settings.push_back({format("L=%.3g", light), [light](Context& ctx, const DemoFrame& f) {
                                  const MsmTable table = build_msm_table(ctx, f.shadow_map);
                                  return msm_soft(ctx, table, f.receivers.light_uvz,
                                                  {light, {}, kDemoMsmDepthBias});
                              }});
    }
    return m;
}

// EVSM with the exact table's default exponents; the sweep is the radius and
// the warp count (EVSM2: positive warp only; EVSM4: both).
DemoMethod evsm_method(int channels)
{
    DemoMethod m{channels == 2 ? "evsm2" : "evsm4", {}, 1};
    for (int radius : {1, 3, 6})
        m.settings.push_back({"r=" + std::to_string(radius), [radius, channels](Context& ctx, const DemoFrame& f) {
                                  EvsmWarp warp;
                                  warp.channels = channels;
                                  const EvsmTable table = build_evsm_table(ctx, f.shadow_map, warp);
                                  EvsmOptions o;
                                  o.radius = radius;
                                  return evsm(ctx, table, f.receivers.light_uvz, o);
                              }});
    return m;
}

// Distance-field shadows trace the scene itself, not the shadow map: the
// grid is what an engine bakes offline, so it is baked once per scene (not
// timed) at a node budget that grows with the demo's map size; the analytic
// form evaluates the primitives in the kernel. k comes from the light's size
// (sdf_options_for); the sweep is the estimate and half / double that k.
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

DemoMethod sdf_method(const reference::Scene& scene, int map_size, bool analytic)
{
    DemoMethod m{analytic ? "sdf-analytic" : "sdf", {}, 0};
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
    for (Variant v : {Variant{"classic", SdfEstimate::Classic, 1.0f}, Variant{"improved", SdfEstimate::Improved, 1.0f},
                      Variant{"classic k/2", SdfEstimate::Classic, 0.5f},
                      Variant{"classic 2k", SdfEstimate::Classic, 2.0f}}) {
        m.settings.push_back({v.label, [grid, primitives, v](Context& ctx, const DemoFrame& f) {
                                  SdfOptions o = sdf_options_for(f.scene, v.estimate);
                                  o.k *= v.k_scale;
                                  const reference::Receivers& r = f.receivers;
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
Image blurred(Context& ctx, const DemoFrame& f, const Image& visibility)
{
    BilateralOptions o;
    o.relative = true;
    o.depth_sigma = 0.02f;
    o.separable = true;
    return cross_bilateral(ctx, visibility, f.receivers.view_depth, o);
}

DemoMethod blurred_method(DemoMethod source, const std::string& name, std::vector<int> keep)
{
    DemoMethod m{name, {}, 0};
    for (int index : keep) {
        DemoSetting inner = source.settings[std::size_t(index)];
        m.settings.push_back({inner.label + " +blur", [inner](Context& ctx, const DemoFrame& f) {
                                  return blurred(ctx, f, inner.run(ctx, f));
                              }});
    }
    return m;
}

}  // namespace

std::vector<DemoMethod> demo_methods(const reference::Scene& scene, int map_size)
{
    DemoMethod sdf_grid = sdf_method(scene, map_size, false);
    return {vsm_method(),
            blurred_method(vsm_method(), "vsm+blur", {0, 1}),
            vssm_method(scene, map_size),
            msm_method(),
            msm_soft_method(scene, map_size),
            evsm_method(2),
            evsm_method(4),
            sdf_grid,
            blurred_method(sdf_grid, "sdf+blur", {0}),
            sdf_method(scene, map_size, true)};
}

}  // namespace penumbra::cli
