// CPU launch of the summed-area table build (kernels/moment_table.h): a
// wavefront of blocks, a special schedule (not launch_tasks over sat_bands_*):
// it writes the table once, at 93-101% of a memcpy of its bytes (below), where
// the banded build (OpenCL's) reads and rewrites the rows below its first band
// in the join pass. (The banded build was not timed on the CPU against it.)
//
// Schedule notes: the table is written once, streamed past the caches
// (pn_store_stream); the running column sums of a band's columns stay in
// L1/L2 (2048 columns x 2 moments = 16 KiB at 4096^2 on 2 threads).
// Measured on the 2-core AVX-512 VM, 4096^2, float, 2 moments, 2 threads, in
// share of a 2-thread memcpy of the same bytes (3 runs each): one band per
// thread and 32-row blocks 93-101%; two bands per thread and 64-row blocks
// 74-87%. Fewer, longer bands mean fewer hand-offs between threads; short
// blocks fill the wavefront quickly. Figures: docs/benchmarks.md.
#include <tbb/parallel_for_each.h>
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

// The column sums and row carries start on a cache line, so that a strip of
// columns is one line (not a load split over two) and two bands never write
// the same line: a std::vector's 16-byte start put the first columns of each
// band in a line with the last columns of the band on its left, which both
// threads wrote on every row.
template <class T>
T* lines_of(AlignedBuffer& buffer)
{
    return reinterpret_cast<T*>(buffer.data());
}

struct Block {
    int bx, by;
};

// Runs `block(bx, by)` for every block of a bands x rows grid once its left and
// upper neighbours are done: the dependencies of a summed-area table.
template <class BlockFn>
void wavefront(int bands, int rows, BlockFn&& block)
{
    std::vector<std::atomic<int>> pending(std::size_t(bands) * rows);
    for (int by = 0; by < rows; ++by)
        for (int bx = 0; bx < bands; ++bx) pending[std::size_t(by) * bands + bx] = (bx > 0) + (by > 0);
    auto release = [&](int bx, int by, tbb::feeder<Block>& feeder) {
        if (bx < bands && by < rows && --pending[std::size_t(by) * bands + bx] == 0) feeder.add({bx, by});
    };
    std::vector<Block> start{{0, 0}};
    tbb::parallel_for_each(start.begin(), start.end(), [&](const Block& b, tbb::feeder<Block>& feeder) {
        block(b.bx, b.by);
        release(b.bx + 1, b.by, feeder);
        release(b.bx, b.by + 1, feeder);
    });
}

}  // namespace

void CpuBackend::build_moment_table(const Image& depth, MomentTable& table, int* bad_rows)
{
    const int bw = band_width(depth.width());
    const int bands = (depth.width() + bw - 1) / bw;
    const int rows = (depth.height() + kBlockRows - 1) / kBlockRows;
    // One row of column totals: the wavefront carries them down (band_height unused).
    const SatParams p = detail::sat_params(depth, table, 1, 0);
    const std::size_t scratch = std::size_t(p.columns.plane_pitch) * table.planes();
    const std::size_t carries = std::size_t(depth.height()) * table.planes();
    auto run = [&](auto* origin, auto* columns, auto* carry, auto block_fn) {
        wavefront(bands, rows, [&](int bx, int by) {
            const int x0 = bx * bw, x1 = std::min(depth.width(), x0 + bw);
            const int y0 = by * kBlockRows, y1 = std::min(depth.height(), y0 + kBlockRows);
            block_fn(depth.plane(0), origin, carry, columns, 0, bad_rows, p, x0, x1, y0, y1);
        });
    };
    // Zeroed and on cache lines (AlignedBuffer): see lines_of.
    static_assert(sizeof(float) == sizeof(u32));
    AlignedBuffer columns(scratch * sizeof(u32)), carry(carries * sizeof(u32));
    if (table.precision() == Precision::Float)
        run(table.float_origin(), lines_of<float>(columns), lines_of<float>(carry), kernels_.sat_block_float);
    else
        run(table.exact_origin(), lines_of<u32>(columns), lines_of<u32>(carry), kernels_.sat_block_exact);
}

}  // namespace penumbra::cpu
