// The work-group size of every launch (cl/opencl_launch.h, cl/opencl_prime.h).
//
// Fixed, not left to the driver (cl::NullRange), so that a program binary
// made once holds the work-group function every later launch uses. PoCL
// compiles a second, specialised work-group function per kernel at the first
// enqueue of each local size (its cache: <kernel>/<lx>-<ly>-<lz>-goffs0-smallgrid),
// and with cl::NullRange it chose the local size from the image size
// (10-1-1, 40-1-1, 80-40-1 for one 320x240 VSM run), so a binary stored for one
// image size was compiled again for the next. With one local size per shape,
// the binary stored after the first launch (Runtime::build, which launches the
// kernel once before it stores) serves every image size below PoCL's small-grid
// limit (65535 work-items a dimension).
//
// OpenCL 1.2 needs the global size to be a multiple of the local size, so the
// launch rounds it up; the surplus work-items return at once, because every
// entry starts with PN_PIXEL_BEGIN or PN_TASK_BEGIN, which test the bounds
// (cl/dialect_cl.h). The sizes and the kernel speeds they were measured
// against (the 5% rule of issue 10) are in docs/opencl_startup.md.
#pragma once

#include <CL/opencl.hpp>

#include <cstddef>

namespace penumbra::cl_backend {

// Pixels: a row strip, long in x, so that PoCL's work-item loop vectorises
// along the row (16 lanes of AVX-512), as the SIMD backend's strips do.
inline constexpr std::size_t kPixelGroupWidth = 64;
inline constexpr std::size_t kPixelGroupHeight = 1;
// Tasks (a band of rows each): one work-item a group, so that PoCL spreads
// the bands over its threads one by one.
inline constexpr std::size_t kTaskGroupSize = 1;

// `count` rounded up to a multiple of `group`.
inline std::size_t round_up(std::size_t count, std::size_t group) { return (count + group - 1) / group * group; }

inline cl::NDRange pixel_group() { return cl::NDRange(kPixelGroupWidth, kPixelGroupHeight); }
inline cl::NDRange task_group() { return cl::NDRange(kTaskGroupSize); }

}  // namespace penumbra::cl_backend
