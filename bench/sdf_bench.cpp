// Benchmarks of the SDF soft shadows (kernels/sdf.h): 1920x1080 receivers of
// the contact scene (its view camera, with normals), through the analytic
// primitives and through the scene's default grid (bake_distance_grid(scene):
// 8 Mi nodes, 16 mm voxels), with the demo's settings (sdf_options_for), per
// backend and ISA, 1 and 2 threads (tbb::task_arena; OpenCL runs on PoCL's own
// threads). Case names follow penumbra_bench's `op/key:value/.../threads:n`.
//
// Counters: rays/s (= pixels/s: one ray per receiver), steps/s (distance
// evaluations: the frame's total, counted once per case from the kernel's
// steps output, times iterations per second) and lane_utilisation (active
// lane-steps / lane-steps run, for the case's lane count: strips of lanes
// along rows, as simd/cpu_sdf.cpp runs them; 1 for scalar and OpenCL).
// docs/sdf.md has the command, the figures and the ratios.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <exception>
#include <map>
#include <string>
#include <vector>

#include "bench_inputs.h"
#include "penumbra/reference.h"
#include "penumbra/reference/sdf_scene.h"
#include "penumbra/sdf.h"
#include "simd/cpu_kernels.h"

namespace penumbra::bench {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;

struct SdfInputs {
    reference::Scene scene = reference::builtin_scene("contact");
    reference::Receivers receivers = reference::render_receivers(scene, kWidth, kHeight);
    AnalyticScene analytic = reference::analytic_scene(scene.primitives);
    DistanceGrid grid = bake_distance_grid(scene);
};

const SdfInputs& inputs()
{
    static const SdfInputs in;
    return in;
}

SdfEstimate estimate_of(const std::string& name)
{
    return name == "improved" ? SdfEstimate::Improved : SdfEstimate::Classic;
}

void shade(Context& ctx, const std::string& source, const SdfOptions& o, Image& out)
{
    const SdfInputs& in = inputs();
    if (source == "grid") sdf_shadows(ctx, in.grid, in.receivers.world_position, &in.receivers.normal, o, out);
    else sdf_shadows(ctx, in.analytic, in.receivers.world_position, &in.receivers.normal, o, out);
}

// Steps per frame and the step counts themselves, once per source and
// estimate (every backend takes the same steps; tests/kernels/sdf_test.cpp checks it).
const Image& steps(const std::string& source, const std::string& estimate)
{
    static std::map<std::string, Image> cache;
    Image& s = cache[source + "/" + estimate];
    if (s.empty()) {
        s = Image(kWidth, kHeight, 2);
        shade(context("scalar"), source, sdf_options_for(inputs().scene, estimate_of(estimate)), s);
    }
    return s;
}

template <class Fn>
void in_arena(int threads, Fn&& fn)
{
    if (threads <= 0) return fn();
    tbb::task_arena arena(threads);
    arena.execute(fn);
}

void run(benchmark::State& state, const std::string& backend, const std::string& source,
         const std::string& estimate, int threads)
{
    try {
        Context& ctx = context(backend);
        state.SetLabel(ctx.description());
        const SdfOptions o = sdf_options_for(inputs().scene, estimate_of(estimate));
        const Image& counted = steps(source, estimate);
        Image out(kWidth, kHeight, 1);
        in_arena(threads, [&] {
            shade(ctx, source, o, out);  // untimed: PoCL's JIT, first touch of the pages
            for (auto _ : state) {
                shade(ctx, source, o, out);
                benchmark::DoNotOptimize(out.plane(0));
                benchmark::ClobberMemory();
            }
        });
        const LaneUtilisation u = lane_utilisation(counted, 1, testing::backend_lanes(backend));
        const double n = double(state.iterations());
        state.counters["pixels/s"] = benchmark::Counter(double(kWidth) * kHeight * n, benchmark::Counter::kIsRate);
        state.counters["rays/s"] = benchmark::Counter(double(kWidth) * kHeight * n, benchmark::Counter::kIsRate);
        state.counters["steps/s"] = benchmark::Counter(u.active * n, benchmark::Counter::kIsRate);
        state.counters["lane_utilisation"] = u.ratio();
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}

// Registered at static initialisation, as BENCHMARK() does, with names built
// from the ISAs this CPU has. The classic estimate on every backend; the
// improved one on the ISA the library picks, for the cost of its extra sqrt.
[[maybe_unused]] const bool registered = [] {
    const std::string best = cpu::supported_isas().empty() ? "scalar" : std::string(cpu::supported_isas().back());
    for (const std::string& backend : testing::backend_names())
        for (const char* source : {"analytic", "grid"})
            for (const char* estimate : {"classic", "improved"})
                for (int threads : {1, 2}) {
                    if (std::string(estimate) == "improved" && backend != best) continue;
                    if (backend == "opencl" && threads == 2) continue;  // PoCL runs its own threads
                    const int arena = backend == "opencl" ? 0 : threads;
                    std::string name = "sdf/backend:" + backend + "/source:" + source + "/estimate:" + estimate +
                                       "/scene:contact/width:1920/height:1080";
                    if (arena) name += "/threads:" + std::to_string(threads);
                    benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) {
                        run(s, backend, source, estimate, arena);
                    })->UseRealTime()->Unit(benchmark::kMillisecond);
                }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
