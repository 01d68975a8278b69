// The moment family: moment shadow maps (MSM, Peters & Klein, I3D 2015, with
// the Hausdorff fallback), moment soft shadows (Peters et al., I3D 2016 /
// JCGT 2017) and exponential variance shadow maps (EVSM2, EVSM4). The kernels
// are kernels/msm.h, msm_soft.h, evsm.h and encoded_table.h; docs/moments.md
// derives the defaults and has the measured figures.
//
// A depth map (one channel, light depth in [0, 1]) becomes a summed-area
// table of encoded texels (build_msm_table, build_evsm_table); lookups take
// receivers (3 channels: u, v in [0, 1], clamped into the map, and light
// depth z) and return one channel of visibility in [0, 1], never NaN.
//
// Storage:
//  - Quantization::None (the default) with Precision::Exact: exact limb tables
//    (kernels/moment_table.h) of the method's own values, z..z^4 (MSM) or the
//    warps (EVSM), each rounded to 48 bits (3 limbs, error <= 1.8e-15): the
//    methods compute their mathematics on the float32 depths
//    (docs/moments.md: fidelity). Windows up to 255 x 255 texels.
//  - Quantization::Bits16 (MSM only, opt-in): the I3D 2015 optimized 16-bit
//    quantization, summed exactly; 16 B/texel instead of 48, at the price of
//    its own quantization error (docs/moments.md).
//  - Quantization::Bits32 with Precision::Float: float sums of floats (legacy;
//    their error grows with the map, docs/moment_table.md).
// Bad input throws penumbra::Error naming the parameter.
#pragma once

#include <optional>

#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"
#include "penumbra/parameter_range.h"
#include "penumbra/pcf.h"

