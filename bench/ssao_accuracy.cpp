// docs/ssao.md, "Accuracy": ssao-vo on every opaque built-in scene against
// both truths (reference/obscurance_truth.h), per unusable-sample rule, with
// and without the blur: RMSE and p99 of the AO term against the AO truth and
// of the obscurance against the volumetric-obscurance truth, the silhouette
// halo (the obscurance's signed mean error and RMSE in a band around depth
// edges), and the flicker of the AO term under a 1 cm camera move
// (reference::flicker against the truth's own change). Prints a table,
// asserts nothing.
//   ssao_accuracy [WIDTH HEIGHT [AO_STRATA VO_STRATA]]   (default 160 90 16 8)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/reference/metrics.h"
#include "penumbra/reference/obscurance_truth.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "penumbra/ssao.h"

namespace penumbra {
namespace {

constexpr double kRadius = 0.5;
constexpr int kBand = 4;               // pixels around a depth edge
constexpr double kEdgeJump = 0.1;      // a relative depth step that makes an edge

// Pixels that see a surface within kBand pixels of a depth edge (a neighbour
// seeing nothing, or a relative step above kEdgeJump).
Image edge_band(const Image& depth)
{
    const int w = depth.width(), h = depth.height();
    Image edge(w, h, 1), band(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x + 1 < w; ++x)
            for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
                if (y + dy >= h) continue;
                const float a = depth.at(0, x, y), b = depth.at(0, x + dx, y + dy);
                const bool jump = (a > 0) != (b > 0) || std::abs(a - b) > kEdgeJump * std::max(a, b);
                if (jump) edge.at(0, x, y) = edge.at(0, x + dx, y + dy) = 1;
            }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (depth.at(0, x, y) <= 0) continue;
            for (int j = std::max(0, y - kBand); j <= std::min(h - 1, y + kBand); ++j)
                for (int i = std::max(0, x - kBand); i <= std::min(w - 1, x + kBand); ++i)
                    if (edge.at(0, i, j) > 0) band.at(0, x, y) = 1;
        }
    return band;
}

double signed_mean(const Image& e, const Image& t, const Image& mask)
{
    double sum = 0;
    long n = 0;
    for (int y = 0; y < e.height(); ++y)
        for (int x = 0; x < e.width(); ++x)
            if (mask.at(0, x, y) > 0) sum += e.at(0, x, y) - t.at(0, x, y), ++n;
    return n ? sum / double(n) : 0.0;
}

const char* rule_name(SsaoUnusable u)
{
    switch (u) {
    case SsaoUnusable::Paired: return "paired";
    case SsaoUnusable::Zero: return "zero";
    case SsaoUnusable::Half: return "half";
    case SsaoUnusable::Renormalise: return "renormalise";
    }
    return "?";
}

struct Frame {
    reference::Receivers rx;
    Image ao_truth, vo_truth;
};

Frame frame(const reference::Scene& scene, int w, int h, int ao_strata, int vo_strata)
{
    Frame f{reference::render_receivers(scene, w, h), {}, {}};
    f.ao_truth = reference::ambient_occlusion_truth(scene, f.rx, {kRadius, ao_strata});
    f.vo_truth = reference::volumetric_obscurance_truth(scene, f.rx, {kRadius, vo_strata});
    return f;
}

Image run(Context& ctx, const Image& depth, double fov, SsaoUnusable rule, SsaoOutput output, bool blur)
{
    SsaoOptions o;
    o.radius = kRadius;
    o.max_screen_radius = 1.0;  // no cap: the sphere is the truths' (R = 0.5 at every depth)
    o.unusable = rule;
    o.output = output;
    return blur ? ssao_blurred(ctx, depth, fov, o) : ssao_obscurance(ctx, depth, fov, o);
}

}  // namespace
}  // namespace penumbra

int main(int argc, char** argv)
{
    using namespace penumbra;
    const int w = argc > 2 ? std::atoi(argv[1]) : 160, h = argc > 2 ? std::atoi(argv[2]) : 90;
    const int ao_strata = argc > 4 ? std::atoi(argv[3]) : 16, vo_strata = argc > 4 ? std::atoi(argv[4]) : 8;
    Context ctx;
    std::printf("ssao-vo against the truths: %dx%d view, R = %.2f, 3 pairs, no screen cap; truths %d^2 AO rays, "
                "%d^3 VO points; backend %s\n\n",
                w, h, kRadius, ao_strata, vo_strata, ctx.description().c_str());
    std::printf("| scene | rule | blur | AO RMSE | AO p99 | VO RMSE | VO p99 | halo VO mean | halo VO RMSE | AO flicker |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string& name : reference::builtin_scene_names()) {
        reference::Scene scene = reference::builtin_scene(name);
        const double fov = scene.view.fov_degrees;
        const Frame a = frame(scene, w, h, ao_strata, vo_strata);
        scene.view.position.x += 0.01;
        scene.view.target.x += 0.01;
        const Frame b = frame(scene, w, h, ao_strata, vo_strata);
        const Image band = edge_band(a.rx.view_depth);
        for (SsaoUnusable rule : {SsaoUnusable::Paired, SsaoUnusable::Zero, SsaoUnusable::Half,
                                  SsaoUnusable::Renormalise})
            for (bool blur : {false, true}) {
                const Image ao = run(ctx, a.rx.view_depth, fov, rule, SsaoOutput::Accessibility, blur);
                const Image vo = run(ctx, a.rx.view_depth, fov, rule, SsaoOutput::Obscurance, blur);
                const Image ao_b = run(ctx, b.rx.view_depth, fov, rule, SsaoOutput::Accessibility, blur);
                const double flicker = reference::flicker({ao, ao_b}, {a.ao_truth, b.ao_truth}, &a.rx.hit);
                std::printf("| %s | %s | %s | %.4f | %.4f | %.4f | %.4f | %+.4f | %.4f | %.4f |\n", name.c_str(),
                            rule_name(rule), blur ? "5x5" : "none", reference::rmse(ao, a.ao_truth, &a.rx.hit),
                            reference::p99_abs_error(ao, a.ao_truth, &a.rx.hit),
                            reference::rmse(vo, a.vo_truth, &a.rx.hit),
                            reference::p99_abs_error(vo, a.vo_truth, &a.rx.hit), signed_mean(vo, a.vo_truth, band),
                            reference::rmse(vo, a.vo_truth, &band), flicker);
            }
    }
    return 0;
}
