// The CPU backend (SIMD and Scalar): the schedule around simd/cpu_kernels.
// One class; each kernel family implements its methods in its own file
// (simd/cpu_<family>.cpp), next to its launches.
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

    // simd/cpu_moment_table.cpp
    void build_moment_table(const Image& depth, MomentTable& table, int* bad_rows) override;
    // simd/cpu_chebyshev.cpp
    void chebyshev(detail::ChebyshevMethod method, const MomentTable& table, const Image& receivers,
                   const ChebyshevParams& params, Image& out, int* bad_rows) override;
    // simd/cpu_bilateral.cpp
    void cross_bilateral(const Image& mask, const Image& guide, const Image* normals, const std::vector<int>& taps,
                         const std::vector<float>& weights, bool separable, const BilateralParams& params, Image& out,
                         int* bad_rows) override;
    // simd/cpu_sdf.cpp
    void sdf_grid(const float* data, std::size_t floats, const Image& positions, const Image& normals,
                  const SdfParams& params, Image& out, int* bad_rows) override;
    void sdf_analytic(const float* data, std::size_t floats, const Image& positions, const Image& normals,
                      const SdfParams& params, Image& out, int* bad_rows) override;
    // simd/cpu_moments.cpp
    void build_encoded_table(const Image& depth, const EncodedSatParams& params, MomentTable& table,
                             int* bad_rows) override;
    void moment_lookup(MomentMethod method, const MomentTable& table, const Image& receivers,
                       const MomentParams& params, Image& out, int* bad_rows) override;

private:
    const CpuKernels& kernels_;
};

std::unique_ptr<detail::BackendImpl> make_cpu_backend(const CpuKernels& kernels);

}  // namespace penumbra::cpu
