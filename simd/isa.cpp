// Which instruction sets this build holds and this CPU runs, and which one
// the SIMD backend uses; the ISAs are those of simd/isa_list.h that
// PENUMBRA_CPU_ISAS built (PN_CPU_ISAS).
#include <cstdlib>
#include <string>

#include "penumbra/error.h"
#include "simd/cpu_kernels.h"

namespace penumbra::cpu {
namespace {

struct BuiltIsa {
    const CpuKernels* kernels;
    bool runs_here;
};

const std::vector<BuiltIsa>& built_isas()
{
    static const std::vector<BuiltIsa> isas{
#define PN_BUILT_ISA(id, label, arch, flags, check) {&kernels_##id, bool(check)},
        PN_CPU_ISAS(PN_BUILT_ISA)
#undef PN_BUILT_ISA
    };
    return isas;
}

bool is_known_isa(std::string_view isa)
{
#define PN_KNOWN_ISA(id, label, arch, flags, check) \
    if (isa == label) return true;
    PN_ISA_ALL(PN_KNOWN_ISA)
#undef PN_KNOWN_ISA
    return false;
}

std::string known_isa_labels()
{
    std::string labels;
#define PN_KNOWN_ISA_LABEL(id, label, arch, flags, check) labels += (labels.empty() ? "" : ", ") + std::string(label);
    PN_ISA_ALL(PN_KNOWN_ISA_LABEL)
#undef PN_KNOWN_ISA_LABEL
    return labels;
}

}  // namespace

std::vector<std::string_view> supported_isas()
{
    std::vector<std::string_view> isas;
    for (const BuiltIsa& built : built_isas())
        if (built.runs_here && built.kernels != &kernels_scalar) isas.push_back(built.kernels->isa);
    return isas;
}

const CpuKernels& kernels_for(std::string_view isa)
{
    for (const BuiltIsa& built : built_isas()) {
        if (isa != built.kernels->isa) continue;
        if (built.runs_here) return *built.kernels;
        throw Error(ErrorCategory::Unavailable, "simd",
                    "this CPU cannot run the " + std::string(isa) +
                        " kernels; choose one of the ISAs `penumbra info` lists");
    }
    if (is_known_isa(isa))
        throw Error(ErrorCategory::Unavailable, "simd",
                    "this build of penumbra has no " + std::string(isa) +
                        " kernels (configure with PENUMBRA_CPU_ISAS including it); `penumbra info` lists those it has");
    throw Error(ErrorCategory::InvalidArgument, "simd",
                "unknown ISA '" + std::string(isa) + "'; valid: " + known_isa_labels());
}

std::string_view chosen_isa()
{
    if (const char* forced = std::getenv("PENUMBRA_SIMD_ISA"); forced && *forced)
        return kernels_for(forced).isa;
    const auto isas = supported_isas();
    return isas.empty() ? std::string_view(kernels_scalar.isa) : isas.back();
}

}  // namespace penumbra::cpu
