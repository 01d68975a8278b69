// The percentage-closer family's depth bias (penumbra/pcf.h's DepthBias) as
// its kernels read it (kernels/params.h's PcfBias): shared by pcf.cpp and
// soft_pcf.cpp, whose operations all take the family's bias.
#pragma once

#include "kernels/params.h"
#include "penumbra/pcf.h"

namespace penumbra::detail {

inline PcfBias kernel_bias(const DepthBias& b)
{
    const int mode = b.mode == BiasMode::Constant ? PN_BIAS_CONSTANT
                     : b.mode == BiasMode::Slope  ? PN_BIAS_SLOPE
                                                  : PN_BIAS_RECEIVER_PLANE;
    return PcfBias{mode, b.constant, b.slope_scale, b.min, b.max};
}

}  // namespace penumbra::detail
