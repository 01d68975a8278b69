// Benchmarks of the ssao-vo pipeline at 1280x720 (the notes' 720p): the
// obscurance step (kernels/ssao_vo.h, 3 pairs, paired samples, the 4x4
// rotations) and the blur that follows it (5x5 cross-bilateral, threshold on
// the relative depth difference, 1 channel), per backend and ISA, 1 and 2
// threads. The view depth is the contact scene's, rendered once. The notes'
// own budget (Xbox 360 GPU, 720p): shadow mask 3 ms, blur 2 ms;
// docs/ssao.md has the command and the figures beside it.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include "bench_inputs.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "penumbra/ssao.h"
#include "timed_loop.h"

namespace penumbra::bench {
namespace {

constexpr int kWidth = 1280, kHeight = 720;

const reference::Scene& scene()
{
    static const reference::Scene s = reference::builtin_scene("contact");
    return s;
}

const Image& view_depth()
{
    static const Image depth = reference::render_receivers(scene(), kWidth, kHeight).view_depth;
    return depth;
}

void set_rates(benchmark::State& state)
{
    const double pixels = double(kWidth) * kHeight * double(state.iterations());
    state.counters["pixels/s"] = benchmark::Counter(pixels, benchmark::Counter::kIsRate);
    state.counters["bytes/s"] = benchmark::Counter(pixels * 8.0, benchmark::Counter::kIsRate);  // read depth, write 1
}

// step: "obscurance" (ssao_obscurance) or "blur" (cross_bilateral of its output).
void run(benchmark::State& state, const std::string& backend, const std::string& step, int threads)
{
    const SsaoOptions options;
    const BilateralOptions blur = ssao_blur_options();
    Image ao(kWidth, kHeight, 1), blurred(kWidth, kHeight, 1);
    bool have_ao = false;  // the blur's input, made on the first (untimed) call
    const bool ran = timed_loop(state, backend, threads, [&](Context& ctx) {
        const Image& depth = view_depth();
        const double fov = scene().view.fov_degrees;
        if (step == "obscurance" || !have_ao) ssao_obscurance(ctx, depth, fov, options, ao);
        have_ao = true;
        if (step == "blur") cross_bilateral(ctx, ao, depth, blur, blurred);
        benchmark::DoNotOptimize(ao.plane(0));
        benchmark::DoNotOptimize(blurred.plane(0));
    });
    if (ran) set_rates(state);
}

double fastest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }

[[maybe_unused]] const bool registered = [] {
    for (const std::string& backend : testing::backend_names())
        for (const char* step : {"obscurance", "blur"})
            for (int threads : {1, 2}) {
                if (backend == "opencl" && threads == 2) continue;  // PoCL runs its own threads
                const int arena = backend == "opencl" ? 0 : threads;
                std::string name = std::string("ssao_vo/backend:") + backend + "/step:" + step +
                                   "/width:1280/height:720/pairs:3";
                if (arena) name += "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) { run(s, backend, step, arena); })
                    ->UseRealTime()
                    ->Unit(benchmark::kMillisecond)
                    ->ComputeStatistics("min", fastest);
            }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
