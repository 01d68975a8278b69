// Benchmarks of the deep shadow map lookup (penumbra/deep_lookup.h,
// kernels/dsm_lookup.h): lookups per second of 1920 x 1080 receivers of the
// `hair` scene on its 512^2 map as `penumbra dsm-build --scene hair --size 512
// --samples 16` makes it (default tolerance, box pixel filter), per backend,
// search (binary, linear), filter (box, tent) and radius (0, 1); the SIMD
// ISAs on 1 and 2 threads (tbb::task_arena), OpenCL on PoCL's own threads, in
// one run so that every comparison is a ratio of the same run
// (docs/deep_shadow_maps.md, "Lookup", has the command and the figures).
// The scalar binding is the oracle, not a schedule: it is left out.
//
// Case names as penumbra_bench's: dsm_lookup/backend:B/filter:F/search:S/radius:R/size:512/threads:T.
#include <benchmark/benchmark.h>

#include <string>

#include "bench_inputs.h"
#include "timed_loop.h"
#include "penumbra/deep_lookup.h"
#include "penumbra/reference/deep_map.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"

namespace penumbra::bench {
namespace {

constexpr int kMapSize = 512, kWidth = 1920, kHeight = 1080;

const reference::Scene& hair()
{
    static const reference::Scene scene = reference::builtin_scene("hair");
    return scene;
}

// dsm-build's map (its defaults but the size), made once, untimed.
const DeepShadowMap& hair_map()
{
    static const DeepShadowMap map = [] {
        reference::DeepMapOptions o;
        o.size = kMapSize;
        o.samples = 16;
        return reference::render_deep_shadow_map(hair(), o);
    }();
    return map;
}

const Image& hair_receivers()
{
    static const Image rx = reference::render_receivers(hair(), kWidth, kHeight).light_uvz;
    return rx;
}

void lookup(benchmark::State& state, const std::string& backend, int threads, const DeepLookupOptions& o)
{
    const DeepShadowMap& map = hair_map();
    const Image& rx = hair_receivers();
    Image out(kWidth, kHeight, 1);
    if (!timed_loop(state, backend, threads, [&](Context& ctx) { deep_lookup(ctx, map, rx, o, out); })) return;
    state.counters["lookups/s"] =
        benchmark::Counter(double(kWidth) * kHeight * double(state.iterations()), benchmark::Counter::kIsRate);
}

[[maybe_unused]] const bool registered = [] {
    for (const std::string& backend : testing::backend_names()) {
        if (backend == "scalar") continue;
        for (int threads : {1, 2}) {
            if (backend == "opencl" && threads == 2) continue;
            const int arena = backend == "opencl" ? 0 : threads;
            for (DeepFilter filter : {DeepFilter::Box, DeepFilter::Tent})
                for (DeepSearch search : {DeepSearch::Binary, DeepSearch::Linear})
                    for (int radius : {0, 1}) {
                        std::string name = "dsm_lookup/backend:" + backend + "/filter:" +
                                           (filter == DeepFilter::Box ? "box" : "tent") + "/search:" +
                                           (search == DeepSearch::Binary ? "binary" : "linear") +
                                           "/radius:" + std::to_string(radius) + "/size:" + std::to_string(kMapSize);
                        if (arena) name += "/threads:" + std::to_string(threads);
                        DeepLookupOptions o;
                        o.filter = filter;
                        o.search = search;
                        o.radius = radius;
                        benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) {
                            lookup(st, backend, arena, o);
                        })->UseRealTime()->Unit(benchmark::kMillisecond);
                    }
        }
    }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
