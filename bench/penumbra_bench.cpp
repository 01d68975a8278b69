// penumbra_bench: every kernel per backend x ISA x size x thread count, with
// pixels/s and bytes/s counters, and the peers that make those figures ratios
// (DESIGN.md "Measuring", STYLE.md item 12). docs/benchmarks.md says how to run
// it and what each case measures; bench/ratios.py turns its JSON into the
// ratios the project quotes and parses the case names made here (the two must
// agree on the name format: `op/key:value/.../threads:n`).
//
// Threads: a tbb::task_arena of n threads around the timed loop bounds the
// library's TBB schedule (simd/cpu_backend.cpp asks its arena for its
// concurrency). OpenCL runs on PoCL's own threads (every core); its cases
// carry no thread count.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "bench_inputs.h"
#include "penumbra/chebyshev.h"
#include "penumbra/moment_table.h"
#include "simd/cpu_kernels.h"

#ifdef __SSE2__
#include <immintrin.h>
#endif
#ifdef PENUMBRA_HAVE_OPENCV
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#endif

namespace penumbra::bench {
namespace {

constexpr int kMoments = 2;
constexpr int kVsmRadius = 8;
const std::vector<int> kSizes{1024, 2048, 4096};
const std::vector<int> kScalarSizes{1024, 2048};  // the scalar path is slow; keep the run short
const std::vector<int> kThreads{1, 2};
// The default --benchmark_min_time (main() passes it unless the command line
// does): long enough for a few iterations of the 4096^2 cases per repetition,
// short enough that --benchmark_repetitions=5 of everything takes minutes. A
// flag rather than Benchmark::MinTime(), which would override the command line
// (profiling wants longer runs) and put "min_time:" into every case name.
constexpr const char* kMinTimeFlag = "--benchmark_min_time=0.2";

// Runs fn inside an arena of `threads` threads; 0 = no arena (OpenCL).
template <class Fn>
void in_arena(int threads, Fn&& fn)
{
    if (threads <= 0) {
        fn();
        return;
    }
    tbb::task_arena arena(threads);
    arena.execute(fn);
}

void set_rates(benchmark::State& state, double pixels, double bytes)
{
    const double n = double(state.iterations());
    state.counters["pixels/s"] = benchmark::Counter(pixels * n, benchmark::Counter::kIsRate);
    if (bytes > 0) state.counters["bytes/s"] = benchmark::Counter(bytes * n, benchmark::Counter::kIsRate);
}

std::string precision_name(Precision p) { return p == Precision::Float ? "float" : "exact"; }

std::string suffix(int size, int threads)
{
    std::string s = "/size:" + std::to_string(size);
    if (threads > 0) s += "/threads:" + std::to_string(threads);
    return s;
}

// True the first time a case asks: its untimed warm-up call (PoCL's kernel JIT,
// the first touch of the inputs' pages) runs once per process, not once per
// repetition, which keeps the slow cases of a 5-repetition run short.
bool first_run(const std::string& name)
{
    static std::set<std::string> seen;
    return seen.insert(name).second;
}

// The timed loop of a library case, in an arena of `threads`: one untimed
// call first (once per process), and an error (Error(Unavailable) from PoCL,
// say) marks the case skipped instead of ending the run.
template <class Fn>
void run_case(benchmark::State& state, const std::string& name, int threads, Fn&& call)
{
    in_arena(threads, [&] {
        try {
            if (first_run(name)) call();
            for (auto _ : state) {
                call();
                benchmark::ClobberMemory();
            }
        } catch (const std::exception& e) {
            state.SkipWithError(e.what());
        }
    });
}

// Best of the repetitions, next to the median: on a shared machine other
// processes only ever add time, so the fastest repetition is the least
// disturbed one (ratios.py --stat min derives its rates from this time).
double fastest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }

void finish_registration(benchmark::internal::Benchmark* b)
{
    b->UseRealTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", fastest);
}

// Fetches the backend's context, or marks the case skipped (OpenCL absent).
Context* context_or_skip(benchmark::State& state, const std::string& backend)
{
    try {
        Context& ctx = context(backend);
        state.SetLabel(ctx.description());
        return &ctx;
    } catch (const std::exception& e) {
        state.SkipWithError((backend + " unavailable: " + e.what()).c_str());
        return nullptr;
    }
}

// 1. The denominator: std::memcpy of as many bytes as the table build moves
// (read + written). A copy reads and writes each byte once, so it copies half
// of table_bytes_per_texel() per texel, in 1 MiB chunks spread over the arena.
void register_memcpy()
{
    constexpr std::size_t kChunk = std::size_t(1) << 20;
    for (int size : kSizes)
        for (int threads : kThreads) {
            const std::size_t moved = std::size_t(size) * size * table_bytes_per_texel(kMoments * kVsmLimbs);
            auto fn = [=](benchmark::State& state) {
                const CopyBuffers& buf = copy_buffers(moved / 2);
                const std::size_t chunks = (buf.bytes + kChunk - 1) / kChunk;
                auto copy = [&] {
                    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1),
                                      [&](const tbb::blocked_range<std::size_t>& r) {
                                          for (std::size_t c = r.begin(); c < r.end(); ++c) {
                                              const std::size_t off = c * kChunk;
                                              std::memcpy(buf.dst + off, buf.src + off,
                                                          std::min(kChunk, buf.bytes - off));
                                          }
                                      });
                    benchmark::ClobberMemory();
                };
                in_arena(threads, [&] {
                    copy();
                    for (auto _ : state) copy();
                });
                set_rates(state, double(size) * size, double(moved));
            };
            finish_registration(benchmark::RegisterBenchmark(("memcpy" + suffix(size, threads)).c_str(), fn));
        }
}

