// The one list of instruction sets the CPU backend is compiled for.
//
// One macro per ISA, worst first: PN_ISA_ENTRY_<id>(X) expands to
// X(id, label, xsimd arch, compiler flags, cpu check), where
//  - id:    the C++ namespace and table name (kernels_<id>) of the ISA's copy
//           of the descriptions, and its name in PENUMBRA_CPU_ISAS;
//  - label: the name users give (PENUMBRA_SIMD_ISA, ContextOptions::simd_isa)
//           and `penumbra info` prints;
//  - arch:  the xsimd architecture the copy is compiled for (scalar: none);
//  - flags: the compiler flags of its translation unit;
//  - check: whether this CPU runs it (PN_CPU_HAS(feature) is
//           __builtin_cpu_supports), for the features the flags enable.
//
// cmake/penumbra_kernels.cmake reads these lines (file(STRINGS): one define
// per line, as below) and builds one object library per ISA of
// PENUMBRA_CPU_ISAS; it writes the generated penumbra_cpu_isas.h with
// PN_CPU_ISAS(X), the ISAs built, and PN_ISA_ALL(X), every ISA defined here,
// both in this order. C++ expands PN_CPU_ISAS (the tables in
// simd/cpu_kernels.h, the dispatch in simd/isa.cpp) and names PN_ISA_ALL only
// to tell an ISA left out of the build from an unknown name.
#pragma once

#define PN_CPU_HAS(feature) __builtin_cpu_supports(feature)
// F, CD, BW, DQ and VL: Skylake-SP and later.
#define PN_CPU_HAS_AVX512                                                                                      \
    (PN_CPU_HAS("avx512f") && PN_CPU_HAS("avx512cd") && PN_CPU_HAS("avx512bw") && PN_CPU_HAS("avx512dq") && \
     PN_CPU_HAS("avx512vl"))

// clang-format off
#define PN_ISA_ENTRY_scalar(X) X(scalar, "scalar", none, "", true)
#define PN_ISA_ENTRY_sse4_2(X) X(sse4_2, "sse4.2", xsimd::sse4_2, "-msse4.2", PN_CPU_HAS("sse4.2"))
#define PN_ISA_ENTRY_avx2(X) X(avx2, "avx2", xsimd::fma3<xsimd::avx2>, "-mavx2 -mfma", PN_CPU_HAS("avx2") && PN_CPU_HAS("fma"))
#define PN_ISA_ENTRY_avx512(X) X(avx512, "avx512", xsimd::avx512bw, "-mavx512f -mavx512cd -mavx512bw -mavx512dq -mavx512vl -mavx2 -mfma", PN_CPU_HAS_AVX512)
// clang-format on
