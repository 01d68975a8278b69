// The CPU function tables: the kernel descriptions compiled once per ISA
// (simd/cpu_kernels.cpp, the ISAs of simd/isa_list.h), each table holding the
// same entry points.
//
// The entry members come from the kernel table (kernels/kernel_table.h):
// one member per entry, named as the entry, its signature derived from
// KernelTraits (the buffers, then Params, then the strip's first pixel x, y
// for a pixel entry or the task index for a task entry). `int*` buffers are
// per-row flags that kernels raise for input values they cannot take (see
// pn_flag_any in kernels/dialect.h). The launches (simd/cpu_schedule.h) name an
// entry by KernelId and reach its member through CpuEntryMember.
#pragma once

#include <cstdint>
#include <string_view>
#include <tuple>
#include <vector>

#include "host/backend/kernel_id.h"
#include "kernels/params.h"
#include "penumbra_cpu_isas.h"  // PN_CPU_ISAS, generated from simd/isa_list.h

namespace penumbra::cpu {

using u32 = std::uint32_t;
using detail::KernelId;
using detail::KernelShape;

namespace table_detail {
template <KernelShape Shape, class Params, class Buffers>
struct EntrySignature;
template <class Params, class... Buffers>
struct EntrySignature<KernelShape::pixel, Params, std::tuple<Buffers...>> {
    using type = void (*)(Buffers..., Params, int x, int y);
};
template <class Params, class... Buffers>
struct EntrySignature<KernelShape::task, Params, std::tuple<Buffers...>> {
    using type = void (*)(Buffers..., Params, int task);
};
}  // namespace table_detail

// The CPU signature of entry K.
template <KernelId K>
using CpuEntry = typename table_detail::EntrySignature<detail::KernelTraits<K>::shape,
                                                       typename detail::KernelTraits<K>::Params,
                                                       typename detail::KernelTraits<K>::Buffers>::type;

struct CpuKernels {
    const char* isa;  // as `penumbra info` prints it: scalar, sse4.2, avx2, avx512
    int lanes;        // pixels per strip

    // The entry points of kernels/kernel_table.h, in its order.
#define PN_CPU_ENTRY_MEMBER(family, name, shape, Params, buffers) CpuEntry<KernelId::name> name;
    PN_KERNEL_TABLE(PN_CPU_ENTRY_MEMBER)
#undef PN_CPU_ENTRY_MEMBER

    // Not entry points: the helpers that only the CPU schedules call, a short
    // hand list (each set in simd/cpu_kernels.cpp, checked in tests/kernel_table_test.cpp).

    // The wavefront schedule's block of kernels/moment_table.h (simd/cpu_moment_table.cpp).
    void (*sat_block_float)(const float*, float*, float*, float*, int, int*, SatParams, int, int, int, int);
    void (*sat_block_exact)(const float*, u32*, u32*, u32*, int, int*, SatParams, int, int, int, int);
    // The spans of kernels/bilateral.h (simd/cpu_bilateral.cpp): the strips
    // from x0 to x1 of rows [y0, y1).
    void (*bilateral_full_span)(const float*, const float*, const float*, const int*, const float*, float*, int*,
                                BilateralParams, int x0, int x1, int y0, int y1);
    void (*bilateral_horizontal_span)(const float*, const float*, const float*, const int*, const float*, float*,
                                      int*, BilateralParams, int x0, int x1, int y0, int y1);
    void (*bilateral_vertical_span)(const float*, const float*, const float*, const int*, const float*, float*,
                                    BilateralParams, int x0, int x1, int y0, int y1);
    // Rows [y0, y1) of a stored map converted to normalised depth into rows
    // 0 .. y1 - y0 of the second (kernels/depth_convention.h; simd/cpu_direct_sums.cpp).
    void (*depth_convert_rows)(const float*, pn_dims, float*, pn_dims, DepthConversion, int y0, int y1);
    // The lowest and highest clamped v of receiver rows [y0, y1), per lane of
    // one strip (kernels/box_window.h; simd/cpu_direct_sums.cpp).
    void (*receiver_v_bounds)(const float*, pn_dims, int y0, int y1, float* low, float* high, pn_dims strip);
    // The double lanes of the dialect on one strip of `lanes` values
    // (tests/kernel_table_test.cpp, DialectDouble): for lane i,
    // d[i] = to_double(f), d[L + i] = uint_to_double(u), d[2L + i] =
    // (to_double(f) * 3 - 1) / 7 in double; g[i] = double_to_float(to_double(f) * 3),
    // g[L + i] = (to_double(f) > 0.5 as a float mask) ? 1 : 0, g[2L + i] =
    // (f > 0.25 as a double mask) ? 1 : 0, g[3L + i] = any lane's double > 0.75;
    // v[i] = double_to_uint(floor(uint_to_double(u) / 2)).
    void (*dialect_double_probe)(const float* f, const u32* u, double* d, float* g, u32* v);
    // pn_ugather_pair on one strip: first[i] = table[index[i]], second[i] = table[index[i] + 1].
    void (*dialect_gather_pair_probe)(const u32* table, const int* index, u32* first, u32* second);
    // pn_upair on one strip: joined[i] = pn_upair_join(gather(index_a[i]) - gather(index_b[i])), the
    // difference of (table[a], table[a + 1]) and (table[b], table[b + 1]), each part wrapping, joined.
    void (*dialect_upair_probe)(const u32* table, const int* index_a, const int* index_b, double* joined);
    // The index lanes on one strip: less[i] = (int(a[i]) < int(b[i])) as a
    // float mask ? 1 : 0 (pn_iless combined with a float condition),
    // selected[i] = that ? a[i] : b[i] (pn_iselect), a and b read as
    // pn_uint_to_index of uint lanes.
    void (*dialect_index_probe)(const u32* a, const u32* b, float* less, int* selected);
};

// The member of CpuKernels that holds entry K: kernels.*CpuEntryMember<K>::pointer.
template <KernelId K>
struct CpuEntryMember;
#define PN_CPU_ENTRY_POINTER(family, name, shape, Params, buffers)               \
    template <>                                                                 \
    struct CpuEntryMember<KernelId::name> {                                     \
        static constexpr CpuEntry<KernelId::name> CpuKernels::*pointer = &CpuKernels::name; \
    };
PN_KERNEL_TABLE(PN_CPU_ENTRY_POINTER)
#undef PN_CPU_ENTRY_POINTER

template <KernelId K>
CpuEntry<K> entry(const CpuKernels& kernels)
{
    return kernels.*CpuEntryMember<K>::pointer;
}

// One table per ISA this build compiled (PENUMBRA_CPU_ISAS, simd/isa_list.h).
#define PN_CPU_TABLE_DECLARATION(id, label, arch, flags, check) extern const CpuKernels kernels_##id;
PN_CPU_ISAS(PN_CPU_TABLE_DECLARATION)
#undef PN_CPU_TABLE_DECLARATION

// ISAs this build holds and this CPU can run, best last (never includes "scalar").
std::vector<std::string_view> supported_isas();
// The table for an ISA name ("scalar", "sse4.2", "avx2", "avx512"); throws
// Error(InvalidArgument) for a name that is not an ISA of this build,
// Error(Unavailable) for one this CPU cannot run.
const CpuKernels& kernels_for(std::string_view isa);
// The ISA the SIMD backend uses: PENUMBRA_SIMD_ISA if set (checked), else the best.
std::string_view chosen_isa();

}  // namespace penumbra::cpu
