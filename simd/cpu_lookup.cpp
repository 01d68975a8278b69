// CPU launch of every lookup-shaped entry of the kernel table (VSM, VSSM,
// MSM, moment soft shadows, EVSM, the deep shadow map lookup, and any entry
// of the same shape added later): one launch_pixels<K> per receiver strip,
// the run-time KernelId made compile-time by the table's one switch
// (detail::visit_lookup), the source's buffers (one, or several arrays) in
// the entry's order (detail::source_buffers). No method is named here: a new
// lookup-shaped entry runs with no edit of this file. The entries reading a
// DirectMap (the direct window sums, pcss, burley) over a map in another
// convention than normalised depth take their own schedule
// (simd/cpu_direct_sums.h), chosen by their Params' DirectMap.
#include <tuple>
#include <type_traits>

#include "simd/cpu_backend.h"
#include "simd/cpu_direct_sums.h"
#include "simd/cpu_schedule.h"

namespace penumbra::cpu {

void CpuBackend::receiver_lookup(KernelId kernel, const detail::LookupSource& source, const Image& receivers,
                                 const void* params, Image& out, int* bad_rows)
{
    detail::visit_lookup(kernel, params, [&](auto k, const auto& p) {
        constexpr KernelId K = decltype(k)::value;
        const auto sources = detail::source_buffers<K>(source);
        // The band conversion's test sits here, in the lambda whose own
        // parameter it depends on: inside std::apply's inner lambda the call
        // would not depend on that lambda's parameters, and clang checks it
        // even in a discarded branch.
        using Sources = std::remove_cvref_t<decltype(sources)>;
        if constexpr (ReadsDirectMap<std::decay_t<decltype(p)>> && std::tuple_size_v<Sources> == 1 &&
                      std::is_same_v<std::tuple_element_t<0, Sources>, const float*>)
            if (converts_per_band(p))
                return launch_in_bands<K>(kernels_, std::get<0>(sources), receivers, out, bad_rows, p);
        std::apply(
            [&](const auto*... buffers) {
                launch_pixels<K>(kernels_, out.width(), out.height(), buffers..., receivers.plane(0), out.plane(0),
                                 bad_rows, p);
            },
            sources);
    });
}

}  // namespace penumbra::cpu
