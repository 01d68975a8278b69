// The cascaded shadow mask (kernels/cascades.h) per backend, 1 and 2
// threads, on one 1280 x 720 view frame: the contact scene's sun, three
// 640 x 640 cascades (the Toy Story 3 notes' setup; their budget: the shadow
// mask in 3 ms on an Xbox 360 GPU at 720p), by bounding-box or split-depth
// selection. cascade_mask() itself, into an output allocated once. The
// receivers and maps are rendered once, untimed (tests/support/cascade_cases.h).
// Counter: pixels/s. docs/cascades.md has the command and the figures.
#include <benchmark/benchmark.h>

#include <string>

#include "bench_inputs.h"
#include "penumbra/cascades.h"
#include "support/cascade_cases.h"
#include "timed_loop.h"

namespace penumbra::bench {
namespace {

constexpr int kWidth = 1280, kHeight = 720;

void run(benchmark::State& state, const std::string& backend, CascadeSelection selection, int threads)
{
    const testing::CascadeCase* c = nullptr;  // rendered on the first (untimed) call, inside timed_loop's try
    CascadeOptions o;
    o.selection = selection;
    Image out(kWidth, kHeight, 2);
    const bool ran = timed_loop(state, backend, threads, [&](Context& ctx) {
        if (!c) c = &testing::cascade_case("contact", 0, kWidth, kHeight);
        cascade_mask(ctx, c->shadows, c->rx, o, out);
        benchmark::DoNotOptimize(out.plane(0));
    });
    if (ran)
        state.counters["pixels/s"] =
            benchmark::Counter(double(state.iterations()) * kWidth * kHeight, benchmark::Counter::kIsRate);
}

[[maybe_unused]] const bool registered = [] {
    for (const std::string& backend : testing::backend_names())
        for (const auto& [label, selection] : {std::pair{"box", CascadeSelection::BoundingBox},
                                               std::pair{"split", CascadeSelection::SplitDepth}})
            for (int threads : {1, 2}) {
                if (backend == "opencl" && threads == 2) continue;  // PoCL runs its own threads
                const int arena = backend == "opencl" ? 0 : threads;
                std::string name = std::string("cascade_mask/backend:") + backend + "/select:" + label + "/frame:1280x720";
                if (arena) name += "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) {
                    run(s, backend, selection, arena);
                })->UseRealTime()->Unit(benchmark::kMillisecond);
            }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
