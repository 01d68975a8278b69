// The SH irradiance coefficients as the kernel takes them
// (host/src/ambient_rig.cpp defines it; host/src/ambient.cpp fills
// AmbientParams with it).
#pragma once

#include "penumbra/ambient.h"

namespace penumbra::detail {

// weights[c * 9 + i]: coefficient i of channel c times its basis function's
// constant, the polynomial weights of kernels/ambient_sh.h.
void polynomial_weights(const ShIrradiance& sh, float* weights);

}  // namespace penumbra::detail
