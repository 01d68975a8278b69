// The float64 reference of the soft members of the percentage-closer family:
// PCSS (Fernando 2005; kernels/pcss.h) and Burley's bias-cone soft shadows
// (kernels/burley.h), written from the formulas with direct loops, not
// through the kernels. Shared by tests/kernels/soft_pcf_test.cpp and the
// contact-hardening figure (bench/contact_hardening.cpp).
//
// Conventions, the kernels' (docs/pcf.md, "Soft members"): a receiver (u, v, z)
// with u, v clamped into [0, 1] sits at the continuous texel position
// (u W, v H); a tap at offset (dx, dy) texels reads the texel containing
// (u W + dx, v H + dy), clamped to the map. Tap k of n is Hammersley's point
// (k / n, phi_2(k)) in polar form: angle 2 pi k / n, radius phi_2(k) (depth
// pass of burley) or sqrt(phi_2(k)) (every other pass). Radii are in texture
// units (a fraction of the map's width across u, of its height across v).
#pragma once

#include <vector>

#include "penumbra/image.h"
#include "support/pcf_reference.h"

namespace penumbra::testing {

struct UnitDiscTap {
    double dx, dy, radius;
};

// The n taps of the unit disc; `uniform_density` takes radius sqrt(phi_2(k)).
std::vector<UnitDiscTap> hammersley_disc(int n, bool uniform_density);

struct PcssSettings {
    double light_size = 0.02;  // texture units; search disc diameter, w = light_size (z - z_b) / z_b
    int blocker_samples = 16;
    int filter_samples = 16;
};

struct BurleySettings {
    double min_radius = 0.0005, max_radius = 0.01;  // texture units
    // A tap r texture units out is compared at z - beta - slope r, with
    // slope = bias_slope + bias_slope_per_depth clamp(z, 0, 1).
    double bias_slope = 2;
    double falloff = 0;  // opacity 1 - (z - z_b) / falloff, clamped; 0 = off
    int blocker_samples = 16;
    int filter_samples = 16;
    double bias_slope_per_depth = 0;  // last: the tests' positional settings leave it 0
};

// One receiver's steps: whether a blocker was found, the blocker depth, the
// filter radius in texture units (PCSS: w / 2) and the visibility in [0, 1];
// `margin` is the smallest distance of any tap to a decision (its depth to
// its comparison depth, its position to a texel edge, in texels), so that a
// test can leave out receivers that float32 may decide either way.
struct SoftLookup {
    bool found = false;
    double blocker_depth = 0, filter_radius = 0, visibility = 1;
    double margin = 1e30;
};

// `bias` is the family's (beta at the texel each tap reads; burley: the
// cone's base bias), as pcf's reference applies it.
SoftLookup pcss_lookup(const Image& map, const RefReceiver& r, const RefBias& bias, const PcssSettings& s);
SoftLookup burley_lookup(const Image& map, const RefReceiver& r, const RefBias& bias, const BurleySettings& s);

}  // namespace penumbra::testing
