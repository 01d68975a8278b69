// Benchmarks of the method table's methods (host/src/methods.cpp,
// penumbra/methods.h): each method's two steps timed alone at 4096^2 per
// backend and ISA, 1 and 2 threads (tbb::task_arena), in the same run so that
// SIMD / scalar and SIMD / OpenCL are ratios of one run
// (bench/moments_ratios.py prints them; docs/moments.md has the command and
// the figures). A method added to the table is benchmarked here with no edit
// (one that reads a deep shadow map, MethodInput::DeepMap, in bench/dsm_bench.cpp).
//
// Cases, named as penumbra_bench's `op/key:value/.../threads:n`:
//  - the shade step (Method::shade into an output allocated once; the
//    prepared table built once, untimed, by the best CPU backend): op is the
//    method's name ('-' -> '_') with `_r8` for a box method (one that reads
//    `radius`; radius 8 like vsm_r8) and also `_r0`.. `_r2` on the exact
//    table and summed directly from the map (`precision:map`; the small
//    windows, issue 9: the method table's build step makes no table there,
//    docs/moment_table.md); a method with a light reads the default light
//    size, like vssm;
//  - the build step (Method::prepare) at radius 8: op `<name>_table`, once
//    per distinct build step (msm's, which makes no table at small radii,
//    and msm-soft's build the same table: msm_table, msm_soft_table).
// Storages, as `precision:`: exact (the default limb tables), 16bit (the
// opt-in optimized quantization, for a method that reads `quantize`) and
// float (the legacy float tables, quantization 32); `map` for a method that
// reads the shadow map itself (prepare_map: no table, no build case) and for
// a box method's small windows summed from the map (a case whose build step
// makes a table at that radius is skipped with a message).
// Methods of VSM's two-moment table (vsm, vssm) are bench/penumbra_bench.cpp's
// own cases (vsm_r0..r8, vssm, table: three sizes, beside memcpy and OpenCV)
// and are not registered again here.
//
// Inputs: bench/bench_inputs.h's scene (a lit ground under a grid of square
// occluders covering 36% of the map, receivers at every texel centre between
// them), so that the figures compare with vsm_r8 and vssm.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <exception>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "bench_inputs.h"
#include "timed_loop.h"
#include "penumbra/methods.h"