// 1b. The exact VSM table build's traffic with none of its arithmetic: the
// map read and the 16 B/texel written into a real table's two pair planes at
// the build's addresses, streamed past the caches as the build streams them
// (16-byte non-temporal stores, SSE2, on every x86-64), rows shared among the
// threads. table_into / table_traffic is what the arithmetic costs beyond the
// bytes; table_traffic / memcpy is what the bytes' pattern (80% writes, two
// streams) allows (docs/moment_table.md, "Session 20").
void stream_pairs(std::uint32_t* pair, const float* row, int width)
{
    int x = 0;
#ifdef __SSE2__
    if (reinterpret_cast<std::uintptr_t>(pair) % 16 == 0)
        for (; x + 4 <= width; x += 4) {
            const __m128i bits = _mm_castps_si128(_mm_loadu_ps(row + x));
            _mm_stream_si128(reinterpret_cast<__m128i*>(pair + 2 * x), _mm_unpacklo_epi32(bits, bits));
            _mm_stream_si128(reinterpret_cast<__m128i*>(pair + 2 * x + 4), _mm_unpackhi_epi32(bits, bits));
        }
#endif
    for (; x < width; ++x) {
        std::memcpy(pair + 2 * x, row + x, sizeof(float));
        std::memcpy(pair + 2 * x + 1, row + x, sizeof(float));
    }
}

void register_table_traffic()
{
    for (int size : kSizes)
        for (int threads : kThreads) {
            auto fn = [=](benchmark::State& state) {
                const Image& depth = depth_map(size);
                MomentTable table(size, size, kMoments, Precision::Exact);
                std::uint32_t* origin = table.exact_origin();
                const std::size_t pitch = std::size_t(table.pitch()), value_stride = table.plane_pitch() * kVsmLimbs;
                auto write = [&] {
                    tbb::parallel_for(tbb::blocked_range<int>(0, size), [&](const tbb::blocked_range<int>& r) {
                        for (int y = r.begin(); y < r.end(); ++y) {
                            const float* row = depth.row(0, y);
                            for (int value = 0; value < kMoments; ++value)
                                stream_pairs(origin + value * value_stride + 2 * (std::size_t(y) + 1) * pitch, row, size);
                        }
#ifdef __SSE2__
                        _mm_sfence();
#endif
                    });
                    benchmark::DoNotOptimize(table.storage());
                };
                in_arena(threads, [&] {
                    write();
                    for (auto _ : state) write();
                });
                set_rates(state, double(size) * size, double(size) * size * table_bytes_per_texel(kMoments * kVsmLimbs));
            };
            finish_registration(benchmark::RegisterBenchmark(("table_traffic" + suffix(size, threads)).c_str(), fn));
        }
}

// 2. build_moment_table(), two ways. `table`: the call that returns a new
// table, as a caller pays for it: the checks, the fresh zero-filled table (its
// page faults included) and the kernel. `table_into`: the per-frame overload
// that fills an existing table, allocated once outside the timing; the
// like-for-like comparison with memcpy, which also writes to touched memory.
void register_table(const std::string& backend, const std::vector<int>& sizes, const std::vector<int>& threads_list)
{
    for (bool into : {false, true})
        for (Precision precision : {Precision::Float, Precision::Exact})
            for (int size : sizes)
                for (int threads : threads_list) {
                    const std::string name = std::string(into ? "table_into" : "table") + "/backend:" + backend +
                                             "/precision:" + precision_name(precision) + suffix(size, threads);
                    auto fn = [=](benchmark::State& state) {
                        Context* ctx = context_or_skip(state, backend);
                        if (!ctx) return;
                        const Image& depth = depth_map(size);
                        if (into) {
                            MomentTable table(size, size, kMoments, precision);
                            run_case(state, name, threads, [&] {
                                build_moment_table(*ctx, depth, table);
                                benchmark::DoNotOptimize(table.storage());
                            });
                        } else {
                            run_case(state, name, threads, [&] {
                                MomentTable table = build_moment_table(*ctx, depth, kMoments, precision);
                                benchmark::DoNotOptimize(table.storage());
                            });
                        }
                        const int planes = precision == Precision::Exact ? kMoments * kVsmLimbs : kMoments;
                        set_rates(state, double(size) * size, double(size) * size * table_bytes_per_texel(planes));
                    };
                    finish_registration(benchmark::RegisterBenchmark(name.c_str(), fn));
                }
}

