// What each depth convention costs against normalised depth
// (kernels/depth_convention.h: the conversion in the kernels' load), on
// penumbra_bench's inputs (bench_inputs.h) rewritten in each convention
// (near 0.5, far 50), on the best CPU backend, one thread
// (`depth_convention/...`), and on OpenCL (`depth_convention_opencl/...`: the
// same calls on Context("opencl"), PoCL's own threads, each call's transfers
// of the host images included, the same for every convention):
//
//   table        the exact VSM table's build (one conversion per texel)
//   table_float  the float VSM table's build (one per texel)
//   table_msm16  MSM's 16-bit encoded table's build (one per texel)
//   vsm          VSM r = 2 on the exact table (one per receiver: its z)
//   vsm_direct   VSM r = 1 summed from the map (9 per receiver: each tap)
//   msm_direct   MSM r = 1 summed from the map (9 per receiver)
//   evsm_direct  EVSM4 r = 1 summed from the map (9 per receiver)
//   pcf          PCF r = 2 (the threshold: one per receiver)
//   pcss, burley their defaults (16 blocker + 24 filter taps, each converted)
//
// The operations as a user calls them (their map checks included), into
// outputs allocated once. docs/integration.md ("Depth conventions") has the
// command and the ratios.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <exception>
#include <map>
#include <string>

#include "bench_inputs.h"
#include "penumbra/chebyshev.h"
#include "penumbra/moments.h"
#include "penumbra/pcf.h"
#include "penumbra/soft_pcf.h"
#include "support/depth_conventions.h"

namespace penumbra::bench {
namespace {

constexpr int kSize = 2048;

struct Inputs {
    Image map, receivers;
    MomentTable table, float_table;
};

// The inputs in convention `kind`, made once (untimed).
Inputs& inputs(DepthConventionKind kind)
{
    static std::map<DepthConventionKind, Inputs> cache;
    auto found = cache.find(kind);
    if (found != cache.end()) return found->second;
    const DepthConvention c = testing::convention_of(kind);
    Inputs in{testing::in_convention(depth_map(kSize), 0, c), testing::in_convention(receivers(kSize), 2, c), {}, {}};
    in.table = MomentTable(kSize, kSize, 2, Precision::Exact, kVsmLimbs, TableValues{0, 0.0f, 0.0f, c});
    in.float_table = MomentTable(kSize, kSize, 2, Precision::Float, kVsmLimbs, TableValues{0, 0.0f, 0.0f, c});
    return cache.emplace(kind, std::move(in)).first->second;
}

using Step = void (*)(Context&, Inputs&, const DepthConvention&, Image&);

void table_step(Context& ctx, Inputs& in, const DepthConvention&, Image&)
{
    build_moment_table(ctx, in.map, in.table);
}

void table_float_step(Context& ctx, Inputs& in, const DepthConvention&, Image&)
{
    build_moment_table(ctx, in.map, in.float_table);
}

// Allocates its table per call, as the library's only form does: the same
// for every convention.
void table_msm16_step(Context& ctx, Inputs& in, const DepthConvention& c, Image&)
{
    benchmark::DoNotOptimize(build_msm_table(ctx, in.map, Quantization::Bits16, Precision::Exact, c));
}

void vsm_step(Context& ctx, Inputs& in, const DepthConvention& c, Image& out)
{
    VsmOptions o;
    o.radius = 2;
    o.depth_convention = c;
    vsm(ctx, in.table, in.receivers, o, out);
}

void vsm_direct_step(Context& ctx, Inputs& in, const DepthConvention& c, Image& out)
{
    VsmOptions o;
    o.radius = 1;
    o.depth_convention = c;
    vsm(ctx, in.map, in.receivers, o, out);
}

void msm_direct_step(Context& ctx, Inputs& in, const DepthConvention& c, Image& out)
{
    MsmOptions o;
    o.radius = 1;
    o.depth_convention = c;
    msm(ctx, in.map, in.receivers, o, out);
}

void evsm_direct_step(Context& ctx, Inputs& in, const DepthConvention& c, Image& out)
{
    EvsmOptions o;
    o.radius = 1;
    o.depth_convention = c;
    evsm(ctx, in.map, EvsmWarp{}, in.receivers, o, out);
}

void pcf_step(Context& ctx, Inputs& in, const DepthConvention& c, Image& out)
{
    PcfOptions o;
    o.radius = 2;
    o.depth_convention = c;
    pcf(ctx, in.map, in.receivers, o, out);
}

void pcss_step(Context& ctx, Inputs& in, const DepthConvention& c, Image& out)
{
    PcssOptions o;
    o.depth_convention = c;
    pcss(ctx, in.map, in.receivers, o, out);
}

void burley_step(Context& ctx, Inputs& in, const DepthConvention& c, Image& out)
{
    BurleyOptions o;
    o.depth_convention = c;
    burley(ctx, in.map, in.receivers, o, out);
}

struct Case {
    const char* name;
    Step step;
};
const Case kCases[] = {{"table", table_step},           {"table_float", table_float_step},
                       {"table_msm16", table_msm16_step}, {"vsm", vsm_step},
                       {"vsm_direct", vsm_direct_step},   {"msm_direct", msm_direct_step},
                       {"evsm_direct", evsm_direct_step}, {"pcf", pcf_step},
                       {"pcss", pcss_step},               {"burley", burley_step}};

void run(benchmark::State& state, bool opencl, const Case& c, DepthConventionKind kind)
{
    tbb::task_arena arena(1);
    arena.execute([&] {
        try {
            Context& ctx = context(opencl ? std::string("opencl") : best_cpu_backend());
            state.SetLabel(ctx.description());
            Inputs& in = inputs(kind);
            const DepthConvention convention = testing::convention_of(kind);
            Image out(kSize, kSize, 1);
            table_step(ctx, in, convention, out);  // untimed: the lookups' table, first touch
            c.step(ctx, in, convention, out);
            for (auto _ : state) {
                c.step(ctx, in, convention, out);
                benchmark::DoNotOptimize(out.plane(0));
            }
            state.counters["pixels/s"] =
                benchmark::Counter(double(state.iterations()) * kSize * kSize, benchmark::Counter::kIsRate);
        } catch (const std::exception& e) {
            state.SkipWithError(e.what());
        }
    });
}

[[maybe_unused]] const bool registered = [] {
    for (const bool opencl : {false, true})
        for (const Case& c : kCases)
            for (DepthConventionKind kind : testing::kAllConventions) {
                const std::string name = std::string(opencl ? "depth_convention_opencl/" : "depth_convention/") +
                                         c.name + "/convention:" + to_string(kind) + "/size:" + std::to_string(kSize);
                benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) { run(s, opencl, c, kind); })
                    ->UseRealTime()
                    ->Unit(benchmark::kMillisecond);
            }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
