// Deep shadow map lookups (Lokovic & Veach 2000, "Lookups"): for receivers
// (u, v, z), the filtered visibility of the deep pixels around (u, v), each
// pixel's function V(z) found by a search through its vertices
// (kernels/dsm_lookup.h; docs/deep_shadow_maps.md, "Lookup").
//
// Receivers: the convention of every method (planes u, v, z: texture
// coordinates in [0, 1], clamped; light depth, the map's depth units).
// Output: one plane, in [0, 1], monotone non-increasing in z.
#pragma once

#include "penumbra/context.h"
#include "penumbra/deep_shadow_map.h"
#include "penumbra/image.h"
#include "penumbra/parameter_range.h"

namespace penumbra {

// Box: the (2r+1)^2 pixels centred on the receiver's pixel, equal weights
// (the window of pcf and vsm; r = 0 is the nearest pixel). Tent: the
// separable tent of half-width r + 1 texels centred on (u, v), its (2r+2)^2
// pixels (r = 0 is bilinear). Both clip to the map and renormalise.
enum class DeepFilter { Box, Tent };
// How a pixel's vertices are searched for z: one result, two speeds.
// Linear is the default: measured faster on both backends on dsm-build maps
// (docs/deep_shadow_maps.md, "Lookup").
enum class DeepSearch { Binary, Linear };

// The paper's lookup meets a receiver's own surface at the pixel's sampled
// depths, not the receiver's: 0.003 (tests/reference/deep_map_test.cpp
// measured it on fog and layers at 256^2).
inline constexpr float kDeepDefaultBias = 3e-3f;

// (2r+1)^2 or (2r+2)^2 taps of a search each: the other methods' widest window.
inline constexpr ParameterRange kDeepRadiusRange{
    "radius", "radius", 0, kExactMaxRadius, false, false,
    ", the widest window of the other methods (255x255 texels); for wider blur use a smaller map"};

struct DeepLookupOptions {
    DeepFilter filter = DeepFilter::Tent;
    int radius = 0;  // texels (kDeepRadiusRange)
    DeepSearch search = DeepSearch::Linear;
    // Depth units (kDepthBiasRange): each pixel is evaluated at the float32 depth z - bias.
    float bias = kDeepDefaultBias;
};

// Throws Error(InvalidArgument) naming the parameter (radius, depth-bias,
// receivers: at least 3 channels; out: 1 channel of the receivers' size; a
// map of 2^30 vertices or more) and for a non-finite receiver. The map is
// valid by construction (DeepShadowMap checks every invariant).
void deep_lookup(Context& context, const DeepShadowMap& map, const Image& receivers, const DeepLookupOptions& options,
                 Image& out);
Image deep_lookup(Context& context, const DeepShadowMap& map, const Image& receivers,
                  const DeepLookupOptions& options = {});

}  // namespace penumbra
