// Schedules shared by the CPU launches of every kernel family: the one
// per-pixel launch and the one task launch of a kernel-table entry.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "penumbra/image.h"
#include "simd/cpu_kernels.h"

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

// Pixel entry K over a width x height grid: args are its buffers and Params,
// in the order of its kernel-table entry (the signature checks them).
template <KernelId K, class... Args>
void launch_pixels(const CpuKernels& kernels, int width, int height, const Args&... args)
{
    static_assert(detail::KernelTraits<K>::shape == KernelShape::pixel, "launch_tasks runs a task entry");
    const CpuEntry<K> kernel = entry<K>(kernels);
    for_each_strip(width, height, kernels.lanes, [&](int x, int y) { kernel(args..., x, y); });
}

// Task entry K for tasks 0 .. tasks - 1, one TBB task each.
template <KernelId K, class... Args>
void launch_tasks(const CpuKernels& kernels, int tasks, const Args&... args)
{
    static_assert(detail::KernelTraits<K>::shape == KernelShape::task, "launch_pixels runs a pixel entry");
    const CpuEntry<K> kernel = entry<K>(kernels);
    tbb::parallel_for(0, tasks, [&](int task) { kernel(args..., task); });
}

}  // namespace penumbra::cpu
