// CPU launch of the summed-area table build (kernels/moment_table.h): a
// wavefront of blocks per group of values, a special schedule (not
// launch_tasks over sat_bands_*): it writes the table once, where the banded
// build (OpenCL's) reads and rewrites the rows below its first band in the
// join pass. (The banded build was not timed on the CPU against it.)
//
// Schedule notes: the table is written once, streamed past the caches
// (pn_store_stream); the running column sums of a band's columns stay in
// L1/L2. Threads split the values first: each value has planes, row carries
// and column sums of its own, so on 2 threads a VSM table's z and z^2 are
// two chains of full-width blocks, no hand-over between threads and no
// column split (on the former Intel VM a 2048-column band cost 1.26x per
// texel even on one thread, and the banded 2-thread build reached 0.70-0.80
// of memcpy). The price: each group reads and converts the map itself (1.1-
// 1.45x the work of one group on this Zen 5 VM, loaded), so on two threads
// sharing one core it was 1.18x slower than the bands; its 2-core figure is
// not yet measured (docs/moment_table.md, "Session 17"). Only with more
// threads than groups are the groups cut into column bands again, one per
// thread of the group (multiples of 64 columns), 32-row blocks: fewer,
// longer bands mean fewer hand-offs, short blocks fill the wavefront quickly
// (measured in docs/benchmarks.md).
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

// Groups of values: as many as threads, of equal size (values / groups is 1,
// 2 or 4: the block functions' literal counts). A group holds an EVSM warp
// with its square, which is formed from it: split, the square's group would
// compute the exponential again (kernels/moment_table.h, texel_values_from).
int value_groups(const MomentTable& table, int threads)
{
    const int values = table.moments();
    const int units = table.values().kind == PN_TABLE_EVSM ? values / 2 : values;
    int groups = std::clamp(threads, 1, units);
    while (units % groups != 0) --groups;
    return groups;
}

// Column bands of a group: one per thread of the group (see the notes above).
int band_width(int width, int threads)
{
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
    int group, bx, by;
};

// Runs `block(group, bx, by)` for every block of `groups` independent bands x
// rows grids once its left and upper neighbours in its group are done: the
// dependencies of a summed-area table.
template <class BlockFn>
void wavefront(int groups, int bands, int rows, BlockFn&& block)
{
    const std::size_t per_group = std::size_t(bands) * rows;
    std::vector<std::atomic<int>> pending(per_group * groups);
    auto slot = [&](int g, int bx, int by) { return g * per_group + std::size_t(by) * bands + bx; };
    for (int g = 0; g < groups; ++g)
        for (int by = 0; by < rows; ++by)
            for (int bx = 0; bx < bands; ++bx) pending[slot(g, bx, by)] = (bx > 0) + (by > 0);
    auto release = [&](int g, int bx, int by, tbb::feeder<Block>& feeder) {
        if (bx < bands && by < rows && --pending[slot(g, bx, by)] == 0) feeder.add({g, bx, by});
    };
    std::vector<Block> start;
    for (int g = 0; g < groups; ++g) start.push_back({g, 0, 0});
    tbb::parallel_for_each(start.begin(), start.end(), [&](const Block& b, tbb::feeder<Block>& feeder) {
        block(b.group, b.bx, b.by);
        release(b.group, b.bx + 1, b.by, feeder);
        release(b.group, b.bx, b.by + 1, feeder);
    });
}

}  // namespace

void CpuBackend::build_moment_table(const Image& depth, MomentTable& table, int* bad_rows)
{
    const int threads = tbb::this_task_arena::max_concurrency();
    const int groups = value_groups(table, threads);
    const int values = table.moments() / groups;
    const int bw = band_width(depth.width(), (threads + groups - 1) / groups);
    const int bands = (depth.width() + bw - 1) / bw;
    const int rows = (depth.height() + kBlockRows - 1) / kBlockRows;
    // One row of column totals: the wavefront carries them down (band_height unused).
    const SatParams p = detail::sat_params(depth, table, 1, 0);
    const std::size_t scratch = std::size_t(p.columns.plane_pitch) * table.planes();
    const std::size_t carries = std::size_t(depth.height()) * table.planes();
    auto run = [&](auto* origin, auto* columns, auto* carry, auto block_fn) {
        wavefront(groups, bands, rows, [&](int group, int bx, int by) {
            const int x0 = bx * bw, x1 = std::min(depth.width(), x0 + bw);
            const int y0 = by * kBlockRows, y1 = std::min(depth.height(), y0 + kBlockRows);
            block_fn(depth.plane(0), origin, carry, columns, 0, bad_rows, p, group * values, values, x0, x1, y0, y1);
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
