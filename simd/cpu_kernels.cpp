// The kernel descriptions compiled for one instruction set.
//
// CMake compiles this file once per ISA (cmake/penumbra_kernels.cmake) with
// PN_ISA_<name> defined and that ISA's -m flags; each copy puts the
// descriptions in its own namespace and exports one CpuKernels table.
#include <immintrin.h>

#include <atomic>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "kernels/params.h"
#include "simd/cpu_kernels.h"

#if defined(PN_ISA_scalar)
#define PN_ISA_NAMESPACE scalar
#define PN_ISA_LABEL "scalar"
#define PN_TABLE_NAME kernels_scalar
#else
#include <xsimd/xsimd.hpp>
#if defined(PN_ISA_sse4_2)
#define PN_ARCH xsimd::sse4_2
#define PN_ISA_NAMESPACE sse4_2
#define PN_ISA_LABEL "sse4.2"
#define PN_TABLE_NAME kernels_sse4_2
#elif defined(PN_ISA_avx2)
#define PN_ARCH xsimd::fma3<xsimd::avx2>
#define PN_ISA_NAMESPACE avx2
#define PN_ISA_LABEL "avx2"
#define PN_TABLE_NAME kernels_avx2
#elif defined(PN_ISA_avx512)
#define PN_ARCH xsimd::avx512bw
#define PN_ISA_NAMESPACE avx512
#define PN_ISA_LABEL "avx512"
#define PN_TABLE_NAME kernels_avx512
#else
#error "define one of PN_ISA_scalar, PN_ISA_sse4_2, PN_ISA_avx2, PN_ISA_avx512"
#endif
#endif

namespace penumbra::cpu::PN_ISA_NAMESPACE {
#if defined(PN_ISA_scalar)
#include "simd/dialect_scalar.h"
#else
#include "simd/dialect_simd.h"
#endif
#include "penumbra_kernel_includes.h"

// Streaming stores are weakly ordered: fence them before the block is
// reported done, so that whichever thread reads the table sees them.
static void sat_block_float_fenced(const float* depth, float* table, float* carry, float* columns, int column_row,
                                   int* bad_rows, SatParams p, int x0, int x1, int y0, int y1)
{
    sat_block_float(depth, table, carry, columns, column_row, bad_rows, p, x0, x1, y0, y1);
    _mm_sfence();
}

static void sat_block_exact_fenced(const float* depth, u32* table, u32* carry, u32* columns, int column_row,
                                   int* bad_rows, SatParams p, int x0, int x1, int y0, int y1)
{
    sat_block_exact(depth, table, carry, columns, column_row, bad_rows, p, x0, x1, y0, y1);
    _mm_sfence();
}
// The probes' index lanes, loaded as uint and reinterpreted.
#if defined(PN_ISA_scalar)
static pn_int pn_uint_to_int_lanes(pn_uint v) { return pn_int(v); }
#else
static pn_int pn_uint_to_int_lanes(pn_uint v) { return xsimd::bitwise_cast<pn_int>(v); }
#endif

// One strip of the double lanes (simd/cpu_kernels.h, dialect_double_probe).
#if defined(PN_ISA_scalar)
static void probe_store(double* out, pn_double d) { *out = d; }
#else
static void probe_store(double* out, pn_double d)
{
    d.lo.store_unaligned(out);
    d.hi.store_unaligned(out + kLanes / 2);
}
#endif
static void dialect_double_probe(const float* f, const u32* u, double* d, float* g, u32* v)
{
    const pn_dims dims{kLanes, 1, kLanes, kLanes};
    const pn_float x = pn_load(f, dims, 0, 0);
    const pn_uint n = pn_uload(u, dims, 0, 0);
    const pn_double dx = pn_to_double(x);
    probe_store(d, dx);
    probe_store(d + kLanes, pn_uint_to_double(n));
    probe_store(d + 2 * kLanes, (dx * 3.0 - 1.0) / 7.0);
    pn_store(g, dims, 0, 0, pn_double_to_float(dx * 3.0));
    pn_store(g + kLanes, dims, 0, 0, pn_select(pn_dmask_to_mask(dx > 0.5), 1.0f, 0.0f));
    pn_store(g + 2 * kLanes, dims, 0, 0, pn_double_to_float(pn_dselect(pn_mask_to_dmask(x > 0.25f), 1.0, 0.0)));
    pn_store(g + 3 * kLanes, dims, 0, 0, pn_dany(dx > 0.75) ? 1.0f : 0.0f);
    pn_ustore(v, dims, 0, 0, pn_double_to_uint(pn_dfloor(pn_uint_to_double(n) / 2.0)));
}
static void dialect_gather_pair_probe(const u32* table, const int* index, u32* first, u32* second)
{
    const pn_dims dims{kLanes, 1, kLanes, kLanes};
    pn_uint a, b;
    pn_ugather_pair(table, pn_uint_to_int_lanes(pn_uload(reinterpret_cast<const u32*>(index), dims, 0, 0)), &a, &b);
    pn_ustore(first, dims, 0, 0, a);
    pn_ustore(second, dims, 0, 0, b);
}
}  // namespace penumbra::cpu::PN_ISA_NAMESPACE

namespace penumbra::cpu {
namespace isa = PN_ISA_NAMESPACE;

// Filled by name, not by position, so that each kernel family adds its own
// lines without caring about the others' order.
static constexpr CpuKernels make_table()
{
    CpuKernels t{};
    t.isa = PN_ISA_LABEL;
    t.lanes = isa::kLanes;
    t.sat_block_float = &isa::sat_block_float_fenced;
    t.sat_block_exact = &isa::sat_block_exact_fenced;
    t.dialect_double_probe = &isa::dialect_double_probe;
    t.dialect_gather_pair_probe = &isa::dialect_gather_pair_probe;
    t.sat_bands_float = &isa::sat_bands_float;
    t.sat_bands_exact = &isa::sat_bands_exact;
    t.sat_join_bands_float = &isa::sat_join_bands_float;
    t.sat_join_bands_exact = &isa::sat_join_bands_exact;
    t.vsm_float = &isa::vsm_float;
    t.vsm_exact = &isa::vsm_exact;
    t.vssm_float = &isa::vssm_float;
    t.vssm_exact = &isa::vssm_exact;
    t.bilateral_full = &isa::bilateral_full;
    t.bilateral_horizontal = &isa::bilateral_horizontal;
    t.bilateral_vertical = &isa::bilateral_vertical;
    t.bilateral_full_span = &isa::bilateral_full_span;
    t.bilateral_horizontal_span = &isa::bilateral_horizontal_span;
    t.bilateral_vertical_span = &isa::bilateral_vertical_span;
    t.sdf_grid = &isa::sdf_grid;
    t.sdf_analytic = &isa::sdf_analytic;
    t.encoded_bands_float = &isa::encoded_bands_float;
    t.encoded_bands_exact = &isa::encoded_bands_exact;
    t.msm_float = &isa::msm_float;
    t.msm_exact = &isa::msm_exact;
    t.msm_soft_float = &isa::msm_soft_float;
    t.msm_soft_exact = &isa::msm_soft_exact;
    t.evsm_float = &isa::evsm_float;
    t.evsm_exact = &isa::evsm_exact;
    return t;
}

extern const CpuKernels PN_TABLE_NAME;
// constinit: other translation units read the tables during their static
// initialisation (test registration), so they must not wait for dynamic init.
constinit const CpuKernels PN_TABLE_NAME = make_table();
}  // namespace penumbra::cpu
