// Runs one entry of the percentage-closer family with complete parameters on a
// backend by name (tests/support/backends.h), for the kernel tests: the
// kernel's own contract, below the library's operation and its checks.
#pragma once

#include <string>

#include "host/backend/backend.h"
#include "host/backend/kernel_id.h"
#include "kernels/params.h"
#include "penumbra/image.h"
#include "support/backends.h"

namespace penumbra::testing {

enum class PcfKernel { Box, Gauss, Disc };

// Params: PcfParams, or SoftPcfParams for pcss and burley.
template <detail::KernelId K, class Params>
Image pcf_shade_on(Context& context, const Image& map, const Image& receivers, Params p)
{
    Image out(receivers.width(), receivers.height(), 1);
    std::vector<int> bad_rows(std::size_t(receivers.height()), 0);
    p.depth = detail::dims_of(map);
    p.receivers = detail::dims_of(receivers);
    p.out = detail::dims_of(out);
    detail::receiver_lookup<K>(context.impl(), map, receivers, p, out, bad_rows.data());
    return out;
}

inline Image pcf_shade(const std::string& backend, PcfKernel kernel, const Image& map, const Image& receivers,
                       const PcfParams& p)
{
    Context& context = PN_CONTEXT_OR_SKIP(backend);
    switch (kernel) {
    case PcfKernel::Box: return pcf_shade_on<detail::KernelId::pcf>(context, map, receivers, p);
    case PcfKernel::Gauss: return pcf_shade_on<detail::KernelId::pcf_gauss>(context, map, receivers, p);
    case PcfKernel::Disc: return pcf_shade_on<detail::KernelId::pcf_disc>(context, map, receivers, p);
    }
    return {};
}

}  // namespace penumbra::testing
