// The ground-truth table of docs/reference.md, a measurement, not a check:
// per built-in scene, the valid fraction, the truth's convergence (RMSE of
// each run against one with 4x the samples, 8^2 .. 64^2 rays per receiver)
// and its throughput in receiver-samples (shadow rays) per second of wall
// clock and of process CPU time. The shadow-map render time is a benchmark:
// penumbra_bench --benchmark_filter=reference_shadow_map (bench/reference_bench.cpp).
// Then what the receiver's own surface changes (docs/reference.md, "Ground
// truth"): per scene, the truth with the receivers' surface ids against the
// same truth with the ids removed (the normal lift), 32^2 rays, one seed.
// usage: ground_truth_figures [width height]   (default 160 120, the doc's)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include <tbb/info.h>

#include "penumbra/reference.h"
#include "penumbra/reference/metrics.h"

using namespace penumbra;
using namespace penumbra::reference;

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

void print_table(int width, int height)
{
    const int strata[] = {8, 16, 32, 64};
    std::printf("receivers %dx%d, %d threads; samples/s counts receiver-samples (shadow rays)\n", width,
                height, tbb::info::default_concurrency());
    std::printf("%-8s %6s %13s %13s %13s %12s %14s\n", "scene", "valid", "RMSE 8 v 16", "RMSE 16 v 32",
                "RMSE 32 v 64", "Msamples/s", "Msamples/cpu-s");
    for (const std::string& name : builtin_scene_names()) {
        const Scene scene = builtin_scene(name);
        const Receivers receivers = render_receivers(scene, width, height);
        std::vector<TimedTruth> runs;
        for (int n : strata) runs.push_back(timed_truth(scene, receivers, n));
        const double hits = count(receivers.hit);
        const double samples = hits * 64.0 * 64.0;  // in the last, largest run
        const double valid = count(receivers.mask) / (width * height);
        std::printf("%-8s %6.3f %13.5f %13.5f %13.5f %12.1f %14.1f\n", name.c_str(), valid,
                    reference::rmse(runs[0].truth, runs[1].truth, &receivers.mask),
                    reference::rmse(runs[1].truth, runs[2].truth, &receivers.mask),
                    reference::rmse(runs[2].truth, runs[3].truth, &receivers.mask), samples / runs.back().seconds / 1e6,
                    samples / runs.back().cpu_seconds / 1e6);
    }
}

// The truth with Receivers::surface against the lift (the ids set to -1):
// the receivers that change, and by how much (new - old).
void print_own_surface_table(int width, int height)
{
    std::printf("\nthe receiver's own surface against the normal lift, 32^2 rays, %dx%d receivers\n", width, height);
    std::printf("%-8s %9s %8s %10s %10s %9s\n", "scene", "receivers", "changed", "RMSE", "mean", "worst");
    for (const std::string& name : builtin_scene_names()) {
        const Scene scene = builtin_scene(name);
        const Receivers receivers = render_receivers(scene, width, height);
        Receivers lifted = receivers;
        lifted.surface.fill(0, -1.0f);
        const Image own = ground_truth(scene, receivers, {32}), lift = ground_truth(scene, lifted, {32});
        int changed = 0;
        double sum = 0, worst = 0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                if (receivers.mask.at(0, x, y) == 0) continue;
                const double d = double(own.at(0, x, y)) - double(lift.at(0, x, y));
                changed += d != 0;
                sum += d;
                worst = std::max(worst, std::fabs(d));
            }
        const double receivers_count = count(receivers.mask);
        std::printf("%-8s %9.0f %8d %10.5f %+10.5f %9.4f\n", name.c_str(), receivers_count, changed,
                    reference::rmse(own, lift, &receivers.mask), sum / std::max(receivers_count, 1.0), worst);
    }
}

}  // namespace

int main(int argc, char** argv)
{
    const int width = argc == 3 ? std::atoi(argv[1]) : 160, height = argc == 3 ? std::atoi(argv[2]) : 120;
    if ((argc != 1 && argc != 3) || width < 1 || height < 1 || width > 8192 || height > 8192) {
        std::fprintf(stderr, "usage: ground_truth_figures [width height, 1..8192]\n");
        return 2;
    }
    print_table(width, height);
    print_own_surface_table(width, height);
    return 0;
}
