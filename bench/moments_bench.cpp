// Benchmarks of the moment family (kernels/msm.h, msm_soft.h, evsm.h,
// encoded_table.h): reconstruction throughput at 4096^2 receivers per backend
// and ISA, 1 and 2 threads (tbb::task_arena), and the tables' builds, in the
// same run so that SIMD / scalar and SIMD / OpenCL are ratios of one run
// (bench/moments_ratios.py prints them; docs/moments.md has the command and
// the figures). Case names follow penumbra_bench's `op/key:value/.../threads:n`.
//
// Inputs: bench/bench_inputs.h's scene (a lit ground under a grid of square
// occluders covering 36% of the map, receivers at every texel centre between
// them), so that the figures compare with vsm_r<n> and vssm. Box methods take
// the radius from the name's last digit (msm_r8, evsm4_r2); msm_soft the
// default light size, like vssm.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <exception>
#include <map>
#include <string>
#include <vector>

#include "bench_inputs.h"
#include "penumbra/moments.h"

namespace penumbra::bench {
namespace {

constexpr int kSize = 4096;

// The storages: exact limb tables (the default), MSM's opt-in 16-bit
// optimized quantization (EVSM has none: its 16-bit tables cannot keep the
// method's tolerance) and the legacy float tables.
struct Storage {
    const char* name;
    Quantization quantization;
    Precision precision;
};
const Storage kStorages[] = {{"exact", Quantization::None, Precision::Exact},
                             {"16bit", Quantization::Bits16, Precision::Exact},
                             {"float", Quantization::Bits32, Precision::Float}};

// Tables built once with the SIMD backend; every backend's lookups read them.
const MsmTable& msm_table(const Storage& s)
{
    static std::map<std::string, MsmTable> cache;
    auto it = cache.find(s.name);
    if (it == cache.end())
        it = cache.emplace(s.name, build_msm_table(context("avx2"), depth_map(kSize), s.quantization, s.precision))
                 .first;
    return it->second;
}

const EvsmTable& evsm_table(const Storage& s, int channels)
{
    static std::map<std::string, EvsmTable> cache;
    const std::string key = std::string(s.name) + std::to_string(channels);
    auto it = cache.find(key);
    if (it == cache.end()) {
        EvsmWarp warp;
        warp.channels = channels;
        warp.quantization = s.quantization;
        it = cache.emplace(key, build_evsm_table(context("avx2"), depth_map(kSize), warp, s.precision)).first;
    }
    return it->second;
}

template <class Fn>
void timed(benchmark::State& state, const std::string& backend, int threads, Fn&& call)
{
    try {
        Context& ctx = context(backend);
        state.SetLabel(ctx.description());
        auto loop = [&] {
            call(ctx);  // untimed: PoCL's first launch, page faults
            for (auto _ : state) {
                call(ctx);
                benchmark::ClobberMemory();
            }
        };
        if (threads > 0) tbb::task_arena(threads).execute(loop);
        else loop();
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
        return;
    }
    const double n = double(state.iterations());
    state.counters["pixels/s"] = benchmark::Counter(double(kSize) * kSize * n, benchmark::Counter::kIsRate);
}

void lookup(benchmark::State& state, const std::string& op, const std::string& backend, const Storage& s,
            int threads)
{
    const Image& rx = receivers(kSize);
    Image out(kSize, kSize, 1);
    timed(state, backend, threads, [&](Context& ctx) {
        if (op.compare(0, 5, "msm_r") == 0) msm(ctx, msm_table(s), rx, MsmOptions{op[5] - '0', {}, {}}, out);
        else if (op == "msm_soft") msm_soft(ctx, msm_table(s), rx, MsmSoftOptions{}, out);
        else evsm(ctx, evsm_table(s, op[4] - '0'), rx, EvsmOptions{op[7] - '0'}, out);  // evsm<channels>_r<radius>
        benchmark::DoNotOptimize(out.plane(0));
    });
}

void table(benchmark::State& state, const std::string& op, const std::string& backend, const Storage& s,
           int threads)
{
    timed(state, backend, threads, [&](Context& ctx) {
        if (op == "msm_table") {
            MsmTable t = build_msm_table(ctx, depth_map(kSize), s.quantization, s.precision);
            benchmark::DoNotOptimize(t.sums.storage());
        } else {
            EvsmTable t = build_evsm_table(ctx, depth_map(kSize), EvsmWarp{4, {}, {}, s.quantization}, s.precision);
            benchmark::DoNotOptimize(t.sums.storage());
        }
    });
}

// Registered at static initialisation, as BENCHMARK() does, with names built
// from the ISAs this CPU has. Scalar runs 1 thread, OpenCL PoCL's own.
[[maybe_unused]] const bool registered = [] {
    // msm_r0 .. msm_r2, evsm4_r0 .. evsm4_r2: the small windows (issue 9: no
    // slower than before it), exact storage only.
    for (const char* op : {"msm_r0", "msm_r1", "msm_r2", "msm_r8", "msm_soft", "evsm2_r8", "evsm4_r0", "evsm4_r1",
                           "evsm4_r2", "evsm4_r8", "msm_table", "evsm4_table"})
        for (const Storage& s : kStorages)
            for (const std::string& backend : testing::backend_names())
                for (int threads : {1, 2}) {
                    // EVSM has no 16-bit storage any more (see kStorages).
                    if (s.quantization == Quantization::Bits16 && std::string(op).find("evsm") == 0) continue;
                    if ((backend == "scalar" || backend == "opencl") && threads == 2) continue;
                    const std::string name_op = op;
                    const bool small = (name_op.compare(0, 5, "msm_r") == 0 || name_op.compare(0, 7, "evsm4_r") == 0) &&
                                       name_op.back() != '8';
                    if (small && std::string(s.name) != "exact") continue;
                    const int arena = backend == "opencl" ? 0 : threads;
                    std::string name = std::string(op) + "/backend:" + backend + "/precision:" + s.name +
                                       "/size:" + std::to_string(kSize);
                    if (arena) name += "/threads:" + std::to_string(threads);
                    const bool is_table = std::string(op).find("_table") != std::string::npos;
                    benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) {
                        if (is_table) table(st, op, backend, s, arena);
                        else lookup(st, op, backend, s, arena);
                    })->UseRealTime()->Unit(benchmark::kMillisecond);
                }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
