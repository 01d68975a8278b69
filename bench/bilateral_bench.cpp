// Benchmarks of the cross-bilateral filter (kernels/bilateral.h) at 1920x1080,
// radius 2: full 2D (square and OpenCV's disk window) and separable, 1 and 4
// channels, per backend and ISA, 1 and 2 threads (tbb::task_arena), and
// OpenCV's cv::ximgproc::jointBilateralFilter with the same parameters as the
// peer in the same run (DESIGN.md "Measuring"). docs/bilateral.md has the
// command and the figures. Case names follow penumbra_bench's
// `op/key:value/.../threads:n` format.
//
// Parameters shared with the peer: spatial sigma 1.5 px, absolute Gaussian
// range weight with depth sigma 0.05, clamp-to-edge borders (OpenCV's
// BORDER_REPLICATE). OpenCV filters 1 or 3 channels per call; its 4-channel
// figure is a 3-channel call plus a 1-channel call, as a user would do it.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <random>
#include <string>
#include <vector>

#include "bench_inputs.h"
#include "penumbra/bilateral.h"

#ifdef PENUMBRA_HAVE_OPENCV_XIMGPROC
#include <opencv2/core.hpp>
#include <opencv2/ximgproc/edge_filter.hpp>
#endif

namespace penumbra::bench {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;
constexpr int kRadius = 2;
constexpr float kSpatialSigma = 1.5f;
constexpr float kDepthSigma = 0.05f;

// A frame's view depth: a ground plane receding from 2 to 40 units with
// 24 boxes standing on it (depth steps of several units at their outlines).
float frame_depth(int x, int y)
{
    const float v = float(y) / float(kHeight);
    float z = 2.0f + 38.0f * (1.0f - v) * (1.0f - v);
    for (int i = 0; i < 24; ++i) {
        const int bx = (i * 421) % (kWidth - 160), by = 200 + (i * 173) % (kHeight - 400);
        if (x >= bx && x < bx + 140 && y >= by && y < by + 180) z = std::min(z, 1.5f + 0.5f * float(i % 7));
    }
    return z;
}

const Image& guide()
{
    static const Image image = [] {
        Image g(kWidth, kHeight, 1);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) g.at(0, x, y) = frame_depth(x, y) / 40.0f;  // in (0, 1]
        return g;
    }();
    return image;
}

// A noisy mask (a stochastic shadow or SSAO estimate): uniform noise around a
// smooth ramp, different per channel.
const Image& mask(int channels)
{
    static std::vector<Image> images(5);
    Image& m = images[std::size_t(channels)];
    if (m.empty()) {
        m = Image(kWidth, kHeight, channels);
        std::mt19937 rng(7 + channels);
        std::uniform_real_distribution<float> noise(-0.25f, 0.25f);
        for (int c = 0; c < channels; ++c)
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x)
                    m.at(c, x, y) =
                        std::clamp(0.5f + 0.4f * std::sin(0.01f * float(x + 37 * c)) + noise(rng), 0.0f, 1.0f);
    }
    return m;
}

BilateralOptions options(const std::string& schedule)
{
    BilateralOptions o;
    o.radius = kRadius;
    o.spatial_sigma = kSpatialSigma;
    o.depth_sigma = kDepthSigma;
    o.relative = false;  // OpenCV's definition
    o.window = schedule == "disk" ? BilateralWindow::Disk : BilateralWindow::Square;
    o.separable = schedule == "separable";
    return o;
}

void set_rates(benchmark::State& state, int channels)
{
    const double pixels = double(kWidth) * kHeight * double(state.iterations());
    state.counters["pixels/s"] = benchmark::Counter(pixels, benchmark::Counter::kIsRate);
    // Read the mask and guide, write the output: 4 bytes each per channel / pixel.
    state.counters["bytes/s"] = benchmark::Counter(pixels * 4.0 * (2 * channels + 1), benchmark::Counter::kIsRate);
}

template <class Fn>
void in_arena(int threads, Fn&& fn)
{
    if (threads <= 0) return fn();
    tbb::task_arena arena(threads);
    arena.execute(fn);
}