// 3. vsm() (radius 8) and vssm() (default light size): receivers of the map's
// size at the texel centres over a table built beforehand. `vsm_r8` and `vssm`
// return a new image (its allocation and first touch timed: 15% of VSSM's
// time on Zen 5, 30% of VSM's); `vsm_r8_into` and `vssm_into` write an output
// image allocated once, the per-frame overloads, so that the two methods are
// measured alike. `*_shuffled`: the same receivers in a random order (into an
// output allocated once), so that neighbouring lanes read unrelated windows:
// the incoherent case, which a gather cannot read as one contiguous run.
// `*_magnified`: receivers 0.6 texel apart (bench_inputs.h), neighbouring
// lanes' corners repeat or skip: a span, not a run.
// vsm_r0 .. vsm_r2 (exact only): the small windows, which issue 9 requires to be
// no slower than before it (their radius is the digit after "vsm_r"), on the
// exact table and summed directly from the map (`precision:map`, no table:
// what `penumbra shade` runs at these radii, docs/moment_table.md).
struct LookupCase {
    std::string op;
    bool vssm, into;
    const Image& (*receivers)(int size);
    int radius;  // vsm's
};
LookupCase lookup_case(const std::string& op)
{
    const bool vssm = op.compare(0, 4, "vssm") == 0;
    const bool shuffled = op.find("_shuffled") != std::string::npos;
    const bool magnified = op.find("_magnified") != std::string::npos;
    const bool into = shuffled || magnified || op.find("_into") != std::string::npos;
    return {op, vssm, into, shuffled ? shuffled_receivers : magnified ? magnified_receivers : receivers,
            vssm ? 0 : op[5] - '0'};
}

void register_lookups(const std::string& backend, const std::vector<int>& sizes, const std::vector<int>& threads_list)
{
    for (const std::string op : {"vsm_r0", "vsm_r1", "vsm_r2", "vsm_r8", "vsm_r8_into", "vsm_r8_shuffled",
                                 "vsm_r8_magnified", "vssm", "vssm_into", "vssm_shuffled", "vssm_magnified"})
        for (int source : {0, 1, 2})  // float table, exact table, the map
            for (int size : sizes)
                for (int threads : threads_list) {
                    const LookupCase c = lookup_case(op);
                    const bool small = !c.vssm && c.radius < kVsmRadius;
                    const bool direct = source == 2;
                    const Precision precision = source == 0 ? Precision::Float : Precision::Exact;
                    if ((small && precision == Precision::Float) || (direct && !small)) continue;
                    const std::string name = op + "/backend:" + backend + "/precision:" +
                                             (direct ? "map" : precision_name(precision)) + suffix(size, threads);
                    auto fn = [=](benchmark::State& state) {
                        Context* ctx = context_or_skip(state, backend);
                        if (!ctx) return;
                        const Image& rx = c.receivers(size);
                        if (direct) {
                            const Image& depth = depth_map(size);
                            run_case(state, name, threads, [&] {
                                Image out = vsm(*ctx, depth, rx, VsmOptions{c.radius});
                                benchmark::DoNotOptimize(out.plane(0));
                            });
                            set_rates(state, double(size) * size, 0);
                            return;
                        }
                        const MomentTable& table = moment_table(size, precision);
                        if (c.into) {
                            Image out(size, size, 1);
                            run_case(state, name, threads, [&] {
                                if (c.vssm) vssm(*ctx, table, rx, VssmOptions{}, out);
                                else vsm(*ctx, table, rx, VsmOptions{c.radius}, out);
                                benchmark::DoNotOptimize(out.plane(0));
                            });
                        } else {
                            run_case(state, name, threads, [&] {
                                Image out = c.vssm ? vssm(*ctx, table, rx, VssmOptions{})
                                                   : vsm(*ctx, table, rx, VsmOptions{c.radius});
                                benchmark::DoNotOptimize(out.plane(0));
                            });
                        }
                        set_rates(state, double(size) * size, 0);
                    };
                    finish_registration(benchmark::RegisterBenchmark(name.c_str(), fn));
                }
}

