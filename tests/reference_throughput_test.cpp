// Measurement, not a check: ground-truth throughput and its error against a
// run with 4x the samples, per built-in scene. Disabled in the default run;
//   penumbra_tests --gtest_also_run_disabled_tests --gtest_filter='*GroundTruthFigures*'
// prints the table quoted in docs/reference.md.
#include <gtest/gtest.h>

#include <chrono>
#include <ctime>
#include <cstdio>
#include <tbb/info.h>

#include "penumbra/reference.h"
#include "penumbra/reference/metrics.h"

namespace penumbra::reference {
namespace {

// Wall-clock and process CPU time (all threads): on a machine shared with
// other jobs the wall clock varies with their load, CPU time much less.
struct TimedTruth {
    Image truth;
    double seconds, cpu_seconds;
};

TimedTruth timed_truth(const Scene& scene, const Receivers& receivers, int strata)
{
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    Image truth = ground_truth(scene, receivers, {strata, 0x51a7ull + std::uint64_t(strata)});
    const double cpu = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    return {std::move(truth), elapsed.count(), cpu};
}

double count(const Image& mask)
{
    double n = 0;
    for (int y = 0; y < mask.height(); ++y)
        for (int x = 0; x < mask.width(); ++x) n += mask.at(0, x, y);
    return n;
}

TEST(ReferenceThroughput, DISABLED_GroundTruthFigures)
{
    constexpr int kWidth = 160, kHeight = 120;
    const int strata[] = {8, 16, 32, 64};
    std::printf("receivers %dx%d, %d threads; samples/s counts receiver-samples (shadow rays)\n", kWidth,
                kHeight, tbb::info::default_concurrency());
    std::printf("%-8s %6s %13s %13s %13s %12s %14s\n", "scene", "valid", "RMSE 8 v 16", "RMSE 16 v 32",
                "RMSE 32 v 64", "Msamples/s", "Msamples/cpu-s");
    for (const std::string& name : builtin_scene_names()) {
        const Scene scene = builtin_scene(name);
        const Receivers receivers = render_receivers(scene, kWidth, kHeight);
        std::vector<TimedTruth> runs;
        for (int n : strata) runs.push_back(timed_truth(scene, receivers, n));
        const double hits = count(receivers.hit);
        const double samples = hits * 64.0 * 64.0;  // in the last, largest run
        const double valid = count(receivers.mask) / (kWidth * kHeight);
        std::printf("%-8s %6.3f %13.5f %13.5f %13.5f %12.1f %14.1f\n", name.c_str(), valid,
                    reference::rmse(runs[0].truth, runs[1].truth, &receivers.mask),
                    reference::rmse(runs[1].truth, runs[2].truth, &receivers.mask),
                    reference::rmse(runs[2].truth, runs[3].truth, &receivers.mask), samples / runs.back().seconds / 1e6,
                    samples / runs.back().cpu_seconds / 1e6);
    }
}

TEST(ReferenceThroughput, DISABLED_LargeShadowMapTime)
{
    const Scene scene = builtin_scene("large");
    for (int size : {1024, 4096}) {
        const auto start = std::chrono::steady_clock::now();
        const Image map = render_shadow_map(scene, size, size);
        const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
        std::printf("large: %dx%d shadow map in %.2f s (%.1f Mrays/s)\n", size, size, elapsed.count(),
                    double(size) * size / elapsed.count() / 1e6);
    }
}

}  // namespace
}  // namespace penumbra::reference