void run_penumbra(benchmark::State& state, const std::string& backend, const std::string& schedule, int channels,
                  int threads)
{
    try {
        Context& ctx = context(backend);
        state.SetLabel(ctx.description());
        const Image& m = mask(channels);
        Image out(kWidth, kHeight, channels);
        const BilateralOptions o = options(schedule);
        in_arena(threads, [&] {
            cross_bilateral(ctx, m, guide(), o, out);  // untimed: PoCL's JIT, first touch of the pages
            for (auto _ : state) {
                cross_bilateral(ctx, m, guide(), o, out);
                benchmark::DoNotOptimize(out.plane(0));
                benchmark::ClobberMemory();
            }
        });
        set_rates(state, channels);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}

#ifdef PENUMBRA_HAVE_OPENCV_XIMGPROC
// cv::ximgproc::jointBilateralFilter(joint, src, dst, d = 2r + 1, sigmaColor,
// sigmaSpace, BORDER_REPLICATE) on the same float images (wrapped, not copied).
void run_opencv(benchmark::State& state, int channels, int threads)
{
    const Image& g = guide();
    const cv::Mat joint(kHeight, kWidth, CV_32F, const_cast<float*>(g.plane(0)), std::size_t(g.pitch()) * 4);
    // OpenCV wants interleaved channels: build them once, outside the timing.
    const Image& m = mask(channels);
    std::vector<cv::Mat> planes;
    for (int c = 0; c < channels; ++c)
        planes.emplace_back(kHeight, kWidth, CV_32F, const_cast<float*>(m.plane(c)), std::size_t(m.pitch()) * 4);
    std::vector<cv::Mat> sources;  // 1 -> {1}, 4 -> {3, 1}
    if (channels == 1) sources.push_back(planes[0]);
    else {
        cv::Mat three;
        cv::merge(std::vector<cv::Mat>{planes[0], planes[1], planes[2]}, three);
        sources.push_back(three);
        sources.push_back(planes[3]);
    }
    std::vector<cv::Mat> outputs(sources.size());
    const int saved = cv::getNumThreads();
    cv::setNumThreads(threads);
    auto filter = [&] {
        for (std::size_t i = 0; i < sources.size(); ++i)
            cv::ximgproc::jointBilateralFilter(joint, sources[i], outputs[i], 2 * kRadius + 1, kDepthSigma,
                                               kSpatialSigma, cv::BORDER_REPLICATE);
    };
    filter();
    for (auto _ : state) {
        filter();
        benchmark::DoNotOptimize(outputs[0].data);
        benchmark::ClobberMemory();
    }
    cv::setNumThreads(saved);
    state.SetLabel(std::string("OpenCV ") + CV_VERSION + (channels == 4 ? ", 3-channel + 1-channel calls" : ""));
    set_rates(state, channels);
}
#endif

// The fastest repetition, as penumbra_bench's other cases report it: on a
// shared machine, the best estimate of the time with every core free.
double fastest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }

// Registered at static initialisation, as BENCHMARK() does, with names built
// from the ISAs this CPU has.
[[maybe_unused]] const bool registered = [] {
    // No "size:" key: bench/ratios.py reads that one as a square map's side.
    const std::string size = "/width:1920/height:1080/radius:2";
    for (const std::string& backend : testing::backend_names())
        for (const char* schedule : {"full", "disk", "separable"})
            for (int channels : {1, 4})
                for (int threads : {1, 2}) {
                    if (backend == "opencl" && threads == 2) continue;  // PoCL runs its own threads
                    const int arena = backend == "opencl" ? 0 : threads;
                    std::string name = std::string("bilateral/backend:") + backend + "/schedule:" + schedule +
                                       "/channels:" + std::to_string(channels) + size;
                    if (arena) name += "/threads:" + std::to_string(threads);
                    benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) {
                        run_penumbra(s, backend, schedule, channels, arena);
                    })->UseRealTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", fastest);
                }
#ifdef PENUMBRA_HAVE_OPENCV_XIMGPROC
    for (int channels : {1, 4})
        for (int threads : {1, 2}) {
            const std::string name = "opencv_joint_bilateral/schedule:disk/channels:" + std::to_string(channels) +
                                     size + "/threads:" + std::to_string(threads);
            benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) { run_opencv(s, channels, threads); })
                ->UseRealTime()
                ->Unit(benchmark::kMillisecond)
                ->ComputeStatistics("min", fastest);
        }
#endif
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