namespace penumbra {

enum class Quantization { None, Bits16, Bits32 };

// --- MSM -----------------------------------------------------------------

// Moment bias alpha: the share of every window replaced by a distribution
// half at depth 0 and half at depth 1, so that rounding cannot push the
// moments out of the set of valid moment vectors; it adds at most alpha / 2
// of light. Both defaults are 6e-5, measured (docs/moments.md, "Biases"):
//  - Bits16: its variance alpha / 4 must cover the worst variance the 16-bit
//    rounding shows at a one-depth window, 1.02e-5 (decoded in float; the
//    sweep of all 65536 depths needs alpha >= 2e-5), so alpha = 4 x 1.5e-5:
//    the paper's 6e-5; the error against the exact bound on few-depth windows
//    stops falling from 3e-5 on;
//  - Bits32: the literature's 3e-7 assumes a reconstruction more precise than
//    float32: on the same windows it is off the exact bound by up to 0.052 (at
//    a depth uncertainty of 1e-3), 6e-5 by 0.002.
inline constexpr float kMsmMomentBias16 = 6e-5f;
inline constexpr float kMsmMomentBias32 = 6e-5f;
// Depth bias, subtracted from the receiver's depth (units of the [0, 1]
// depth range). Bits16: twice the worst error of a one-depth window's
// decoded mean (9.1e-6), rounded up to two 16-bit depth steps, 2 / 65535 =
// 3.05e-5 (0.4 mm on a 13.5 m depth range). Bits32: one 16-bit step,
// 2^-16 = 1.5e-5: the depths of a two-depth window come back from float
// moments to about 1e-6 (the straight-edge test, tests/kernels/msm_soft_test.cpp,
// fails at 2^-21), with margin. A sloped receiver needs more: about half a
// texel's depth change at the receiver (receiver-plane bias; 3e-4 on the
// overlap scene at 512^2, docs/moments.md).
inline constexpr float kMsmDepthBias16 = 2.0f / 65535.0f;
// Quantization::None keeps the defaults of the former default storage (Bits16),
// so that the same options mean the same method (docs/moments.md, "Biases").
inline constexpr float kMsmMomentBiasExact = 6e-5f;
inline constexpr float kMsmDepthBiasExact = 2.0f / 65535.0f;
inline constexpr float kMsmDepthBias32 = 0x1p-16f;
float default_moment_bias(Quantization quantization);
float default_depth_bias(Quantization quantization);

// Four moments per texel, summed.
struct MsmTable {
    MomentTable sums;  // z..z^4 (None: 3 limbs each; Bits32: floats) or the optimized channels (Bits16)
    Quantization quantization = Quantization::None;
};

// Throws Error for an empty or multi-channel map, depths outside [0, 1] or
// non-finite, and Bits32 with Precision::Exact (an exact table holds 16-bit
// values).
// `convention`: the map's depths (penumbra/depth_convention.h); the table
// records it, and its lookups take receivers in the same one.
MsmTable build_msm_table(Context& context, const Image& depth, Quantization quantization = Quantization::None,
                         Precision precision = Precision::Exact, const DepthConvention& convention = {});

struct MsmOptions {
    int radius = 2;                     // box (2r+1)^2 texels; exact tables: r <= 127
    std::optional<float> moment_bias{}; // alpha in [0, 1); unset: default_moment_bias()
    std::optional<float> depth_bias{};  // >= 0 and < 1; unset: default_depth_bias()
    DepthConvention depth_convention{}; // the receivers' z; a table's must equal it
};

struct MsmSoftOptions {
    float light_size = 0.02f;           // as VssmOptions::light_size (> 0)
    std::optional<float> moment_bias{};
    std::optional<float> depth_bias{};
    // The receiver's own plane inside wide windows (kernels/msm_soft.h): each
    // window compares against z - depth_bias - min(plane_bias x the plane's
    // largest drop inside it, plane_bias_max). 0 = off, the window contract
    // of the other lookups; 1 = a planar receiver never shadows itself. The
    // plane: dz/du, dz/dv as the percentage-closer family's (pcf_receivers,
    // penumbra/pcf.h): by finite differences on the receivers' grid (a host
    // pass over the receivers on every call), or from the receivers' channels
    // 3 and 4 (dzdu, dzdv) with DerivativeSource::Channels, which a renderer
    // that has them (its G-buffer's depth derivatives) should pass.
    float plane_bias = 0.0f;            // in [0, 16]
    float plane_bias_max = 0.02f;       // in [0, 1], depth units
    DerivativeSource derivatives = DerivativeSource::FiniteDifferences;
    DepthConvention depth_convention{}; // the receivers' z (and their dzdu, dzdv); the table's must equal it
};

Image msm(Context& context, const MsmTable& table, const Image& receivers, const MsmOptions& options = {});
Image msm_soft(Context& context, const MsmTable& table, const Image& receivers, const MsmSoftOptions& options = {});
// Into an existing 1-channel image of the receivers' size.
void msm(Context& context, const MsmTable& table, const Image& receivers, const MsmOptions& options, Image& out);
void msm_soft(Context& context, const MsmTable& table, const Image& receivers, const MsmSoftOptions& options,
              Image& out);

// MSM with the window's z .. z^4 summed directly from the shadow map
// (`depth`: one channel, depths in [0, 1]) instead of a table: the default
// storage's method (Quantization::None; its biases), O((2r+1)^2) per
// receiver and no table to build; faster than the table's lookup for
// radius <= kMsmDirectMaxRadius (docs/moment_table.md, "Direct sums for small
// windows"), which `penumbra shade` then picks.
inline constexpr int kMsmDirectMaxRadius = 1;
Image msm(Context& context, const Image& depth, const Image& receivers, const MsmOptions& options = {});
void msm(Context& context, const Image& depth, const Image& receivers, const MsmOptions& options, Image& out);

// --- EVSM ----------------------------------------------------------------

// The largest exponent each storage holds (kernels/exponential_warp.h):
// 16-bit steps: e^{-2c} must be one step, c <= ln(65535) / 2; floats: the
// literature's 42 (e^{-2c} a normal float needs c <= 43.67).
inline constexpr float kEvsmMaxExponent16 = 5.545177f;
inline constexpr float kEvsmMaxExponent32 = 42.0f;
// Quantization::None (exact 48-bit limb tables): the warped variance floor
// min_variance (c w)^2 at the smallest warp e^-c must stay far above the
// storage's 1.8e-15: the bound's error 1.8e-15 / (4 x 2e-5 c^2 e^-2c) is
// below 2e-4 up to c = 10.2 at the default floor (docs/moments.md).
inline constexpr float kEvsmMaxExponentExact = float(kPositiveExponentRange.high);
inline constexpr float kEvsmPositiveExponentExact = 10.0f;
inline constexpr float kEvsmNegativeExponentExact = 5.0f;
// Defaults. Bits16: the limit for both warps. Bits32 (float tables): a float
// summed-area table loses the small warped values near the light as its sums
// grow, so the limit is not the best choice: on the overlap scene (radius 2,
// 512^2 and 1024^2) c+ = 42 gives RMSE 0.21-0.30, c+ = 10 0.113-0.117
// (docs/moments.md); c- = 5 (the literature's).
inline constexpr float kEvsmPositiveExponent32 = 10.0f;
inline constexpr float kEvsmNegativeExponent32 = 5.0f;

struct EvsmWarp {
    int channels = 4;                   // 2: positive warp only (EVSM2); 4: both (EVSM4)
    std::optional<float> positive{};    // c+ in (0, max]; unset: the default for the quantization
    std::optional<float> negative{};    // c- in (0, max]; unset: likewise (EVSM4 only)
    Quantization quantization = Quantization::None;  // None (exact) or Bits32 (float tables)
};
float default_evsm_exponent(Quantization quantization, bool positive);

struct EvsmTable {
    MomentTable sums;                   // `channels` planes: w+, w+^2 [, |w-|, w-^2]
    int channels = 4;
    float positive = 0.0f, negative = 0.0f;  // the exponents used
    Quantization quantization = Quantization::None;
};

EvsmTable build_evsm_table(Context& context, const Image& depth, const EvsmWarp& warp = {},
                           Precision precision = Precision::Exact, const DepthConvention& convention = {});

struct EvsmOptions {
    int radius = 2;
    float min_variance = 2e-5f;         // depth^2 (as VSM's), scaled by the warp's slope; >= 0
    float bleed = 0.0f;                 // light-bleeding reduction in [0, 1)
    float depth_bias = 0.0f;            // >= 0 and < 1
    DepthConvention depth_convention{}; // the receivers' z; a table's must equal it
};

Image evsm(Context& context, const EvsmTable& table, const Image& receivers, const EvsmOptions& options = {});
void evsm(Context& context, const EvsmTable& table, const Image& receivers, const EvsmOptions& options, Image& out);

// EVSM with the window's warps summed directly from the shadow map (`depth`)
// under `warp` (its quantization must be None: the warps in double, as the
// exact table holds them), no table; faster than the table's lookup for
// radius <= kEvsmDirectMaxRadius (docs/moment_table.md), which `penumbra
// shade` then picks.
inline constexpr int kEvsmDirectMaxRadius = 0;
Image evsm(Context& context, const Image& depth, const EvsmWarp& warp, const Image& receivers,
           const EvsmOptions& options = {});
void evsm(Context& context, const Image& depth, const EvsmWarp& warp, const Image& receivers,
          const EvsmOptions& options, Image& out);

std::string to_string(Quantization quantization);
// "none", "16" or "32"; throws Error(InvalidArgument) otherwise.
Quantization parse_quantization(const std::string& bits);

}  // namespace penumbra
