// Schedules shared by the CPU launches of every kernel family.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace penumbra::cpu {

inline constexpr int kRowsPerTask = 8;  // grain of per-pixel kernels

// Calls kernel(x, y) for every strip of `lanes` pixels of a width x height
// grid, rows spread over TBB's threads.
template <class Kernel>
void for_each_strip(int width, int height, int lanes, Kernel&& kernel)
{
    tbb::parallel_for(tbb::blocked_range<int>(0, height, kRowsPerTask), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < width; x += lanes) kernel(x, y);
    });
}

}  // namespace penumbra::cpu
