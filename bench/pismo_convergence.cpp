// docs/pismo.md, "Convergence through the kernel": RMSE against the
// ray-traced truth as the light mesh is refined, Pismo beside the classical
// alternative at the same maps (the area-weighted average of the vertices'
// hard shadows), both shaded by the kernel (penumbra/pismo.h): the average is
// Pismo's kernel with one ray at each corner of each triangle, weighing a
// third of its share of the area, since a ray at a vertex is that vertex's
// hard shadow-map test (Pismo.ARayEndingAtALightVertexIsThatVertexsHardShadowTest).
// The truth's own noise is the RMSE between two truths of independent
// samples over sqrt(2).
//
// Usage: pismo_convergence [map size, 1024] [highest level, 3] [scene ...; contact overlap fence]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "host/src/pismo_rays.h"
#include "kernels/params.h"
#include "penumbra/context.h"
#include "penumbra/pismo.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/metrics.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "support/pismo_scenes.h"

namespace penumbra {
namespace {

// Three rays a triangle, at its corners, each weighing a third of its share.
detail::PismoRayTable vertex_rays(const PismoMaps& maps)
{
    double total = 0;
    for (const auto& t : maps.triangles()) total += detail::pismo_triangle_area(maps.vertices(), t);
    detail::PismoRayTable table;
    for (const auto& t : maps.triangles()) {
        const auto first = std::uint32_t(table.rays.size() / PN_PISMO_RAY_FLOATS);
        const float third = float(detail::pismo_triangle_area(maps.vertices(), t) / total / 3);
        table.rays.insert(table.rays.end(), {1, 0, 0, third, 0, 1, 0, third, 0, 0, 1, third});
        table.triangles.insert(table.triangles.end(), {std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2]),
                                                       first, first + 3});
    }
    return table;
}

double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void run(Context& ctx, const std::string& name, int size, int top)
{
    const reference::Scene scene = reference::builtin_scene(name);
    const reference::Receivers rx = reference::render_receivers(scene, 64, 48);
    reference::GroundTruthOptions go;
    go.strata = 16;
    const Image truth = reference::ground_truth(scene, rx, go);
    go.seed = 12345;
    const double noise = reference::rmse(reference::ground_truth(scene, rx, go), truth, &rx.mask) / std::sqrt(2.0);
    for (int level = 0; level <= top; ++level) {
        reference::LayeredMapOptions mo;
        mo.size = size;
        auto start = std::chrono::steady_clock::now();
        const PismoMaps maps = testing::library_maps(reference::render_pismo_maps(scene, level, mo));
        const double build = seconds_since(start);
        PismoOptions o;
        o.rays = 256;
        start = std::chrono::steady_clock::now();
        const Image pismo = pismo_shade(ctx, maps, rx.world_position, o);
        const double shade = seconds_since(start);
        Image averaged(rx.width(), rx.height(), 1);
        detail::pismo_shade_rays(ctx, maps, vertex_rays(maps), o.bias_texels, rx.world_position, averaged);
        std::printf("| %s | %d | %zu | %.4f | %.4f | %.4f | %.0f | %.1f | %.2f |\n", name.c_str(), level,
                    maps.vertices().size(), reference::rmse(pismo, truth, &rx.mask),
                    reference::rmse(averaged, truth, &rx.mask), noise, double(maps.bytes()) / (1 << 20), build,
                    shade);
        std::fflush(stdout);
    }
}

}  // namespace
}  // namespace penumbra

int main(int argc, char** argv)
{
    const int size = argc > 1 ? std::atoi(argv[1]) : 1024;
    const int top = argc > 2 ? std::atoi(argv[2]) : 3;
    std::vector<std::string> scenes;
    for (int i = 3; i < argc; ++i) scenes.push_back(argv[i]);
    if (scenes.empty()) scenes = {"contact", "overlap", "fence"};
    penumbra::Context ctx;
    std::printf("maps %d^2, 64 x 48 receivers, 256 rays, truth 16 x 16 strata, %s\n", size, ctx.description().c_str());
    std::printf("| scene | level | maps | Pismo | averaged hard shadows | truth's noise | maps MiB | build s | shade s |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string& name : scenes) penumbra::run(ctx, name, size, top);
}
