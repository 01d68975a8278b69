// Chebyshev-bound shadow filtering over a moment table: VSM and VSSM.
//
// Receivers: a 3-channel image (u, v, z): light-space texture coordinates in
// [0, 1] (clamped into the map) and light-space depth. Output: a 1-channel
// image of visibility in [0, 1] on the receivers' grid.
#pragma once

#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"

namespace penumbra {

// Default variance floor, in depth^2: above the exact table's quantization of
// z^2 (0.5 / 65535 = 7.6e-6 per texel) so that a flat window never reads a
// rounding residue as a depth spread, small enough to keep contact shadows
// sharp (a 16-bit depth step is 1.5e-5; its square is far below).
inline constexpr float kDefaultMinVariance = 2e-5f;

struct VsmOptions {
    int radius = 2;                       // texels; window (2r+1)^2
    float min_variance = kDefaultMinVariance;
    float bleed = 0.0f;                   // light-bleeding reduction in [0, 1); 0 = off
    // The receivers' z (and the direct form's map): a table's convention
    // (build_moment_table) must equal it (penumbra/depth_convention.h).
    DepthConvention depth_convention{};
};

struct VssmOptions {
    float light_size = 0.02f;             // texture units: the blocker search's width, and L in w = L (z - z_b) / z_b (> 0; docs/reference.md)
    float min_variance = kDefaultMinVariance;
    float bleed = 0.0f;
    DepthConvention depth_convention{};   // as VsmOptions'
};

Image vsm(Context& context, const MomentTable& table, const Image& receivers, const VsmOptions& options);
Image vssm(Context& context, const MomentTable& table, const Image& receivers, const VssmOptions& options);

// The same into an existing 1-channel image of the receivers' size: no
// allocation, for per-frame use. If they throw, `out` is left unspecified.
void vsm(Context& context, const MomentTable& table, const Image& receivers, const VsmOptions& options, Image& out);

// VSM with the window's sums taken directly from the shadow map (`depth`:
// one channel, depths in [0, 1]) instead of a table: the same method (the
// same window and bound, to the last bits of double), O((2r+1)^2) per
// receiver and no table to build, faster than a table's lookup for
// radius <= kVsmDirectMaxRadius (measured, docs/moment_table.md: "Direct sums
// for small windows"); any radius the table takes is accepted.
// `penumbra shade` and the method table pick this form for those radii.
inline constexpr int kVsmDirectMaxRadius = 0;
Image vsm(Context& context, const Image& depth, const Image& receivers, const VsmOptions& options);
void vsm(Context& context, const Image& depth, const Image& receivers, const VsmOptions& options, Image& out);

void vssm(Context& context, const MomentTable& table, const Image& receivers, const VssmOptions& options, Image& out);

}  // namespace penumbra
