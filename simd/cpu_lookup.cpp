// CPU launch of every lookup-shaped entry of the kernel table (VSM, VSSM,
// MSM, moment soft shadows, EVSM, and any entry of the same shape added
// later): one launch_pixels<K> per receiver strip, the run-time KernelId made
// compile-time by the table's one switch (detail::visit_lookup). No method is
// named here: a new lookup-shaped entry runs with no edit of this file.
#include "simd/cpu_backend.h"
#include "simd/cpu_schedule.h"

namespace penumbra::cpu {

void CpuBackend::receiver_lookup(KernelId kernel, const detail::LookupSource& source, const Image& receivers,
                                 const void* params, Image& out, int* bad_rows)
{
    detail::visit_lookup(kernel, params, [&](auto k, const auto& p) {
        constexpr KernelId K = decltype(k)::value;
        const auto* origin = source.origin<detail::LookupSourceOf<K>>(K);
        launch_pixels<K>(kernels_, out.width(), out.height(), origin, receivers.plane(0), out.plane(0), bad_rows, p);
    });
}

}  // namespace penumbra::cpu
