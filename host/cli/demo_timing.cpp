#include "demo_timing.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <numeric>
#include <random>

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace penumbra::cli {
namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point from, Clock::time_point to)
{
    return std::chrono::duration<double, std::milli>(to - from).count();
}

double median(std::vector<double> values)
{
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

struct Samples {
    std::vector<double> map_ms, receiver_ms, frame_ms;
};

void time_once(Context& context, const DemoSetting& setting, const DemoFrame& frame,
               const reference::Receivers& timed, Samples& samples)
{
    const Clock::time_point start = Clock::now();
    const DemoPrepared prepared = setting.prepare(context, frame);
    const Clock::time_point built = Clock::now();
    const Image visibility = setting.shade(context, frame, timed, prepared);
    const Clock::time_point shaded = Clock::now();
    samples.map_ms.push_back(ms_between(start, built));
    samples.receiver_ms.push_back(ms_between(built, shaded));
    samples.frame_ms.push_back(ms_between(start, shaded));
}

FrameTimes summarize(const Samples& s)
{
    const auto [low, high] = std::minmax_element(s.frame_ms.begin(), s.frame_ms.end());
    return {median(s.map_ms), median(s.receiver_ms), median(s.frame_ms), *low, *high, int(s.frame_ms.size())};
}

// An engine allocates its tables once and rebuilds them in place each frame;
// the methods' build steps return new ones. glibc serves every block above
// 32 MB (a 2048^2 MSM or EVSM4 table is 200 MB) by a fresh mmap, so each
// frame page-faulted its table anew and the map step of `large` varied from
// 24 to 146 ms between two runs (docs/demo.md). Freed blocks are kept in the
// process instead, so that from the warm-up on a table lands on pages
// already mapped, as an engine's would.
void keep_freed_memory()
{
#ifdef __GLIBC__
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}

}  // namespace

std::vector<FrameTimes> time_settings(Context& context, const std::vector<const DemoSetting*>& settings,
                                      const DemoFrame& frame, const reference::Receivers& timed, int repetitions)
{
    keep_freed_memory();
    std::vector<Samples> samples(settings.size());
    for (const DemoSetting* setting : settings) {  // warm-up, not kept
        Samples ignored;
        time_once(context, *setting, frame, timed, ignored);
    }
    std::vector<std::size_t> order(settings.size());
    std::iota(order.begin(), order.end(), 0);
    std::mt19937 shuffle_source(20261203u);  // fixed: two runs shuffle alike
    for (int round = 0; round < repetitions; ++round) {
        std::shuffle(order.begin(), order.end(), shuffle_source);
        for (std::size_t i : order) time_once(context, *settings[i], frame, timed, samples[i]);
    }
    std::vector<FrameTimes> times;
    for (const Samples& s : samples) times.push_back(summarize(s));
    return times;
}

}  // namespace penumbra::cli
