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

    // simd/cpu_lookup.cpp: every lookup-shaped entry
    void receiver_lookup(KernelId kernel, const detail::LookupSource& source, const Image& receivers,
                         const void* params, Image& out, int* bad_rows) override;
    // simd/cpu_moment_table.cpp
    void build_moment_table(const Image& depth, MomentTable& table, int* bad_rows) override;
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

private:
    const CpuKernels& kernels_;
};

std::unique_ptr<detail::BackendImpl> make_cpu_backend(const CpuKernels& kernels);

}  // namespace penumbra::cpu
