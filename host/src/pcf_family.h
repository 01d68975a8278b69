// What every operation of the percentage-closer family (penumbra/pcf.h,
// penumbra/soft_pcf.h) shares: its bias as the kernels read it, its checks
// of the map, the bias and the receivers, and the one checked run of an
// entry into an existing output.
#pragma once

#include <string>

#include "checked_lookup.h"
#include "depth_conversion.h"
#include "host/backend/backend.h"
#include "kernels/params.h"
#include "penumbra/error.h"
#include "penumbra/pcf.h"

namespace penumbra::detail {

// DepthBias (penumbra/pcf.h) as the kernels read it (kernels/params.h's PcfBias).
inline PcfBias kernel_bias(const DepthBias& b)
{
    const int mode = b.mode == BiasMode::Constant ? PN_BIAS_CONSTANT
                     : b.mode == BiasMode::Slope  ? PN_BIAS_SLOPE
                                                  : PN_BIAS_RECEIVER_PLANE;
    return PcfBias{mode, b.constant, b.slope_scale, b.min, b.max};
}

inline bool reads_derivatives(const DepthBias& b) { return b.mode != BiasMode::Constant; }

// In pcf.cpp. Each throws Error(InvalidArgument) naming the parameter.
void check_family_bias(const DepthBias& b, const std::string& op);
void check_family_receivers(const Image& receivers, const DepthBias& b, const std::string& op);

// Checks the map (in `convention`, which the map and the receivers' z are
// stored in), the bias, the receivers and `out` (1 channel, the
// receivers' size); prepares the receivers (their derivative planes when the
// bias mode reads them, pcf_receivers; the constant bias reads u, v, z only,
// so no copy) and runs K with Params p (PcfParams or SoftPcfParams) into out.
template <KernelId K, class Params>
void family_lookup(Context& context, const std::string& op, const Image& map, const Image& receivers,
                   const DepthBias& bias, const DepthConvention& convention, Params p, Image& out)
{
    check_shadow_map(map, op, convention);
    check_family_bias(bias, op);
    check_family_receivers(receivers, bias, op);
    require(out.channels() == 1 && out.width() == receivers.width() && out.height() == receivers.height(), op,
            "the output must be a 1-channel image of the receivers' size (" + std::to_string(receivers.width()) +
                "x" + std::to_string(receivers.height()) + ")");
    const Image planes = reads_derivatives(bias) ? pcf_receivers(receivers, bias, op) : Image{};
    const Image& prepared = reads_derivatives(bias) ? planes : receivers;
    p.depth = dims_of(map);
    p.receivers = dims_of(prepared);
    p.out = dims_of(out);
    p.bias = kernel_bias(bias);
    p.convention = kernel_conversion(convention);
    if constexpr (requires { p.direct; }) p.direct = DirectMap{p.depth, 0, p.convention};  // the soft discs' map
    checked_lookup(op, prepared, [&](int* bad_rows) {
        receiver_lookup<K>(context.impl(), map, prepared, p, out, bad_rows);
    });
}

}  // namespace penumbra::detail
