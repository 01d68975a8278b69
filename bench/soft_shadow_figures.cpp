// The soft members' figures of docs/soft_pcf.md (not tests: they print tables
// and assert nothing).
//  contact  the contact-hardening figure: RMSE against ray-traced ground truth
//           within a band of 5 shadow-map texels around the contacts of the
//           `contact` scene (the sphere on the ground, the capsule's foot on
//           the ground, the capsule on the sphere), for pcf, pcss, burley,
//           vssm and msm-soft at the scene's light size; also over all valid
//           receivers.
//  depth    acne and leaks against the shadow map's depth mode (first,
//           midpoint, second; Woo 1992): over-darkening, leaking and RMSE
//           per scene, method and mode.
// Methods come from the library's method table (penumbra/methods.h); a name
// missing from this build is listed as such. The backend is the context's
// default (Auto).
// usage: soft_shadow_figures contact|depth [view WxH = 480x360] [truth samples = 256]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "penumbra/methods.h"
#include "penumbra/reference.h"
#include "contact_band.h"

namespace ref = penumbra::reference;
using penumbra::Image;
using penumbra::bench::contact_band;

namespace {

// The methods of the figures, each at the setting that matches the scene's
// light (burley: the widest radius = light_size, docs/soft_pcf.md).
struct Entry {
    const char* name;
    std::vector<std::pair<std::string, std::string>> options;
};

// Burley's cone with its slope in world units (penumbra::world_cone) from
// the scene's light, as the options that carry it.
std::vector<std::pair<std::string, std::string>> world_cone_options(const ref::Scene& scene, const std::string& light,
                                                                    float world_slope)
{
    const penumbra::BurleyOptions cone = penumbra::world_cone({}, world_slope, ref::light_frustum(scene));
    return {{"max-radius", light},
            {"bias-slope", std::to_string(cone.bias_slope)},
            {"bias-slope-per-depth", std::to_string(cone.bias_slope_per_depth)}};
}

std::vector<Entry> entries(const ref::Scene& scene)
{
    const std::string light = std::to_string(ref::light_size(scene));
    return {{"pcf", {{"radius", "2"}}},
            {"pcss", {{"light-size", light}}},
            {"burley", {{"max-radius", light}}},
            {"burley", world_cone_options(scene, light, 2.0f)},
            {"burley", world_cone_options(scene, light, 1.0f)},
            {"burley", {{"max-radius", light}, {"bias-slope", "0.5"}}},
            {"burley", {{"max-radius", light}, {"bias-slope", "0"}, {"depth-bias", "5e-4"}}},
            {"vssm", {{"light-size", light}}},
            {"msm-soft", {{"light-size", light}, {"depth-bias", "3e-4"}}}};
}

const penumbra::Method* method_or_null(const char* name)
{
    for (const penumbra::Method& m : penumbra::methods())
        if (std::string(m.name) == name) return &m;
    return nullptr;
}

std::string setting_of(const Entry& e)
{
    std::string setting;
    for (const auto& [k, v] : e.options) setting += k + "=" + v + " ";
    return setting;
}

int count(const Image& mask)
{
    int n = 0;
    for (int y = 0; y < mask.height(); ++y)
        for (int x = 0; x < mask.width(); ++x) n += mask.at(0, x, y) > 0.5f;
    return n;
}

bool available(const Entry& e) { return method_or_null(e.name) != nullptr; }

Image shade(penumbra::Context& context, const Entry& e, const Image& map, const ref::Receivers& rx)
{
    const penumbra::Method* m = method_or_null(e.name);
    return m->run(context, map, rx.light_uvz, penumbra::parse_method_settings(*m, e.options));
}

void contact_figure(int view_w, int view_h, int samples)
{
    penumbra::Context context;
    const ref::Scene scene = ref::builtin_scene("contact");
    const int map_size = scene.map_size;
    const Image map = ref::render_shadow_map(scene, map_size, map_size);
    const ref::Receivers rx = ref::render_receivers(scene, view_w, view_h);
    const Image truth = ref::ground_truth(scene, rx, {int(std::lround(std::sqrt(samples)))});
    const Image band = contact_band(scene, rx, map_size, 5.0);
    double band_truth = 0;
    for (int y = 0; y < band.height(); ++y)
        for (int x = 0; x < band.width(); ++x) band_truth += band.at(0, x, y) * truth.at(0, x, y);
    std::printf("contact, %d^2 map, %dx%d receivers, truth %d rays; band: %d receivers within 5 texels of a contact, "
                "mean truth %.3f\n",
                map_size, view_w, view_h, samples, count(band), band_truth / std::max(1, count(band)));
    std::printf("| method | setting | RMSE in band | RMSE all | leak all | over-darkening all |\n|---|---|---|---|---|---|\n");
    for (const Entry& e : entries(scene)) {
        if (!available(e)) {
            std::printf("| %s | not in this build | | | | |\n", e.name);
            continue;
        }
        const Image estimate = shade(context, e, map, rx);
        std::printf("| %s | %s| %.4f | %.4f | %.4f | %.4f |\n", e.name,
                    setting_of(e).c_str(), ref::rmse(estimate, truth, &band), ref::rmse(estimate, truth, &rx.mask),
                    ref::light_leaking(estimate, truth, &rx.mask), ref::over_darkening(estimate, truth, &rx.mask));
    }
}

void depth_figure(int view_w, int view_h, int samples)
{
    penumbra::Context context;
    for (const char* name : {"contact", "grazing", "overlap"}) {
        const ref::Scene scene = ref::builtin_scene(name);
        const ref::Receivers rx = ref::render_receivers(scene, view_w, view_h);
        const Image truth = ref::ground_truth(scene, rx, {int(std::lround(std::sqrt(samples)))});
        std::printf("\n%s, %d^2 map, %dx%d receivers, truth %d rays\n", name, scene.map_size, view_w, view_h, samples);
        std::printf("| method | setting | depth | over-darkening | leak | RMSE |\n|---|---|---|---|---|---|\n");
        for (const ref::ShadowDepth depth : {ref::ShadowDepth::First, ref::ShadowDepth::Midpoint, ref::ShadowDepth::Second}) {
            const Image map = ref::render_shadow_map(scene, scene.map_size, scene.map_size, depth);
            for (const Entry& e : entries(scene)) {
                if (!available(e)) continue;
                const Image estimate = shade(context, e, map, rx);
                std::printf("| %s | %s| %s | %.4f | %.4f | %.4f |\n", e.name, setting_of(e).c_str(),
                            ref::shadow_depth_name(depth),
                            ref::over_darkening(estimate, truth, &rx.mask), ref::light_leaking(estimate, truth, &rx.mask),
                            ref::rmse(estimate, truth, &rx.mask));
            }
        }
    }
}

}  // namespace

int main(int argc, char** argv)
{
    const std::string figure = argc > 1 ? argv[1] : "";
    int view_w = 480, view_h = 360, samples = 256;
    if (argc > 2 && std::sscanf(argv[2], "%dx%d", &view_w, &view_h) != 2) view_w = 0;
    if (argc > 3) samples = std::atoi(argv[3]);
    if ((figure != "contact" && figure != "depth") || view_w < 1 || view_h < 1 || view_w > 4096 || view_h > 4096 ||
        samples < 1 || samples > 65536) {
        std::fprintf(stderr, "usage: soft_shadow_figures contact|depth [WxH in 1..4096] [truth samples in 1..65536]\n");
        return 2;
    }
    if (figure == "contact") contact_figure(view_w, view_h, samples);
    else depth_figure(view_w, view_h, samples);
    return 0;
}
