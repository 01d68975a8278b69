// The CPU backend (SIMD and Scalar): the schedule around simd/cpu_kernels.
#pragma once

#include <memory>

#include "backend.h"
#include "simd/cpu_kernels.h"

namespace penumbra::cpu {

std::unique_ptr<detail::BackendImpl> make_cpu_backend(const CpuKernels& kernels);

}  // namespace penumbra::cpu
