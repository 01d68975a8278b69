// CPU launches of the Chebyshev lookups (kernels/vsm.h, kernels/vssm.h).
#include "simd/cpu_backend.h"
#include "simd/cpu_schedule.h"

namespace penumbra::cpu {

void CpuBackend::chebyshev(detail::ChebyshevMethod method, const MomentTable& table, const Image& receivers,
                           const ChebyshevParams& p, Image& out, int* bad_rows)
{
    const bool vsm = method == detail::ChebyshevMethod::Vsm;
    const float* rx = receivers.plane(0);
    float* result = out.plane(0);
    if (table.precision() == Precision::Float) {
        auto* kernel = vsm ? k_.vsm_float : k_.vssm_float;
        for_each_strip(out.width(), out.height(), k_.lanes,
                       [&](int x, int y) { kernel(table.float_origin(), rx, result, bad_rows, p, x, y); });
    } else {
        auto* kernel = vsm ? k_.vsm_exact : k_.vssm_exact;
        for_each_strip(out.width(), out.height(), k_.lanes,
                       [&](int x, int y) { kernel(table.exact_origin(), rx, result, bad_rows, p, x, y); });
    }
}

}  // namespace penumbra::cpu
