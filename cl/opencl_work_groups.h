// The work-group size of every launch (cl/opencl_launch.h, cl/opencl_prime.h).
//
// Fixed per device, not left to the driver (cl::NullRange), so that a program
// binary made once holds the work-group function every later launch uses.
// PoCL compiles a second, specialised work-group function per kernel at the
// first enqueue of each local size (its cache: <kernel>/<lx>-<ly>-<lz>-goffs0-smallgrid),
// and with cl::NullRange it chose the local size from the image size (10-1-1,
// 40-1-1, 80-40-1 in one 320x240 VSM run; 120-1-1 at 1920x1080; 512-8-1 at
// 4096^2), so a binary stored for one image size was compiled again for the
// next. With one local size per shape, the binary stored after the first
// launch (Runtime::build launches the kernel once before it stores it) serves
// every image size below PoCL's small-grid limit (65535 work-items a dimension).
//
// OpenCL 1.2 needs the global size to be a multiple of the local size, so the
// launch rounds it up; the surplus work-items return at once, because every
// entry starts with PN_PIXEL_BEGIN or PN_TASK_BEGIN, which test the bounds
// (cl/dialect_cl.h). The sizes, and the kernel speeds they were measured with
// against PoCL's own choice (the 5% rule of issue 10): docs/opencl_startup.md.
#pragma once

#include <CL/opencl.hpp>

#include <cstddef>
#include <string>

namespace penumbra::cl_backend {

struct WorkGroups {
    std::size_t pixel_width, pixel_height;  // per pixel: a tile, long in x
    std::size_t task;                       // per task (a band of rows)

    cl::NDRange pixel() const { return cl::NDRange(pixel_width, pixel_height); }
    cl::NDRange tasks() const { return cl::NDRange(task); }
};

// Pixels: 512x8 where a group may hold 4096 work-items (PoCL's CPU device:
// the size PoCL itself chose for the 4096^2 benchmarks, so those run PoCL's
// own schedule), else 64x4, which nearly every GPU allows. Long in x, so that
// PoCL's work-item loop vectorises along the row. Tasks: 64 a group (PoCL's
// choice for 128 bands), so that its loop vectorises across the bands.
inline WorkGroups work_groups_for(std::size_t max_work_group_size)
{
    if (max_work_group_size >= 4096) return {512, 8, 64};
    return {64, 4, 64};
}

// "512x8,64": the sizes as the program cache's key holds them.
inline std::string to_string(const WorkGroups& g)
{
    return std::to_string(g.pixel_width) + "x" + std::to_string(g.pixel_height) + "," + std::to_string(g.task);
}

// `count` rounded up to a multiple of `group`.
inline std::size_t round_up(std::size_t count, std::size_t group) { return (count + group - 1) / group * group; }

}  // namespace penumbra::cl_backend
