// The percentage-closer family's float64 reference (kernels/pcf.h,
// pcf_gauss.h, pcf_disc.h and the bias modes of kernels/depth_bias.h),
// written from the definitions by loops over taps, not through the kernels:
// the Gaussian filter as its n x n bilinear taps (not the kernel's merged
// (n+1)^2 footprint), the disc's taps at cos / sin of their angles (not the
// kernel's rotation recurrence). Each result carries the smallest margin of
// any tap to a decision (a depth comparison, a disc tap's distance to a texel
// edge), so that a test can leave out receivers that float32 may decide
// either way.
#pragma once

#include "penumbra/image.h"

namespace penumbra::testing {

enum class RefBiasMode { Constant, Slope, ReceiverPlane };

struct RefBias {
    RefBiasMode mode = RefBiasMode::Constant;
    double constant = 0.0, slope_scale = 1.0, low = 0.0, high = 1.0;
};

// One receiver as the kernels read it: u, v unclamped (the reference
// clamps), the derivatives and plane flag of the receivers' planes 3 .. 5.
struct RefReceiver {
    double u, v, z;
    double dzdu = 0.0, dzdv = 0.0;
    bool plane = false;
    int x = 0, y = 0;  // the receiver's pixel (the disc's rotation tile)
};

struct RefResult {
    double visibility = 0.0;
    double margin = 1e30;  // smallest |depth - (z - beta)| of any tap, or disc tap to texel edge
};

// The comparison depth z - beta for the tap at texel (tx, ty), inside the map
// (kernels/depth_bias.h); also the soft members' (support/soft_pcf_reference.h).
double tap_reference(const Image& map, const RefReceiver& r, const RefBias& b, int tx, int ty);

// The receiver of pixel (x, y) of a 3- or 6-plane receivers image.
RefReceiver ref_receiver(const Image& receivers, int x, int y);

RefResult pcf_box_reference(const Image& map, const RefReceiver& r, const RefBias& bias, int radius);
RefResult pcf_gauss_reference(const Image& map, const RefReceiver& r, const RefBias& bias, int grid, double sigma);
RefResult pcf_disc_reference(const Image& map, const RefReceiver& r, const RefBias& bias, int taps, double radius,
                             bool rotate);

}  // namespace penumbra::testing
