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
inline constexpr ParameterRange kFalloffRange{"falloff", "falloff", 0, kNoUpperBound, false, true};

struct PcssOptions {
    float light_size = 0.02f;  // texture units: the blocker search's diameter, and L in w = L (z - z_b) / z_b
    int blocker_samples = 16;
    int filter_samples = 24;
    // The family's bias (penumbra/pcf.h): a tap is lit where its depth >= z - beta.
    DepthBias bias{BiasMode::Constant, 5e-4f};
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
    float bias_slope = 2.0f;     // depth units per texture unit (the paper's 2.0)
    float falloff = 0.0f;        // opacity 1 - (z - z_b) / falloff, clamped to [0, 1]; 0 = off
    int blocker_samples = 16;
    int filter_samples = 24;
    // The family's bias at the cone's tip (Burley's base bias: 0 or near it).
    DepthBias bias{BiasMode::Constant, 0.0f};
};

// Both take the family's bias modes: with slope or receiver-plane the
// receivers' derivatives come from pcf_receivers() (penumbra/pcf.h).
Image pcss(Context& context, const Image& map, const Image& receivers, const PcssOptions& options);
Image burley(Context& context, const Image& map, const Image& receivers, const BurleyOptions& options);

// The same into an existing 1-channel image of the receivers' size (no
// allocation for the constant bias). If they throw, `out` is left unspecified.
void pcss(Context& context, const Image& map, const Image& receivers, const PcssOptions& options, Image& out);
void burley(Context& context, const Image& map, const Image& receivers, const BurleyOptions& options, Image& out);

}  // namespace penumbra
