// CPU launches of the Chebyshev lookups (kernels/vsm.h, kernels/vssm.h).
#include "simd/cpu_backend.h"
#include "simd/cpu_schedule.h"

namespace penumbra::cpu {

void CpuBackend::chebyshev(detail::ChebyshevMethod method, const MomentTable& table, const Image& receivers,
                           const ChebyshevParams& p, Image& out, int* bad_rows)
{
    switch (method) {
    case detail::ChebyshevMethod::Vsm:
        return launch_table_lookup<KernelId::vsm_float, KernelId::vsm_exact>(kernels_, table, receivers, p, out,
                                                                             bad_rows);
    case detail::ChebyshevMethod::Vssm:
        return launch_table_lookup<KernelId::vssm_float, KernelId::vssm_exact>(kernels_, table, receivers, p, out,
                                                                               bad_rows);
    }
}

}  // namespace penumbra::cpu
