// Benchmarks of the percentage-closer family (kernels/pcf.h, pcf_gauss.h,
// pcf_disc.h) per backend and ISA, 1 and 2 threads (tbb::task_arena; OpenCL
// runs on PoCL's own threads), on penumbra_bench's inputs (bench_inputs.h: a
// size^2 map of occluders over a lit ground, one receiver per texel, 36% in
// shadow). The entries run through the generic lookup exactly as the
// operations call it (the output allocated once), with the constant bias:
//
//   pcf          box r = 2: 25 taps per receiver
//   pcf_gather   the same 25 gathers with no comparison (kernels/pcf.h's
//                pcf_gather): the gather limit pcf's taps/s is a share of
//   pcf_gauss    Toy Story 3's 4x4 grid: 25 texels (its 5x5 footprint)
//   pcf_disc     16 Vogel taps, radius 2.5 texels, rotated
//   pcf_op       pcf() itself: + the output allocation and the map's [0, 1] check
//
// Counters: taps/s (receivers x taps per receiver x iterations / s) and
// pixels/s. docs/pcf.md has the command and the figures.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <exception>
#include <string>
#include <vector>

#include "bench_inputs.h"
#include "host/backend/backend.h"
#include "penumbra/pcf.h"
#include "simd/cpu_kernels.h"

namespace penumbra::bench {
namespace {

using detail::KernelId;

struct PcfCase {
    const char* name;
    KernelId kernel;
    int taps;
};

const PcfCase kCases[] = {{"pcf", KernelId::pcf, 25},
                          {"pcf_gather", KernelId::pcf_gather, 25},
                          {"pcf_gauss", KernelId::pcf_gauss, 25},
                          {"pcf_disc", KernelId::pcf_disc, 16},
                          {"pcf_op", KernelId::pcf, 25}};

PcfParams params_for(const Image& map, const Image& rx, const Image& out)
{
    PcfParams p{};
    p.depth = detail::dims_of(map);
    p.receivers = detail::dims_of(rx);
    p.out = detail::dims_of(out);
    p.bias = PcfBias{PN_BIAS_CONSTANT, kPcfDefaultDepthBias, 1.0f, 0.0f, 0.02f};
    p.radius = 2;
    p.grid = 4;
    p.sigma = 1.0f;
    p.taps = 16;
    p.disc_radius = 2.5f;
    p.rotate = 1;
    return p;
}

void lookup(Context& ctx, const PcfCase& c, const Image& map, const Image& rx, const PcfParams& p, Image& out,
            std::vector<int>& bad_rows)
{
    if (std::string(c.name) == "pcf_op") {
        out = pcf(ctx, map, rx, PcfOptions{2, DepthBias{}});
        return;
    }
    detail::visit_lookup(c.kernel, &p, [&](auto k, const auto& params) {
        constexpr KernelId K = decltype(k)::value;
        detail::receiver_lookup<K>(ctx.impl(), map, rx, params, out, bad_rows.data());
    });
}

void run(benchmark::State& state, const std::string& backend, const PcfCase& c, int size, int threads)
{
    auto body = [&] {
        try {
            Context& ctx = context(backend);
            state.SetLabel(ctx.description());
            const Image& map = depth_map(size);
            const Image& rx = receivers(size);
            Image out(size, size, 1);
            std::vector<int> bad_rows(std::size_t(size), 0);
            const PcfParams p = params_for(map, rx, out);
            lookup(ctx, c, map, rx, p, out, bad_rows);  // untimed: PoCL's JIT, first touch
            for (auto _ : state) {
                lookup(ctx, c, map, rx, p, out, bad_rows);
                benchmark::DoNotOptimize(out.plane(0));
            }
            const double n = double(state.iterations()) * size * size;
            state.counters["pixels/s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
            state.counters["taps/s"] = benchmark::Counter(n * c.taps, benchmark::Counter::kIsRate);
        } catch (const std::exception& e) {
            state.SkipWithError(e.what());
        }
    };
    if (threads <= 0) return body();
    tbb::task_arena arena(threads);
    arena.execute(body);
}

// Registered at static initialisation, as BENCHMARK() does.
[[maybe_unused]] const bool registered = [] {
    for (const std::string& backend : testing::backend_names())
        for (const PcfCase& c : kCases)
            for (int threads : {1, 2}) {
                if (backend == "opencl" && threads == 2) continue;  // PoCL runs its own threads
                const int size = backend == "scalar" ? 1024 : 4096;
                const int arena = backend == "opencl" ? 0 : threads;
                std::string name = std::string(c.name) + "/backend:" + backend + "/size:" + std::to_string(size);
                if (arena) name += "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) {
                    run(s, backend, c, size, arena);
                })->UseRealTime()->Unit(benchmark::kMillisecond);
            }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
