#include "simd/cpu_backend.h"

#include <string>

namespace penumbra::cpu {

std::string CpuBackend::description() const
{
    if (std::string(kernels_.isa) == "scalar") return "scalar (1 lane)";
    return "simd (" + std::string(kernels_.isa) + ", " + std::to_string(kernels_.lanes) + " lanes)";
}

std::unique_ptr<detail::BackendImpl> make_cpu_backend(const CpuKernels& kernels)
{
    return std::make_unique<CpuBackend>(kernels);
}

}  // namespace penumbra::cpu
