// The receivers' depth derivatives for the slope-scaled and receiver-plane
// biases of the percentage-closer family (kernels/depth_bias.h).
#pragma once

#include "penumbra/image.h"

namespace penumbra::detail {

// One-sided differences of u, v or z along one axis of the receivers' grid
// are "planar" when they agree: |d+ - d-| <= kPlanarTolerance max(|d+|, |d-|)
// + kPlanarFloor. A silhouette (a depth jump) or a crease fails it; there
// the plane flag is 0 and the kernel uses the constant bias.
inline constexpr double kPlanarTolerance = 0.5;
inline constexpr double kPlanarFloor = 1e-6;

// `receivers` (u, v, z) with planes dz/du, dz/dv and the plane flag appended
// (6 planes), by finite differences on the receivers' grid (host, once per
// call, before the lookup; docs/pcf.md).
Image receivers_with_differences(const Image& receivers);

// `receivers` (u, v, z, dzdu, dzdv; finite, checked before) with the plane
// flag appended: 1 everywhere.
Image receivers_with_channels(const Image& receivers);

}  // namespace penumbra::detail
