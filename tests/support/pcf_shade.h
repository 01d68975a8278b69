// Runs one entry of the percentage-closer family with complete PcfParams on a
// backend by name (tests/support/backends.h), for the kernel tests: the
// kernel's own contract, below the library's operation and its checks.
#pragma once

#include <string>

#include "host/backend/backend.h"
#include "host/backend/kernel_id.h"
#include "kernels/params.h"
#include "penumbra/image.h"
#include "simd/cpu_schedule.h"
#include "support/backends.h"

namespace penumbra::testing {

enum class PcfKernel { Box, Gauss, Disc };

template <detail::KernelId K>
Image pcf_shade_cpu(const std::string& isa, const Image& map, const Image& receivers, PcfParams p)
{
    Image out(receivers.width(), receivers.height(), 1);
    std::vector<int> bad_rows(std::size_t(receivers.height()), 0);
    p.depth = detail::dims_of(map);
    p.receivers = detail::dims_of(receivers);
    p.out = detail::dims_of(out);
    cpu::launch_pixels<K>(cpu::kernels_for(isa), out.width(), out.height(), map.plane(0), receivers.plane(0),
                          out.plane(0), bad_rows.data(), p);
    return out;
}

inline Image pcf_shade(const std::string& backend, PcfKernel kernel, const Image& map, const Image& receivers,
                       const PcfParams& p)
{
    if (backend == "opencl") throw SkipBackend{"the generic lookup is not merged yet"};
    const std::string& isa = backend;  // the CPU backends are named by their ISA
    switch (kernel) {
    case PcfKernel::Box: return pcf_shade_cpu<detail::KernelId::pcf>(isa, map, receivers, p);
    case PcfKernel::Gauss: return pcf_shade_cpu<detail::KernelId::pcf_gauss>(isa, map, receivers, p);
    case PcfKernel::Disc: return pcf_shade_cpu<detail::KernelId::pcf_disc>(isa, map, receivers, p);
    }
    return {};
}

}  // namespace penumbra::testing
