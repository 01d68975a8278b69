// Cascaded shadow maps of a directional light, shaded per view pixel as Toy
// Story 3's deferred shadow mask does (Siggraph 2010 course notes; docs/cascades.md):
// the cascade chosen by bounding box (Zhang et al. 2009) or by split depth,
// a dynamic receiver-plane bias invalidated where the derivatives cross
// cascades, clamped, and a 4x4 Gaussian PCF in the chosen cascade.
#pragma once

#include <array>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/image.h"

namespace penumbra {

inline constexpr int kMaxCascades = 4;  // kernels/params.h, PN_CASCADES_MAX

// Where a world point p lands in one cascade's orthographic map:
//   u = dot(p, axis_u) u_scale + u_offset, v and z alike,
// the cascade's box being [0, 1]^3 (z: its linear depth, 0 at its near plane).
struct CascadeFrame {
    float u_scale = 1, u_offset = 0;
    float v_scale = 1, v_offset = 0;
    float z_scale = 1, z_offset = 0;
    float split_far = 0;  // the view depth at which the cascade's split ends
};

struct CascadeShadows {
    // The light's frame in world space: unit vectors, the map's columns (u),
    // rows (v) and the light's direction (z).
    std::array<float, 3> axis_u{1, 0, 0}, axis_v{0, 0, 1}, axis_z{0, -1, 0};
    std::vector<CascadeFrame> cascades;  // finest first, 1 .. kMaxCascades
    // One channel, the cascades' maps stacked: W x (cascades.size() H),
    // cascade c in rows [c H, (c + 1) H); depths in [0, 1].
    Image maps;
};

enum class CascadeSelection {
    BoundingBox,  // the finest cascade whose box holds the pixel's PCF footprint (Zhang 2009)
    SplitDepth,   // the first cascade whose split ends beyond the pixel's view depth
};

// Biases are in texels of the chosen cascade: a value b means the depth a
// 45-degree surface drops across b texels of that cascade (b / (u_scale W)
// world units), so one value serves every cascade (the notes' "scaled static
// bias based on the current cascade").
struct CascadeOptions {
    CascadeSelection selection = CascadeSelection::BoundingBox;
    int grid = 4;        // Gaussian PCF taps per side
    float sigma = 1.0f;  // texels
    float static_bias = 2.0f;  // where the receiver-plane derivatives do not hold
    // The clamp of every bias; the minimum is also the margin above the
    // receiver's plane (docs/cascades.md has the figures behind the defaults).
    float bias_min = 0.5f, bias_max = 8.0f;
};

// Receivers: PN_CASCADE_PLANES = 5 channels on the view grid: world x, y, z,
// view depth, and 1 where the pixel sees a surface (else 0).
inline constexpr int kCascadeReceiverChannels = 5;

// Out: 2 channels of the receivers' size: visibility in [0, 1] (1 where no
// cascade holds the pixel or it sees no surface) and the cascade used (-1
// for none). Throws Error(InvalidArgument) naming the parameter: "cascades"
// (none, more than kMaxCascades, a non-finite frame, a maps image whose
// height is not a multiple of their count), "maps", "receivers", "grid",
// "sigma", "static-bias", "bias-min", "bias-max", "out".
void cascade_mask(Context& context, const CascadeShadows& shadows, const Image& receivers,
                  const CascadeOptions& options, Image& out);
Image cascade_mask(Context& context, const CascadeShadows& shadows, const Image& receivers,
                   const CascadeOptions& options = {});

}  // namespace penumbra
