// The soft members of the percentage-closer family, read straight from the
// shadow map (no table): PCSS (Fernando 2005) and Burley's bias-cone soft
// shadows. kernels/pcss.h and kernels/burley.h state the mathematics;
// docs/pcf.md ("Soft members") the choices and the measured figures.
//
// Map: a 1-channel image of light depth in [0, 1]. Receivers: a 3-channel
// image (u, v, z), u and v clamped into the map. Output: a 1-channel image of
// visibility in [0, 1] on the receivers' grid. Radii and light sizes are in
// texture units (a fraction of the map's width across u, of its height across v).
#pragma once

#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/parameter_range.h"
#include "penumbra/pcf.h"

namespace penumbra {

// The ranges of the soft members' parameters (checked by pcss() and burley(),
// printed by the method table's help). Sample counts stop at 1024: each
// receiver costs blocker + filter fetches, and beyond a thousand taps the
// Hammersley disc's error is far below the shadow map's own.
inline constexpr int kMaxSoftSamples = 1024;
inline constexpr ParameterRange kBlockerSamplesRange{
    "blocker-samples", "blocker-samples", 1, kMaxSoftSamples, false, false,
    ", the stated limit of taps per pass (penumbra/soft_pcf.h); use fewer samples"};
inline constexpr ParameterRange kFilterSamplesRange{
    "filter-samples", "filter-samples", 1, kMaxSoftSamples, false, false, kBlockerSamplesRange.why_high};
// 0 is a hard shadow (the receiver's own texel); 1 is the whole map's width.
inline constexpr ParameterRange kPcssLightSizeRange{"light-size", "light-size", 0, 1, false, false};
inline constexpr ParameterRange kMinRadiusRange{"min-radius", "min-radius", 0, 0.5, false, false};
inline constexpr ParameterRange kMaxRadiusRange{"max-radius", "max-radius", 0, 0.5, false, false};
inline constexpr ParameterRange kBiasSlopeRange{"bias-slope", "bias-slope", 0, 1000, false, false};
inline constexpr ParameterRange kSlopePerDepthRange{"bias-slope-per-depth", "bias-slope-per-depth", -1000, 1000, false, false};
// The slope at z = 1, bias_slope + bias_slope_per_depth, has bias_slope's range:
// the slope is affine in z, so it stays in [0, 1000] over the whole depth range.
inline constexpr ParameterRange kSlopeAtFarRange{"bias-slope-per-depth", "cone slope at z = 1 (bias-slope + bias-slope-per-depth)", 0, 1000, false, false};
inline constexpr ParameterRange kFalloffRange{"falloff", "falloff", 0, kNoUpperBound, false, true};

struct PcssOptions {
    float light_size = 0.02f;  // texture units: the blocker search's diameter, and L in w = L (z - z_b) / z_b
    int blocker_samples = 16;
    int filter_samples = 24;
    // The family's bias (penumbra/pcf.h): a tap is lit where its depth >= z - beta.
    DepthBias bias{BiasMode::Constant, 5e-4f};
    DepthConvention depth_convention{};  // as PcfOptions' (penumbra/pcf.h)
};

// Named sample counts, as `--preset` (blocker / filter taps): the counts the
// issue names for HDRP's PCSS and for Godot's "Ultra" soft-shadow quality.
struct PcssPreset {
    const char* name;
    int blocker_samples, filter_samples;
};
inline constexpr PcssPreset kPcssPresets[] = {{"hdrp", 16, 24}, {"godot-ultra", 32, 32}};

struct BurleyOptions {
    float min_radius = 0.0005f;  // texture units: the filter radius at contact
    float max_radius = 0.01f;    // the depth pass's radius R, and the widest filter
    float bias_slope = 2.0f;     // depth units per texture unit at z = 0 (the paper's 2.0)
    // Added to the slope per unit of receiver depth z (z clamped into [0, 1]):
    // 0 keeps the cone in depth per texture unit; world_cone() sets both
    // terms from a slope in world units and the light's frustum.
    float bias_slope_per_depth = 0.0f;
    float falloff = 0.0f;        // opacity 1 - (z - z_b) / falloff, clamped to [0, 1]; 0 = off
    int blocker_samples = 16;
    int filter_samples = 24;
    // The family's bias at the cone's tip (Burley's base bias: 0 or near it).
    DepthBias bias{BiasMode::Constant, 0.0f};
    DepthConvention depth_convention{};  // as PcfOptions' (penumbra/pcf.h)
};

// The light's frustum as the cone needs it: the world width the whole map
// (one texture unit) covers at the near and at the far plane -- 2 d tan(fov/2)
// at distance d for a perspective light, the extent for an orthographic one --
// and the planes' distances (linear depth z = (d - near) / (far - near)).
struct LightFrustum {
    float width_at_near = 0, width_at_far = 0;
    float near = 0, far = 0;
};

// Burley's cone with its slope in world units: a tap at world distance x from
// the receiver is compared world_slope * x nearer the light (the paper's
// shadow space, where 2.0 clears any surface tilted less than about 63 degrees
// from facing the light). One texture unit at depth z is w(z) = width_at_near
// + (width_at_far - width_at_near) z wide, so in depth per texture unit the
// slope is world_slope w(z) / (far - near): affine in z, returned as
// bias_slope (at z = 0) and bias_slope_per_depth; the rest of `options` is
// kept. Error (InvalidArgument) for a slope outside [0, 1000], a frustum with
// near < 0, far <= near or a width not finite and > 0, or a resulting slope
// outside the cone's range.
BurleyOptions world_cone(BurleyOptions options, float world_slope, const LightFrustum& light);

// Both take the family's bias modes: with slope or receiver-plane the
// receivers' derivatives come from pcf_receivers() (penumbra/pcf.h).
Image pcss(Context& context, const Image& map, const Image& receivers, const PcssOptions& options);
Image burley(Context& context, const Image& map, const Image& receivers, const BurleyOptions& options);

// The same into an existing 1-channel image of the receivers' size (no
// allocation for the constant bias). If they throw, `out` is left unspecified.
void pcss(Context& context, const Image& map, const Image& receivers, const PcssOptions& options, Image& out);
void burley(Context& context, const Image& map, const Image& receivers, const BurleyOptions& options, Image& out);

}  // namespace penumbra
