// Benchmarks of Pismo (penumbra/pismo.h, kernels/pismo.h): shadow rays per
// second over 320 x 240 receivers of the `contact` scene (world positions),
// 64 rays a point, on the light mesh at levels 0 and 1 (4 and 9 layered
// maps of 512^2), per backend: the SIMD ISAs on 1 and 2 threads
// (tbb::task_arena), OpenCL on PoCL's own threads, in one run so that every
// comparison is a ratio of the same run; and the time to build the maps
// (the tracer's layered maps, then PismoMaps: the bled copies, packed), on 2 threads.
// docs/pismo.md, "The kernel", has the command and the figures. The scalar
// binding is the oracle, not a schedule: it is left out.
//
// Case names: pismo/backend:B/level:L/size:512/threads:T, pismo_build/level:L/size:512;
// and the cost of surface ids (docs/pismo.md, "A surface id per layer"), level 1,
// 1 thread: pismo_planes:6/backend:B (normals) against pismo_planes:7/backend:B
// (normals and ids: the layer walk).
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <map>
#include <string>

#include "bench_inputs.h"
#include "host/src/pismo_rays.h"
#include "kernels/params.h"
#include "penumbra/pismo.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "support/backend_list.h"
#include "support/pismo_scenes.h"
#include "timed_loop.h"

namespace penumbra::bench {
namespace {

constexpr int kMapSize = 512, kWidth = 320, kHeight = 240, kRays = 64;

const reference::Scene& contact()
{
    static const reference::Scene scene = reference::builtin_scene("contact");
    return scene;
}

PismoMaps build(int level, bool surface_ids = false)
{
    reference::LayeredMapOptions o;
    o.size = kMapSize;
    return testing::library_maps(reference::render_pismo_maps(contact(), level, o), PismoDepths::Layered, surface_ids);
}

// Level `level`'s maps, with surface ids when planes is 7.
const PismoMaps& maps(int level, int planes = 3)
{
    static std::map<int, PismoMaps> made;
    const int key = 10 * level + planes;
    auto it = made.find(key);
    if (it == made.end()) it = made.emplace(key, build(level, planes == 7)).first;
    return it->second;
}

// World positions (3 planes), then normals (6), then surface ids (7).
const Image& receivers(int planes = 3)
{
    static const reference::Receivers rx = reference::render_receivers(contact(), kWidth, kHeight);
    static const Image three = rx.world_position, six = rx.positions_and_normals(),
                       seven = rx.positions_normals_and_surface();
    return planes == 7 ? seven : planes == 6 ? six : three;
}

// The rays the pattern casts per point (at least one per triangle, so a few more than kRays).
double rays_per_point(const PismoMaps& m)
{
    return double(detail::pismo_ray_table(m.vertices(), m.triangles(), kRays).rays.size() / PN_PISMO_RAY_FLOATS);
}

void shade(benchmark::State& state, const std::string& backend, int threads, int level, int planes = 3)
{
    const PismoMaps& m = maps(level, planes);
    const Image& rx = receivers(planes);
    Image out(kWidth, kHeight, 1);
    PismoOptions o;
    o.rays = kRays;
    if (!timed_loop(state, backend, threads, [&](Context& ctx) { pismo_shade(ctx, m, rx, o, out); })) return;
    state.counters["rays/s"] = benchmark::Counter(double(kWidth) * kHeight * rays_per_point(m) *
                                                      double(state.iterations()),
                                                  benchmark::Counter::kIsRate);
}

void build_maps(benchmark::State& state, int level)
{
    for (auto _ : state) benchmark::DoNotOptimize(build(level));
}

[[maybe_unused]] const bool registered = [] {
    for (int level : {0, 1}) {
        const std::string suffix = "/level:" + std::to_string(level) + "/size:" + std::to_string(kMapSize);
        for (const std::string& backend : testing::backend_names()) {
            if (backend == "scalar") continue;
            for (int threads : {1, 2}) {
                if (backend == "opencl" && threads == 2) continue;
                const int arena = backend == "opencl" ? 0 : threads;
                std::string name = "pismo/backend:" + backend + suffix;
                if (arena) name += "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) {
                    shade(st, backend, arena, level);
                })->UseRealTime()->Unit(benchmark::kMillisecond);
            }
        }
        benchmark::RegisterBenchmark(("pismo_build" + suffix).c_str(), [=](benchmark::State& st) {
            build_maps(st, level);
        })->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(1);
    }
    for (int planes : {6, 7})
        for (const std::string& backend : testing::backend_names()) {
            if (backend == "scalar") continue;
            const int arena = backend == "opencl" ? 0 : 1;
            const std::string name = "pismo_planes:" + std::to_string(planes) + "/backend:" + backend + "/level:1";
            benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) {
                shade(st, backend, arena, 1, planes);
            })->UseRealTime()->Unit(benchmark::kMillisecond);
        }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
