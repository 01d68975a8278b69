// OpenCL launches of the Chebyshev lookups (kernels/vsm.h, kernels/vssm.h).
#include "cl/opencl_table_lookup.h"

namespace penumbra::cl_backend {

using detail::KernelId;

void OpenClBackend::chebyshev(detail::ChebyshevMethod method, const MomentTable& table, const Image& receivers,
                              const ChebyshevParams& p, Image& out, int* bad_rows)
{
    if (method == detail::ChebyshevMethod::Vsm)
        table_lookup<KernelId::vsm_float, KernelId::vsm_exact>(table, receivers, p, out, bad_rows);
    else
        table_lookup<KernelId::vssm_float, KernelId::vssm_exact>(table, receivers, p, out, bad_rows);
}

}  // namespace penumbra::cl_backend
