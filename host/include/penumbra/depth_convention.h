// Depth conventions: how a shadow map's depths and the receivers' z are
// stored, converted by the kernels where they load them to the normalised
// linear depth l = (d - near) / (far - near) in [0, 1] every method computes
// with (kernels/depth_convention.h has the formulas; docs/integration.md,
// "Depth conventions", the why). The receivers' z is in the map's convention
// (a renderer computes both the same way); biases and depth options stay in
// units of l.
#pragma once

#include <limits>
#include <string>

#include "penumbra/image.h"

namespace penumbra {

enum class DepthConventionKind {
    Normalized,   // l itself, in [0, 1] (the default: the contract before conventions)
    Linear,       // the distance d along the light's axis, in [near, far]
    Perspective,  // D3D / Vulkan [0, 1] depth: z = far (d - near) / (d (far - near))
    Reversed,     // reversed Z: 1 - the perspective depth
};

struct DepthConvention {
    DepthConventionKind kind = DepthConventionKind::Normalized;
    // Read by linear, perspective and reversed (unset: NaN, refused there).
    float near = std::numeric_limits<float>::quiet_NaN();
    float far = std::numeric_limits<float>::quiet_NaN();
};

// Equal kinds, and for a kind that reads them equal near and far.
bool same_convention(const DepthConvention& a, const DepthConvention& b);

// Throws Error(InvalidArgument) naming "near" or "far": a kind that reads
// them needs both finite, far > near, and near > 0 for perspective and
// reversed (the projection divides by d). far = infinity (an infinite
// projection) is refused: every finite distance would have l = 0.
void check_depth_convention(const DepthConvention& convention, const std::string& operation);

// The stored values a convention takes: [0, 1], or [near, far] for linear.
struct StoredDepthRange {
    float low = 0.0f, high = 1.0f;
};
StoredDepthRange stored_depth_range(const DepthConvention& convention);

// Throws Error(InvalidData), parameter "depth", naming the first texel that
// is not finite or lies outside the convention's stored range.
void require_depths_in(const Image& depth, const DepthConvention& convention, const std::string& operation);

// "normalized", "linear", "perspective", "reversed" (the CLI's words).
std::string to_string(DepthConventionKind kind);
// Throws Error(InvalidArgument), parameter "depth-convention", for another word.
DepthConventionKind parse_depth_convention(const std::string& name);
// "perspective (near 0.1, far 100)", for messages.
std::string describe(const DepthConvention& convention);

}  // namespace penumbra