namespace penumbra::bench {
namespace {

constexpr int kSize = 4096;
constexpr int kRadius = 8;
const int kSmallRadii[] = {0, 1, 2};

struct Storage {
    const char* name;
    Quantization quantization;
    Precision precision;
};
const Storage kStorages[] = {{"exact", Quantization::None, Precision::Exact},
                             {"16bit", Quantization::Bits16, Precision::Exact},
                             {"float", Quantization::Bits32, Precision::Float}};
// A method that reads the shadow map itself (prepare_map) has no storage
// choice; a box method's small windows read it too (direct sums).
const Storage kMapItself{"map", Quantization::None, Precision::Exact};

bool reads(const Method& m, std::string_view option)
{
    return std::find(m.reads.begin(), m.reads.end(), option) != m.reads.end();
}

MethodSettings settings_for(const Storage& s, int radius)
{
    MethodSettings settings;
    settings.quantization = s.quantization;
    settings.precision = s.precision;
    settings.radius = radius;
    return settings;
}

// A method's prepared map, built once per build step and storage by the
// best CPU backend; every backend's shade step reads it. A table storage
// is built at radius 8 (a table whatever the radius of the shade step); the
// map storage of a box method at the case's own radius, and must then hold
// no table (throws otherwise: that radius is above the method's cut).
const PreparedMap& prepared(const Method& m, const Storage& s, const MethodSettings& settings)
{
    static std::map<std::tuple<const void*, std::string, int>, PreparedMap> cache;
    const bool direct = &s == &kMapItself;
    MethodSettings build = settings;
    if (!direct) build.radius = kRadius;
    const auto key = std::make_tuple(reinterpret_cast<const void*>(m.prepare), std::string(s.name), build.radius);
    auto it = cache.find(key);
    if (it == cache.end())
        it = cache.emplace(key, m.prepare(context(best_cpu_backend()), depth_map(kSize), build)).first;
    if (direct && it->second.has_table())
        throw std::runtime_error("the build step makes a table at radius " + std::to_string(build.radius) +
                                 " (above the method's direct-sum cut)");
    return it->second;
}

template <class Fn>
void timed(benchmark::State& state, const std::string& backend, int threads, Fn&& call)
{
    if (!timed_loop(state, backend, threads, call)) return;
    const double n = double(state.iterations());
    state.counters["pixels/s"] = benchmark::Counter(double(kSize) * kSize * n, benchmark::Counter::kIsRate);
}

void shade_step(benchmark::State& state, const Method& m, const MethodSettings& settings, const std::string& backend,
                const Storage& s, int threads)
{
    const Image& rx = receivers(kSize);
    Image out(kSize, kSize, 1);
    timed(state, backend, threads, [&](Context& ctx) {
        m.shade(ctx, prepared(m, s, settings), rx, settings, out);
        benchmark::DoNotOptimize(out.plane(0));
    });
}

void build_step(benchmark::State& state, const Method& m, const MethodSettings& settings, const std::string& backend,
                int threads)
{
    timed(state, backend, threads, [&](Context& ctx) {
        const PreparedMap p = m.prepare(ctx, depth_map(kSize), settings);
        benchmark::DoNotOptimize(&p);
    });
}

// The storages a method takes: 16-bit only where it reads `quantize`; the
// map for a box method's small windows.
std::vector<const Storage*> storages_of(const Method& m)
{
    if (m.prepare == prepare_map) return {&kMapItself};
    std::vector<const Storage*> list;
    for (const Storage& s : kStorages)
        if (s.quantization != Quantization::Bits16 || reads(m, "quantize")) list.push_back(&s);
    if (reads(m, "radius")) list.push_back(&kMapItself);
    return list;
}

// (op, radius) of a method's shade cases on storage `s`.
std::vector<std::pair<std::string, int>> shade_ops(const Method& m, const Storage& s)
{
    std::string name = m.name;
    std::replace(name.begin(), name.end(), '-', '_');
    if (!reads(m, "radius")) return {{name, kRadius}};
    std::vector<std::pair<std::string, int>> ops;
    if (s.quantization == Quantization::None)
        for (int r : kSmallRadii) ops.emplace_back(name + "_r" + std::to_string(r), r);
    if (&s != &kMapItself) ops.emplace_back(name + "_r" + std::to_string(kRadius), kRadius);
    return ops;
}

// Registers `run` on every backend: 1 and 2 threads on SIMD, scalar 1, OpenCL PoCL's own.
template <class Run>
void register_on_backends(const std::string& op, const Storage& s, Run run)
{
    for (const std::string& backend : testing::backend_names())
        for (int threads : {1, 2}) {
            if ((backend == "scalar" || backend == "opencl") && threads == 2) continue;
            const int arena = backend == "opencl" ? 0 : threads;
            std::string name = op + "/backend:" + backend + "/precision:" + s.name + "/size:" + std::to_string(kSize);
            if (arena) name += "/threads:" + std::to_string(threads);
            benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) { run(st, backend, arena); })
                ->UseRealTime()
                ->Unit(benchmark::kMillisecond);
        }
}

// Registered at static initialisation, as BENCHMARK() does, with names built
// from the method table and the backends of this machine.
[[maybe_unused]] const bool registered = [] {
    const Method& vsm = find_method("vsm");
    const Method& vssm = find_method("vssm");
    std::vector<const void*> timed_builds;
    for (const Method& m : methods()) {
        if (m.prepare == vsm.prepare || m.prepare == vssm.prepare) continue;  // bench/penumbra_bench.cpp's cases
        if (m.input != MethodInput::ShadowMap) continue;  // a deep map's lookups: bench/dsm_bench.cpp
        for (const Storage* s : storages_of(m))
            for (const auto& [op, radius] : shade_ops(m, *s)) {
                const MethodSettings settings = settings_for(*s, radius);
                register_on_backends(op, *s, [&m, settings, s](benchmark::State& st, const std::string& b, int t) {
                    shade_step(st, m, settings, b, *s, t);
                });
            }
        const void* build = reinterpret_cast<const void*>(m.prepare);
        if (m.prepare == prepare_map) continue;  // no table: nothing to time
        if (std::find(timed_builds.begin(), timed_builds.end(), build) != timed_builds.end()) continue;
        timed_builds.push_back(build);
        std::string op = std::string(m.name) + "_table";
        std::replace(op.begin(), op.end(), '-', '_');
        for (const Storage* s : storages_of(m)) {
            if (s == &kMapItself) continue;  // a box method's direct sums: no table to build
            const MethodSettings settings = settings_for(*s, kRadius);
            register_on_backends(op, *s, [&m, settings](benchmark::State& st, const std::string& b, int t) {
                build_step(st, m, settings, b, t);
            });
        }
    }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
