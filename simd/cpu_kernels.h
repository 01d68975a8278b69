// The CPU function tables: the kernel descriptions compiled once per ISA
// (simd/cpu_kernels.cpp), each table holding the same entry points.
//
// Entries are the descriptions' own functions. `int*` arguments are per-row
// flags that kernels raise for input values they cannot take (see
// pn_flag_any in kernels/dialect.h). Pixel kernels take the strip's
// first pixel (x, y) last; the schedule (simd/cpu_backend.cpp) walks strips of
// `lanes` pixels. Task kernels take their task index last.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "kernels/params.h"

namespace penumbra::cpu {

using u32 = std::uint32_t;

struct CpuKernels {
    const char* isa;  // as `penumbra info` prints it: scalar, sse4.2, avx2, avx512
    int lanes;        // pixels per strip

    // The wavefront schedule's block (not an entry point of the registry).
    void (*sat_block_float)(const float*, float*, float*, float*, int, int*, SatParams, int, int, int, int);
    void (*sat_block_exact)(const float*, u32*, u32*, u32*, int, int*, SatParams, int, int, int, int);

    // The double lanes of the dialect on one strip of `lanes` values (not an
    // entry point; tests/registry_test.cpp, DialectDouble): for lane i,
    // d[i] = to_double(f), d[L + i] = uint_to_double(u), d[2L + i] =
    // (to_double(f) * 3 - 1) / 7 in double; g[i] = double_to_float(to_double(f) * 3),
    // g[L + i] = (to_double(f) > 0.5 as a float mask) ? 1 : 0, g[2L + i] =
    // (f > 0.25 as a double mask) ? 1 : 0, g[3L + i] = any lane's double > 0.75;
    // v[i] = double_to_uint(floor(uint_to_double(u) / 2)).
    void (*dialect_double_probe)(const float* f, const u32* u, double* d, float* g, u32* v);
    // pn_ugather_pair on one strip: first[i] = table[index[i]], second[i] = table[index[i] + 1].
    void (*dialect_gather_pair_probe)(const u32* table, const int* index, u32* first, u32* second);

    // Entry points, in the order of kernels/registry.h.
    void (*sat_bands_float)(const float*, float*, float*, float*, int*, SatParams, int task);
    void (*sat_bands_exact)(const float*, u32*, u32*, u32*, int*, SatParams, int task);
    void (*sat_join_bands_float)(float*, const float*, SatParams, int x, int y);
    void (*sat_join_bands_exact)(u32*, const u32*, SatParams, int x, int y);
    void (*vsm_float)(const float*, const float*, float*, int*, ChebyshevParams, int x, int y);
    void (*vsm_exact)(const u32*, const float*, float*, int*, ChebyshevParams, int x, int y);
    void (*vssm_float)(const float*, const float*, float*, int*, ChebyshevParams, int x, int y);
    void (*vssm_exact)(const u32*, const float*, float*, int*, ChebyshevParams, int x, int y);
    void (*bilateral_full)(const float*, const float*, const float*, const int*, const float*, float*, int*,
                           BilateralParams, int x, int y);
    void (*bilateral_horizontal)(const float*, const float*, const float*, const int*, const float*, float*, int*,
                                 BilateralParams, int x, int y);
    void (*bilateral_vertical)(const float*, const float*, const float*, const int*, const float*, float*,
                               BilateralParams, int x, int y);
    // The SIMD schedule's spans of kernels/bilateral.h (not registry entries):
    // the strips from x0 to x1 of rows [y0, y1).
    void (*bilateral_full_span)(const float*, const float*, const float*, const int*, const float*, float*, int*,
                                BilateralParams, int x0, int x1, int y0, int y1);
    void (*bilateral_horizontal_span)(const float*, const float*, const float*, const int*, const float*, float*,
                                      int*, BilateralParams, int x0, int x1, int y0, int y1);
    void (*bilateral_vertical_span)(const float*, const float*, const float*, const int*, const float*, float*,
                                    BilateralParams, int x0, int x1, int y0, int y1);
    void (*sdf_grid)(const float*, const float*, const float*, float*, int*, SdfParams, int x, int y);
    void (*sdf_analytic)(const float*, const float*, const float*, float*, int*, SdfParams, int x, int y);
    void (*encoded_bands_float)(const float*, float*, float*, int*, EncodedSatParams, int task);
    void (*encoded_bands_exact)(const float*, u32*, u32*, int*, EncodedSatParams, int task);
    void (*msm_float)(const float*, const float*, float*, int*, MomentParams, int x, int y);
    void (*msm_exact)(const u32*, const float*, float*, int*, MomentParams, int x, int y);
    void (*msm_soft_float)(const float*, const float*, float*, int*, MomentParams, int x, int y);
    void (*msm_soft_exact)(const u32*, const float*, float*, int*, MomentParams, int x, int y);
    void (*evsm_float)(const float*, const float*, float*, int*, MomentParams, int x, int y);
    void (*evsm_exact)(const u32*, const float*, float*, int*, MomentParams, int x, int y);
};

extern const CpuKernels kernels_scalar;
extern const CpuKernels kernels_sse4_2;
extern const CpuKernels kernels_avx2;
extern const CpuKernels kernels_avx512;

// ISAs this CPU can run, best last (never includes "scalar").
std::vector<std::string_view> supported_isas();
// The table for an ISA name ("scalar", "sse4.2", "avx2", "avx512"); throws
// Error(InvalidArgument) for an unknown name, Error(Unavailable) for one this CPU cannot run.
const CpuKernels& kernels_for(std::string_view isa);
// The ISA the SIMD backend uses: PENUMBRA_SIMD_ISA if set (checked), else the best.
std::string_view chosen_isa();

}  // namespace penumbra::cpu
