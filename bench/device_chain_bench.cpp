// The chained pipeline at 1080p (issue 18, item 2): moment table build of a
// 1024^2 map, VSM lookup of 1920x1080 receivers, cross-bilateral blur of the
// visibility, per backend:
//   residency:host      the Image forms, each step's inputs and outputs on the host;
//   residency:device    penumbra/device_image.h: the three inputs uploaded,
//                       the chain enqueued, one finish, the result downloaded;
//   residency:resident  the same with the inputs already on the device (a
//                       renderer's own buffers, Context::from_opencl): only
//                       the result comes back.
// Counters: host transfers per frame (uploads, downloads and their MB, from
// penumbra::host_transfers(): OpenCL only, 0 on the CPU backends, which have
// no device). docs/integration.md has the command and the figures.
#include <benchmark/benchmark.h>

#include <string>

#include "bench_inputs.h"
#include "timed_loop.h"
#include "penumbra/bilateral.h"
#include "penumbra/chebyshev.h"
#include "penumbra/device_image.h"

namespace penumbra::bench {
namespace {

constexpr int kWidth = 1920, kHeight = 1080, kMapSize = 1024;

// Receivers over the whole map at z 0.55 (between bench_inputs.h's occluders
// and its ground: about a third in shadow), and a guide depth with a slope.
struct Frame {
    Image receivers{kWidth, kHeight, 3}, guide{kWidth, kHeight, 1};
    Frame()
    {
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                receivers.at(0, x, y) = (float(x) + 0.5f) / kWidth;
                receivers.at(1, x, y) = (float(y) + 0.5f) / kHeight;
                receivers.at(2, x, y) = 0.55f;
                guide.at(0, x, y) = 0.5f + 0.1f * float(y) / kHeight;
            }
    }
};
const Frame& frame()
{
    static const Frame f;
    return f;
}

const VsmOptions kVsm{};  // radius 2
BilateralOptions blur() { return BilateralOptions{}; }  // radius 2, 5x5 square

void host_chain(Context& ctx, Image& out)
{
    const MomentTable table = build_moment_table(ctx, depth_map(kMapSize), 2, Precision::Exact);
    const Image visibility = vsm(ctx, table, frame().receivers, kVsm);
    cross_bilateral(ctx, visibility, frame().guide, blur(), out);
}

struct Resident {
    DeviceImage depth, receivers, guide, visibility, blurred;
    DeviceMomentTable table;
    explicit Resident(Context& ctx)
        : depth(upload(ctx, depth_map(kMapSize))), receivers(upload(ctx, frame().receivers)),
          guide(upload(ctx, frame().guide)), visibility(device_image(ctx, kWidth, kHeight, 1)),
          blurred(device_image(ctx, kWidth, kHeight, 1)), table(device_moment_table(ctx, kMapSize, kMapSize))
    {
    }
    Image run(Context& ctx)
    {
        build_moment_table(ctx, depth, table);
        vsm(ctx, table, receivers, kVsm, visibility);
        cross_bilateral(ctx, visibility, guide, blur(), blurred);
        return download(ctx, blurred);
    }
};

void set_counters(benchmark::State& state, const HostTransfers& before)
{
    const HostTransfers after = host_transfers();
    // Per frame: the untimed first call is one more frame than the iterations.
    const double frames = double(state.iterations()) + 1.0;
    state.counters["uploads"] = double(after.uploads - before.uploads) / frames;
    state.counters["downloads"] = double(after.downloads - before.downloads) / frames;
    state.counters["upload_MB"] = double(after.upload_bytes - before.upload_bytes) / frames / 1e6;
    state.counters["download_MB"] = double(after.download_bytes - before.download_bytes) / frames / 1e6;
    state.counters["pixels/s"] =
        benchmark::Counter(double(kWidth) * kHeight * double(state.iterations()), benchmark::Counter::kIsRate);
}

void run(benchmark::State& state, const std::string& backend, const std::string& residency)
{
    frame();
    depth_map(kMapSize);
    Image out(kWidth, kHeight, 1);
    std::unique_ptr<Resident> resident;
    HostTransfers before{};
    bool first = true;
    timed_loop(state, backend, 0, [&](Context& ctx) {
        if (first) {  // the inputs of `resident` are there before the counting starts
            if (residency == "resident") resident = std::make_unique<Resident>(ctx);
            before = host_transfers();
            first = false;
        }
        if (residency == "host") host_chain(ctx, out);
        else if (residency == "device") out = Resident(ctx).run(ctx);
        else out = resident->run(ctx);
        benchmark::DoNotOptimize(out.plane(0));
    });
    set_counters(state, before);
}

[[maybe_unused]] const bool registered = [] {
    for (const std::string& backend : {std::string("opencl"), best_cpu_backend()})
        for (const char* residency : {"host", "device", "resident"}) {
            const std::string name = "device_chain/backend:" + backend + "/residency:" + residency +
                                     "/map:1024/width:1920/height:1080";
            benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) { run(s, backend, residency); })
                ->UseRealTime()
                ->Unit(benchmark::kMillisecond);
        }
    return true;
}();

}  // namespace
}  // namespace penumbra::bench
