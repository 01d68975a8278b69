// The cross-bilateral blur's window and parameters from geometry alone:
// shared by the Image form (bilateral.cpp) and the device-resident one
// (device_image.cpp), so that both run the same taps and weights.
#pragma once

#include <vector>

#include "kernels/params.h"
#include "penumbra/bilateral.h"

namespace penumbra::detail {

struct BilateralSetup {
    std::vector<int> taps;       // (dx, dy) pairs
    std::vector<float> weights;  // (weight, base-2 exponent) pairs
    BilateralParams params;      // complete but for the separable schedule's pass fields
};

// Checks the options (Error(InvalidArgument) naming the bad one) and builds the window.
BilateralSetup bilateral_setup(const BilateralOptions& options, pn_dims mask, int channels, pn_dims guide,
                               const pn_dims* normals, pn_dims out);

// True when the mask's largest magnitude is beyond what the kernels' float
// sums take unscaled (2^100, bilateral.cpp's overflow guard).
bool needs_overflow_guard(const Image& mask);

}  // namespace penumbra::detail
