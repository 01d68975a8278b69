// The percentage-closer family: filters that compare the shadow map's own
// texels with each receiver and average the results (Reeves et al. 1987),
// with one set of depth-bias modes for all of them (kernels/depth_bias.h;
// docs/pcf.md). The map is read as it is (one float channel, depths in
// [0, 1]); no table is built.
//
// Receivers: channels u, v, z (texture coordinates in [0, 1], light depth),
// optionally followed by dzdu, dzdv (the receiver surface's depth slope per
// unit of u and v), which DerivativeSource::Channels reads.
#pragma once

#include "penumbra/context.h"
#include "penumbra/depth_convention.h"
#include "penumbra/image.h"

namespace penumbra {

enum class BiasMode {
    Constant,       // depth >= z - constant: the `shade` window contract
    Slope,          // + slope_scale x the receiver plane's depth change per texel, clamped to [min, max]
    ReceiverPlane,  // each tap compared with the receiver's plane at that texel (Isidoro 2006), clamped
};

enum class DerivativeSource {
    FiniteDifferences,  // from the receivers' neighbours on their grid (host; docs/pcf.md states the test)
    Channels,           // the receivers' channels 3 and 4 (dzdu, dzdv)
};

inline constexpr float kPcfDefaultDepthBias = 1e-3f;

struct DepthBias {
    BiasMode mode = BiasMode::Constant;
    float constant = kPcfDefaultDepthBias;  // depth units: the constant bias, the others' base
    float slope_scale = 1.0f;               // slope mode: bias per unit of depth change across a texel
    float min = 0.0f, max = 0.02f;          // slope, receiver-plane: the clamp (Toy Story 3)
    DerivativeSource derivatives = DerivativeSource::FiniteDifferences;
};

struct PcfOptions {
    int radius = 2;  // window (2 radius + 1)^2 texels
    DepthBias bias{};
    // How the map and the receivers' z are stored (penumbra/depth_convention.h);
    // the bias stays in normalised depth.
    DepthConvention depth_convention{};
};

struct PcfGaussOptions {
    int grid = 4;        // taps per side (4: Toy Story 3's 4x4); 1 .. kPcfMaxGrid
    float sigma = 1.0f;  // the Gaussian's standard deviation in texels
    DepthBias bias{};
    DepthConvention depth_convention{};  // as PcfOptions'
};

struct PcfDiscOptions {
    int taps = 16;        // 1 .. kPcfMaxTaps
    float radius = 2.5f;  // the disc's radius in texels
    bool rotate = true;   // rotate per receiver from a 4x4 tile (Toy Story 3)
    DepthBias bias{};
    DepthConvention depth_convention{};  // as PcfOptions'
};

inline constexpr int kPcfMaxGrid = 16;   // kernels/params.h, PN_PCF_MAX_GRID
inline constexpr int kPcfMaxTaps = 256;  // kernels/params.h, PN_PCF_MAX_TAPS

// Visibility in [0, 1] on the receivers' grid. Throws Error naming the
// parameter ("radius", "grid", "sigma", "taps", "disc-radius", "depth-bias",
// "slope-scale", "bias-min", "bias-max", "receivers", "depth").
Image pcf(Context& context, const Image& map, const Image& receivers, const PcfOptions& options = {});
Image pcf_gauss(Context& context, const Image& map, const Image& receivers, const PcfGaussOptions& options = {});
Image pcf_disc(Context& context, const Image& map, const Image& receivers, const PcfDiscOptions& options = {});

// The same into an existing 1-channel image of the receivers' size (no
// allocation for the constant bias). If they throw, `out` is left unspecified.
void pcf(Context& context, const Image& map, const Image& receivers, const PcfOptions& options, Image& out);
void pcf_gauss(Context& context, const Image& map, const Image& receivers, const PcfGaussOptions& options, Image& out);
void pcf_disc(Context& context, const Image& map, const Image& receivers, const PcfDiscOptions& options, Image& out);

// The receivers as the family's kernels read them for `bias`: u, v, z, and
// for the slope and receiver-plane modes dz/du, dz/dv and the plane flag
// (1: the derivatives hold; 0: they cross a depth discontinuity and the
// constant bias applies). Checks `bias` and the receivers' channels.
Image pcf_receivers(const Image& receivers, const DepthBias& bias, const std::string& operation);

}  // namespace penumbra
