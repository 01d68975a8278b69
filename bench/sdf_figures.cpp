// The measured figures of docs/sdf.md, not checks: error against the ground
// truth of the classic and improved estimates (contact and fence), the
// hardness fit, and lane utilisation of row strips against tiles. Tens of
// seconds each (the fence's truth takes 64^2 rays per receiver).
// usage: sdf_figures [error|hardness|lanes]...   (default: all three)
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "penumbra/reference.h"
#include "penumbra/reference/metrics.h"
#include "penumbra/reference/sdf_scene.h"
#include "penumbra/sdf.h"

using namespace penumbra;

namespace {

struct Case {
    const char* scene;
    int strata;  // docs/reference.md: truth RMSE below 1e-3 at 32 (contact), 80 (fence: 64 gives ~8e-4)
};

// docs/sdf.md, "Error against the ground truth": the classic and improved
// estimates on the analytic scene and the baked grid.
const char* name_of(SdfEstimate e) { return e == SdfEstimate::Classic ? "classic" : "improved"; }

void error_against_ground_truth()
{
    Context ctx;
    std::printf("view 320x240, valid receivers (mask); %s\n", ctx.description().c_str());
    std::printf("scene    source    estimate  RMSE     p99      leaking  over-dark  steps/ray\n");
    for (const Case c : {Case{"contact", 32}, Case{"fence", 64}}) {
        const reference::Scene scene = reference::builtin_scene(c.scene);
        const reference::Receivers r = reference::render_receivers(scene, 320, 240);
        const Image truth = reference::ground_truth(scene, r, {c.strata});
        const DistanceGrid grid = bake_distance_grid(scene);
        const AnalyticScene analytic = reference::analytic_scene(scene.primitives);
        for (const char* source : {"analytic", "grid"})
            for (SdfEstimate e : {SdfEstimate::Classic, SdfEstimate::Improved}) {
                Image out(320, 240, 2);
                const SdfOptions o = sdf_options_for(scene, e);
                if (std::string(source) == "grid") sdf_shadows(ctx, grid, r.world_position, &r.normal, o, out);
                else sdf_shadows(ctx, analytic, r.world_position, &r.normal, o, out);
                Image y(320, 240, 1);
                double steps = 0;
                for (int j = 0; j < 240; ++j)
                    for (int i = 0; i < 320; ++i) {
                        y.at(0, i, j) = out.at(0, i, j);
                        steps += out.at(1, i, j);
                    }
                std::printf("%-8s %-9s %-9s %.4f   %.4f   %.4f   %.4f     %.1f\n", c.scene, source, name_of(e),
                            reference::rmse(y, truth, &r.mask), reference::p99_abs_error(y, truth, &r.mask),
                            reference::light_leaking(y, truth, &r.mask), reference::over_darkening(y, truth, &r.mask), steps / (320 * 240));
            }
        std::printf("%s grid: %dx%dx%d nodes, voxel %.4f\n", c.scene, grid.nx(), grid.ny(), grid.nz(),
                    grid.voxel_size());
    }
}

// docs/sdf.md, "k from the light": RMSE for k = fit 2 D / W with D the reference distance (uniform) or each
// receiver's own (per receiver, light_width set), classic estimate, analytic.
void hardness_fit()
{
    Context ctx;
    std::printf("view 240x180, 24^2 rays per receiver; RMSE of the classic estimate, analytic scene\n");
    std::printf("scene    k             fit 1.0  fit 1.5  fit 2.0  fit 2.5  fit 3.0\n");
    for (const char* name : {"contact", "overlap", "grazing", "fence"}) {
        const reference::Scene scene = reference::builtin_scene(name);
        const reference::Receivers r = reference::render_receivers(scene, 240, 180);
        const Image truth = reference::ground_truth(scene, r, {24});
        const AnalyticScene analytic = reference::analytic_scene(scene.primitives);
        for (bool per_receiver : {false, true}) {
            std::printf("%-8s %-13s", name, per_receiver ? "per receiver" : "uniform");
            for (double fit : {1.0, 1.5, 2.0, 2.5, 3.0}) {
                SdfOptions o = sdf_options_for(scene);
                if (per_receiver) o.k = float(fit);
                else o.k = float(sdf_hardness(scene, fit)), o.light_width = 0.0f;
                std::printf("  %.4f", reference::rmse(sdf_shadows(ctx, analytic, r.world_position, &r.normal, o), truth, &r.mask));
            }
            std::printf("\n");
        }
    }
}

// docs/sdf.md, "Lane utilisation": active lane-steps / lane-steps for strips along rows (what the backends run)
// and for square-ish tiles of the same lane count, at 1920x1080.
void lane_utilisation_table()
{
    Context ctx;
    std::printf("1920x1080, classic estimate; utilisation = active lane-steps / lane-steps\n");
    std::printf("scene    source    steps/ray  16 rows  4x4 tiles  8 rows  4x2 tiles  4 rows  2x2 tiles\n");
    for (const char* name : {"contact", "fence"}) {
        const reference::Scene scene = reference::builtin_scene(name);
        const reference::Receivers r = reference::render_receivers(scene, 1920, 1080);
        const DistanceGrid grid = bake_distance_grid(scene);
        for (const char* source : {"analytic", "grid"}) {
            Image out(1920, 1080, 2);
            const SdfOptions o = sdf_options_for(scene);
            if (std::string(source) == "grid") sdf_shadows(ctx, grid, r.world_position, &r.normal, o, out);
            else sdf_shadows(ctx, reference::analytic_scene(scene.primitives), r.world_position, &r.normal, o, out);
            const double rays = 1920.0 * 1080.0;
            std::printf("%-8s %-9s %-9.1f  %.3f    %.3f      %.3f   %.3f      %.3f   %.3f\n", name, source,
                        lane_utilisation(out, 1, 1).active / rays, lane_utilisation(out, 1, 16).ratio(),
                        lane_utilisation(out, 1, 4, 4).ratio(), lane_utilisation(out, 1, 8).ratio(),
                        lane_utilisation(out, 1, 4, 2).ratio(), lane_utilisation(out, 1, 4).ratio(),
                        lane_utilisation(out, 1, 2, 2).ratio());
        }
    }
}

}  // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> tables(argv + 1, argv + argc);
    if (tables.empty()) tables = {"error", "hardness", "lanes"};
    for (const std::string& t : tables)
        if (t != "error" && t != "hardness" && t != "lanes") {
            std::fprintf(stderr, "usage: sdf_figures [error|hardness|lanes]...\n");
            return 2;
        }
    for (const std::string& t : tables) {
        if (t == "error") error_against_ground_truth();
        if (t == "hardness") hardness_fit();
        if (t == "lanes") lane_utilisation_table();
    }
    return 0;
}
