// Which instruction sets this CPU runs, and which one the SIMD backend uses.
#include <cstdlib>
#include <string>

#include "penumbra/error.h"
#include "simd/cpu_kernels.h"

namespace penumbra::cpu {
namespace {

bool cpu_has_avx512()
{
    // The avx512 table is built with F, CD, BW, DQ and VL (Skylake-SP and later).
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
           __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512vl");
}

bool cpu_has_avx2() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }
bool cpu_has_sse4_2() { return __builtin_cpu_supports("sse4.2"); }

}  // namespace

std::vector<std::string_view> supported_isas()
{
    std::vector<std::string_view> isas;
    if (cpu_has_sse4_2()) isas.push_back(kernels_sse4_2.isa);
    if (cpu_has_avx2()) isas.push_back(kernels_avx2.isa);
    if (cpu_has_avx512()) isas.push_back(kernels_avx512.isa);
    return isas;
}

const CpuKernels& kernels_for(std::string_view isa)
{
    if (isa == kernels_scalar.isa) return kernels_scalar;
    const CpuKernels* tables[] = {&kernels_sse4_2, &kernels_avx2, &kernels_avx512};
    for (const CpuKernels* table : tables) {
        if (isa != table->isa) continue;
        for (std::string_view supported : supported_isas())
            if (supported == isa) return *table;
        throw Error(ErrorCategory::Unavailable, "simd",
                    "this CPU cannot run the " + std::string(isa) +
                        " kernels; choose one of the ISAs `penumbra info` lists");
    }
    throw Error(ErrorCategory::InvalidArgument, "simd",
                "unknown ISA '" + std::string(isa) + "'; valid: scalar, sse4.2, avx2, avx512");
}

std::string_view chosen_isa()
{
    if (const char* forced = std::getenv("PENUMBRA_SIMD_ISA"); forced && *forced)
        return kernels_for(forced).isa;
    const auto isas = supported_isas();
    return isas.empty() ? std::string_view(kernels_scalar.isa) : isas.back();
}

}  // namespace penumbra::cpu
