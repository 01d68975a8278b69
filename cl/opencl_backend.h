// The OpenCL backend: the embedded program, its kernels, and the launches.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "backend.h"

namespace penumbra::cl_backend {

extern const char* const kEmbeddedProgramSource;  // generated: cl/dialect_cl.h + kernels/*.h

// Options every build of the program uses. Division and sqrt correctly
// rounded, as on the CPU, so that the backends agree to the last bit where
// the operations are the same.
inline constexpr const char* kProgramOptions = "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt";

// The entry points of kernels/registry.h, by name.
std::vector<std::string> registry_kernel_names();

bool has_non_cpu_device();
// non_cpu_only: Auto's request (a GPU or accelerator); else any device, PoCL included.
std::unique_ptr<detail::BackendImpl> make_opencl_backend(bool non_cpu_only);

}  // namespace penumbra::cl_backend
