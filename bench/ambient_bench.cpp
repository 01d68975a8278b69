// Benchmarks of the ambient family (kernels/ambient_sh.h, ambient_volumes.h)
// per backend and ISA, 1 and 2 threads (tbb::task_arena; OpenCL runs on
// PoCL's own threads), at 1920x1080 through ambient_irradiance() into an
// output allocated once:
//
//   ambient_light        the light rig alone: normals in, R, G, B out
//   ambient_volumes      light and dark rigs blended by 4 volumes (2 boxes,
//                        2 spheres) at each pixel's world position
//   ambient_cheap_dark   the same, the dark rig's first 4 coefficients only
//   ambient_project_rig  the host's projection of the six-axis rig to order 2
//                        (it runs every frame)
//
// Counters: pixels/s and bytes/s (the receivers' planes read and the three
// written). docs/ambient.md has the command and the figures.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <exception>
#include <string>
#include <vector>

#include "bench_inputs.h"
#include "penumbra/ambient.h"
#include "support/ambient_cases.h"
#include "support/backend_list.h"

namespace penumbra::bench {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;

enum class Case { Light, Volumes, CheapDark };

// Normals over the sphere and positions over a 20 x 11 m floor at y = 0.5.
const Image& receivers(int channels)
{
    static const Image six = [] {
        const Image n = testing::sphere_of_normals(kWidth * kHeight, kWidth);
        Image rx(kWidth, kHeight, 6);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                for (int c = 0; c < 3; ++c) {
                    rx.at(c, x, y) = n.at(c, x, y);
                    rx.at(3 + c, x, y) = c == 0 ? -10.0f + 20.0f * x / kWidth : c == 1 ? 0.5f : -5.5f + 11.0f * y / kHeight;
                }
        return rx;
    }();
    static const Image three = [] {
        Image rx(kWidth, kHeight, 3);
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x) rx.at(c, x, y) = six.at(c, x, y);
        return rx;
    }();
    return channels == 6 ? six : three;
}

AmbientLighting lighting(Case c)
{
    const std::vector<testing::NamedRig> rigs = testing::error_table_rigs();
    AmbientLighting l;
    l.light = project_rig(rigs[1].rig);
    if (c == Case::Light) return l;
    l.dark = project_rig(rigs[2].rig);
    std::vector<AmbientVolume> volumes(4);
    for (int i = 0; i < 4; ++i) {
        volumes[std::size_t(i)].shape = i % 2 ? AmbientVolume::Shape::Box : AmbientVolume::Shape::Sphere;
        volumes[std::size_t(i)].center = {-6.0 + 4.0 * i, 0.0, 0.0};
        volumes[std::size_t(i)].half_size = {2.5, 2.0, 3.0};
        volumes[std::size_t(i)].scale_bias = 1.05;
        volumes[std::size_t(i)].falloff_delay = 0.5;
    }
    l.volumes = AmbientVolumes(volumes);
    l.cheap_dark = c == Case::CheapDark;
    return l;
}

void run(benchmark::State& state, const std::string& backend, Case c, int threads)
{
    auto body = [&] {
        try {
            Context& ctx = context(backend);
            state.SetLabel(ctx.description());
            const AmbientLighting l = lighting(c);
            const Image& rx = receivers(ambient_receiver_channels(l));
            Image out(kWidth, kHeight, 3);
            ambient_irradiance(ctx, rx, l, out);  // untimed: PoCL's JIT, first touch
            for (auto _ : state) {
                ambient_irradiance(ctx, rx, l, out);
                benchmark::DoNotOptimize(out.plane(0));
            }
            const double n = double(state.iterations()) * kWidth * kHeight;
            state.counters["pixels/s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
            state.counters["bytes/s"] =
                benchmark::Counter(n * 4.0 * (rx.channels() + 3), benchmark::Counter::kIsRate);
        } catch (const std::exception& e) {
            state.SkipWithError(e.what());
        }
    };
    if (threads <= 0) return body();
    tbb::task_arena arena(threads);
    arena.execute(body);
}

void project(benchmark::State& state)
{
    const AmbientRig rig = testing::error_table_rigs()[1].rig;
    for (auto _ : state) {
        ShIrradiance sh = project_rig(rig);
        benchmark::DoNotOptimize(sh);
    }
    state.counters["rigs/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

[[maybe_unused]] const bool registered = [] {
    const std::pair<const char*, Case> cases[] = {
        {"ambient_light", Case::Light}, {"ambient_volumes", Case::Volumes}, {"ambient_cheap_dark", Case::CheapDark}};
    for (const std::string& backend : testing::backend_names())
        for (const auto& [name, c] : cases)
            for (int threads : {1, 2}) {
                if (backend == "opencl" && threads == 2) continue;  // PoCL runs its own threads
                const int arena = backend == "opencl" ? 0 : threads;
                std::string full = std::string(name) + "/backend:" + backend + "/size:1920x1080";
                if (arena) full += "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(full.c_str(), [=](benchmark::State& s) { run(s, backend, c, arena); })
                    ->UseRealTime()
                    ->Unit(benchmark::kMillisecond);
            }
    benchmark::RegisterBenchmark("ambient_project_rig/six-axis/order:2", project)->Unit(benchmark::kMicrosecond);
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
