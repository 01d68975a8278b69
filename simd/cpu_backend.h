// The CPU backend (SIMD and Scalar): the schedule around simd/cpu_kernels.
// One class: the generic lookup of every lookup-shaped entry in
// simd/cpu_lookup.cpp, and each schedule that differs (table builds,
// bilateral, SDF) in its family's file (simd/cpu_<family>.cpp).
#pragma once

#include <memory>

#include "host/backend/backend.h"
#include "simd/cpu_kernels.h"

namespace penumbra::cpu {

class CpuBackend final : public detail::BackendImpl {
public:
    explicit CpuBackend(const CpuKernels& kernels) : kernels_(kernels) {}

    std::string description() const override;
    std::string isa() const override { return kernels_.isa; }

    PN_BACKEND_OPERATIONS(, override);  // host/backend/backend.h

private:
    const CpuKernels& kernels_;
};

std::unique_ptr<detail::BackendImpl> make_cpu_backend(const CpuKernels& kernels);

}  // namespace penumbra::cpu
