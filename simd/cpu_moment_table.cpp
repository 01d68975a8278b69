// CPU launch of the summed-area table build (kernels/moment_table.h): a
// pipeline of column bands, a special schedule (not launch_tasks over
// sat_bands_*): it writes the table once, where the banded build (OpenCL's)
// reads and rewrites the rows below its first band in the join pass. (The
// banded build was not timed on the CPU against it.)
//
// Schedule notes: the table is written once, streamed past the caches
// (pn_store_stream); the running column sums of a band's columns stay in
// L1/L2 (2048 columns x 4 limb planes = 32 KiB at 4096^2 on 2 threads) as
// long as one core runs the band from top to bottom. The former schedule, a
// TBB wavefront whose blocks any thread could take (parallel_for_each with a
// feeder), kept both threads busy but ran each block about 1.45x slower than
// one thread alone does (per-block timing, 4096^2 exact VSM table, quiet
// machine), while two independent one-thread builds at once ran at full
// speed each: not the memory, but (we take it) the column sums and row
// carries moving between the cores' caches with the blocks.
// Band counts (1, 2, 4 per thread) and block heights (8 to 64 rows) changed
// the 2-thread time by less than that (15.1-18.2 ms against a 11.0-11.7 ms
// memcpy of the same bytes). Figures: docs/moment_table.md, "Build schedule".
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <vector>

#include "simd/cpu_backend.h"

namespace penumbra::cpu {
namespace {

constexpr int kBlockRows = 32;
constexpr int kBandQuantum = 64;  // block widths are multiples of every lane count

// Column bands: one per thread (see the schedule notes above).
int band_width(int width)
{
    const int threads = tbb::this_task_arena::max_concurrency();
    const int target = std::max(1, (width + threads - 1) / threads);
    const int rounded = (target + kBandQuantum - 1) / kBandQuantum * kBandQuantum;
    return std::max(kBandQuantum, rounded);
}

// Runs `block(bx, by)` for every block of a bands x rows grid once its left and
// upper neighbours are done: the dependencies of a summed-area table. Each band
// is claimed whole by one thread and run top to bottom, so that its running
// column sums stay in that core's caches; a band waits only for the band on its
// left to be a block ahead. Bands are claimed in order, so the band waited for
// is always being run by a live thread (no deadlock on any number of threads;
// one thread runs the bands one after the other).
template <class BlockFn>
void band_pipeline(int bands, int rows, BlockFn&& block)
{
    std::vector<std::atomic<int>> done(static_cast<std::size_t>(bands));  // blocks finished, per band
    std::atomic<int> next_band{0};
    auto run_bands = [&] {
        for (int bx; (bx = next_band.fetch_add(1)) < bands;)
            for (int by = 0; by < rows; ++by) {
                if (bx > 0)
                    for (int d; (d = done[bx - 1].load(std::memory_order_acquire)) <= by;)
                        done[bx - 1].wait(d, std::memory_order_acquire);
                block(bx, by);
                done[bx].store(by + 1, std::memory_order_release);
                done[bx].notify_all();
            }
    };
    tbb::parallel_for(0, bands, [&](int) { run_bands(); }, tbb::simple_partitioner{});
}

}  // namespace

void CpuBackend::build_moment_table(const Image& depth, MomentTable& table, int* bad_rows)
{
    const int bw = band_width(depth.width());
    const int bands = (depth.width() + bw - 1) / bw;
    const int rows = (depth.height() + kBlockRows - 1) / kBlockRows;
    // One row of column totals: the pipeline carries them down (band_height unused).
    const SatParams p = detail::sat_params(depth, table, 1, 0);
    const std::size_t scratch = std::size_t(p.columns.plane_pitch) * table.planes();
    const std::size_t carries = std::size_t(depth.height()) * table.planes();
    auto run = [&](auto* origin, auto* columns, auto* carry, auto block_fn) {
        band_pipeline(bands, rows, [&](int bx, int by) {
            const int x0 = bx * bw, x1 = std::min(depth.width(), x0 + bw);
            const int y0 = by * kBlockRows, y1 = std::min(depth.height(), y0 + kBlockRows);
            block_fn(depth.plane(0), origin, carry, columns, 0, bad_rows, p, x0, x1, y0, y1);
        });
    };
    if (table.precision() == Precision::Float) {
        std::vector<float> columns(scratch, 0.0f), carry(carries, 0.0f);
        run(table.float_origin(), columns.data(), carry.data(), kernels_.sat_block_float);
    } else {
        std::vector<u32> columns(scratch, 0u), carry(carries, 0u);
        run(table.exact_origin(), columns.data(), carry.data(), kernels_.sat_block_exact);
    }
}

}  // namespace penumbra::cpu
