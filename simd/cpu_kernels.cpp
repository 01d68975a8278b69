// The kernel descriptions compiled for one instruction set.
//
// CMake compiles this file once per ISA of simd/isa_list.h
// (cmake/penumbra_kernels.cmake) with that ISA's flags and its generated
// penumbra_this_isa.h; each copy puts the descriptions in its own namespace
// and exports one CpuKernels table, its entries filled from the kernel table:
// an entry of kernels/kernel_table.h that no description defines does not
// compile.
#include <immintrin.h>

#include <atomic>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "kernels/params.h"
#include "penumbra_this_isa.h"  // PN_ISA_<id>, PN_ISA_NAMESPACE, PN_ISA_LABEL, PN_TABLE_NAME, PN_ARCH
#include "simd/cpu_kernels.h"

#if !defined(PN_ISA_scalar)
#include <xsimd/xsimd.hpp>
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
// The probes' int lanes stored as they are.
#if defined(PN_ISA_scalar)
static void probe_store_int(int* out, pn_int v) { *out = v; }
#else
static void probe_store_int(int* out, pn_int v) { v.store_unaligned(out); }
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
    pn_ugather_pair(table, pn_uint_to_index(pn_uload(reinterpret_cast<const u32*>(index), dims, 0, 0)), &a, &b);
    pn_ustore(first, dims, 0, 0, a);
    pn_ustore(second, dims, 0, 0, b);
}
static void dialect_upair_probe(const u32* table, const int* index_a, const int* index_b, double* joined)
{
    const pn_dims dims{kLanes, 1, kLanes, kLanes};
    const auto lanes = [&](const int* index) {
        return pn_uint_to_index(pn_uload(reinterpret_cast<const u32*>(index), dims, 0, 0));
    };
    probe_store(joined, pn_upair_join(pn_ugather_upair(table, lanes(index_a)) - pn_ugather_upair(table, lanes(index_b))));
}

// The index lanes (simd/cpu_kernels.h, dialect_index_probe).
static void dialect_index_probe(const u32* a, const u32* b, float* less, int* selected)
{
    const pn_dims dims{kLanes, 1, kLanes, kLanes};
    const pn_int ia = pn_uint_to_index(pn_uload(a, dims, 0, 0)), ib = pn_uint_to_index(pn_uload(b, dims, 0, 0));
    const pn_mask m = pn_iless(ia, ib);
    pn_store(less, dims, 0, 0, pn_select(pn_and(m, pn_float(1.0f) > 0.0f), 1.0f, 0.0f));
    probe_store_int(selected, pn_iselect(m, ia, ib));
}
}  // namespace penumbra::cpu::PN_ISA_NAMESPACE

namespace penumbra::cpu {
namespace isa = PN_ISA_NAMESPACE;

static constexpr CpuKernels make_table()
{
    CpuKernels t{};
    t.isa = PN_ISA_LABEL;
    t.lanes = isa::kLanes;
#define PN_CPU_SET_ENTRY(family, name, shape, Params, buffers) t.name = &isa::name;
    PN_KERNEL_TABLE(PN_CPU_SET_ENTRY)
#undef PN_CPU_SET_ENTRY
    t.sat_block_float = &isa::sat_block_float_fenced;
    t.sat_block_exact = &isa::sat_block_exact_fenced;
    t.bilateral_full_span = &isa::bilateral_full_span;
    t.bilateral_horizontal_span = &isa::bilateral_horizontal_span;
    t.bilateral_vertical_span = &isa::bilateral_vertical_span;
    t.depth_convert_rows = &isa::depth_convert_rows;
    t.receiver_v_bounds = &isa::receiver_v_bounds;
    t.dialect_double_probe = &isa::dialect_double_probe;
    t.dialect_gather_pair_probe = &isa::dialect_gather_pair_probe;
    t.dialect_upair_probe = &isa::dialect_upair_probe;
    t.dialect_index_probe = &isa::dialect_index_probe;
    return t;
}

extern const CpuKernels PN_TABLE_NAME;
// constinit: other translation units read the tables during their static
// initialisation (test registration), so they must not wait for dynamic init.
constinit const CpuKernels PN_TABLE_NAME = make_table();
}  // namespace penumbra::cpu