// Where `table` loses to `table_into`: a fresh table alone, aligned_alloc and
// its memset (8 B/texel for 2 moments) on one thread, page faults included
// (glibc maps blocks above its mmap threshold, at most 32 MiB, afresh on every
// call: 2048^2 and 4096^2 tables are above it, 1024^2 ones are reused).
void register_diagnostics()
{
    for (int size : kSizes) {
        auto alloc = [=](benchmark::State& state) {
            for (auto _ : state) {
                MomentTable table(size, size, kMoments, Precision::Float);
                benchmark::DoNotOptimize(table.storage());
            }
            set_rates(state, double(size) * size, double(size) * size * 4 * kMoments);
        };
        finish_registration(
            benchmark::RegisterBenchmark(("diag_table_alloc" + suffix(size, 1)).c_str(), alloc));
    }
}

#ifdef PENUMBRA_HAVE_OPENCV
// 4. The peer: cv::integral(src, sum, sqsum) on the same float depth map, with
// a CV_32F sum and a CV_32F square sum, the combination that matches a float
// table of 2 moments byte for byte (OpenCV 4.6 accepts 32F/32F, 32F/64F and
// 64F/64F for a CV_32F source). Outputs are reused, as OpenCV users do; bytes
// counted as for the table build.
void register_opencv()
{
    for (int size : kSizes)
        for (int threads : kThreads) {
            auto fn = [=](benchmark::State& state) {
                const Image& depth = depth_map(size);
                const cv::Mat src(size, size, CV_32F, const_cast<float*>(depth.plane(0)),
                                  std::size_t(depth.pitch()) * sizeof(float));
                cv::Mat sum, sqsum;
                const int saved = cv::getNumThreads();
                cv::setNumThreads(threads);
                cv::integral(src, sum, sqsum, CV_32F, CV_32F);  // warm-up: allocates the outputs
                for (auto _ : state) {
                    cv::integral(src, sum, sqsum, CV_32F, CV_32F);
                    benchmark::DoNotOptimize(sum.data);
                    benchmark::DoNotOptimize(sqsum.data);
                    benchmark::ClobberMemory();
                }
                cv::setNumThreads(saved);
                state.SetLabel("OpenCV " CV_VERSION ", sum CV_32F, sqsum CV_32F");
                set_rates(state, double(size) * size, double(size) * size * table_bytes_per_texel(kMoments));
            };
            const std::string name = "opencv_integral/sum:32f/sqsum:32f" + suffix(size, threads);
            finish_registration(benchmark::RegisterBenchmark(name.c_str(), fn));
        }
}
#endif

// Sizes and thread counts per backend (testing::backend_names()): scalar is
// slow, so its run is short and on one thread; OpenCL runs PoCL's own
// threads (0: no arena).
struct BackendPlan {
    std::vector<int> sizes, threads;
};
BackendPlan plan_for(const std::string& backend)
{
    if (backend == "scalar") return {kScalarSizes, {1}};
    if (backend == "opencl") return {kSizes, {0}};
    return {kSizes, kThreads};
}

void register_all()
{
    std::vector<std::string> isas;
    for (std::string_view isa : cpu::supported_isas()) isas.emplace_back(isa);
    std::string isa_list;
    for (const auto& isa : isas) isa_list += (isa_list.empty() ? "" : ",") + isa;
    benchmark::AddCustomContext("penumbra_simd_isas", isa_list);
    benchmark::AddCustomContext("penumbra_default_isa", std::string(cpu::chosen_isa()));

    register_memcpy();
    register_table_traffic();
    const std::vector<std::string> backends = testing::backend_names();
    for (const std::string& backend : backends)
        register_table(backend, plan_for(backend).sizes, plan_for(backend).threads);
#ifdef PENUMBRA_HAVE_OPENCV
    register_opencv();
#endif
    for (const std::string& backend : backends)
        register_lookups(backend, plan_for(backend).sizes, plan_for(backend).threads);
    register_diagnostics();
}

}  // namespace
}  // namespace penumbra::bench

int main(int argc, char** argv)
{
    std::vector<char*> args(argv, argv + argc);
    const bool has_min_time = std::any_of(args.begin(), args.end(), [](const char* a) {
        return std::string_view(a).rfind("--benchmark_min_time", 0) == 0;
    });
    std::string min_time = penumbra::bench::kMinTimeFlag;
    if (!has_min_time) args.insert(args.begin() + 1, min_time.data());
    args.push_back(nullptr);
    argc = int(args.size()) - 1;
    argv = args.data();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    penumbra::bench::register_all();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
