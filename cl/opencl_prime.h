// One empty launch of a freshly built program's kernel, before its binary is
// stored (Runtime::build), so that the binary holds the work-group function
// every later launch of it uses.
//
// PoCL compiles a kernel's work-group function specialised for the local size
// at the first enqueue (cl/opencl_work_groups.h), and serialises a program's
// binary once, at the first CL_PROGRAM_BINARIES query: read right after the
// build, the binary lacks that function and a run from it compiles it again
// (about 0.3 s a kernel here, docs/opencl_startup.md). The empty launch is one
// work-group of the shape's fixed local size with every buffer a small dummy,
// the parameters zeroed and, for a task entry, a task count of 0, so that
// every work-item returns in PN_PIXEL_BEGIN / PN_TASK_BEGIN (a zero width or
// count; kernels/dialect.h requires the begin macro first).
#pragma once

#include <CL/opencl.hpp>

#include "cl/opencl_work_groups.h"
#include "host/backend/kernel_id.h"

namespace penumbra::cl_backend {

// Enqueues the empty launch of `id`, the one kernel of `program`, and waits
// for it. Throws cl::Error as the OpenCL calls do.
void prime_kernel(const cl::Context& context, const cl::CommandQueue& queue, const cl::Program& program,
                  detail::KernelId id, const WorkGroups& groups);

}  // namespace penumbra::cl_backend
