// The ground-truth subsystem's shadow-map render (reference/, a BVH over the
// scene's primitives, one ray per texel, TBB across the machine's threads):
// the `large` scene at 1024^2 and 4096^2, the sizes docs/reference.md quotes
// ("large: 4096x4096 shadow map in 1.17 s"). Counter: rays/s (one per texel).
// Run: build/bench/penumbra_bench --benchmark_filter=reference_shadow_map
#include <benchmark/benchmark.h>

#include <string>

#include "penumbra/reference.h"

namespace penumbra::bench {
namespace {

void shadow_map(benchmark::State& state, int size)
{
    const reference::Scene scene = reference::builtin_scene("large");
    for (auto _ : state) {
        Image map = reference::render_shadow_map(scene, size, size);
        benchmark::DoNotOptimize(map.plane(0));
    }
    state.counters["rays/s"] =
        benchmark::Counter(double(size) * size * double(state.iterations()), benchmark::Counter::kIsRate);
}

[[maybe_unused]] const bool registered = [] {
    for (int size : {1024, 4096}) {
        const std::string name = "reference_shadow_map/scene:large/size:" + std::to_string(size);
        benchmark::RegisterBenchmark(name.c_str(), [size](benchmark::State& s) { shadow_map(s, size); })
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
