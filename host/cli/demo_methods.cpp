// The demo's method list. Settings sweep the parameter that trades time or
// blur for error: the window radius of VSM, the light size of VSSM (around the
// scene's own, from reference::light_size), the table precision.
#include "demo_methods.h"

#include <algorithm>
#include <cstdio>

#include "penumbra/chebyshev.h"
#include "penumbra/moment_table.h"
#include "penumbra/reference_light_space.h"

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
    // The float table on the same windows: precision loss on large maps.
    m.settings.push_back({"r=3 float", [](Context& ctx, const DemoFrame& f) {
                              const MomentTable table = build_moment_table(ctx, f.shadow_map, 2, Precision::Float);
                              return vsm(ctx, table, f.receivers.light_uvz, VsmOptions{3});
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

}  // namespace

std::vector<DemoMethod> demo_methods(const reference::Scene& scene, int map_size)
{
    return {vsm_method(), vssm_method(scene, map_size)};
}

}  // namespace penumbra::cli
