// The valid range of each numeric parameter of the shading operations,
// declared once: the operations check their options against these
// (vsm(), vssm(), msm(), msm_soft(), evsm(), build_evsm_table()), and the
// method table (penumbra/methods.h) prints them in its help. A caller (the
// CLI) does not check them again; it maps Error::parameter() to its own name.
#pragma once

#include <limits>
#include <string>
#include <string_view>

#include "penumbra/moment_table.h"

namespace penumbra {

struct ParameterRange {
    const char* name;         // the API's name, Error::parameter(): "radius"
    const char* label;        // in messages: "radius", "positive exponent"
    double low, high;
    bool low_open, high_open; // (low vs [low; high) vs high]
    // Why the upper bound holds, for the "exceeds" message; empty when the
    // bound is the parameter's meaning (a share below 1), not a storage limit.
    const char* why_high = "";
};

inline constexpr double kNoUpperBound = std::numeric_limits<double>::infinity();

// Window radius in texels, window (2r+1)^2: the exact tables keep every sum
// of at most 255 x 255 texels exact (penumbra/moment_table.h, kExactMaxRadius).
inline constexpr ParameterRange kRadiusRange{
    "radius", "radius", 0, kExactMaxRadius, false, false,
    ", the largest window (255x255 texels) whose sums an exact table keeps exact; use a smaller radius"};
inline constexpr ParameterRange kMinVarianceRange{"min-variance", "min-variance", 0, kNoUpperBound, false, true};
inline constexpr ParameterRange kBleedRange{"bleed", "bleed", 0, 1, false, true};
// The blocker search's own limit depends on the map's size (vssm, msm_soft).
inline constexpr ParameterRange kLightSizeRange{"light-size", "light-size", 0, kNoUpperBound, true, true};
inline constexpr ParameterRange kMomentBiasRange{"moment-bias", "moment-bias", 0, 1, false, true};
inline constexpr ParameterRange kDepthBiasRange{"depth-bias", "depth-bias", 0, 1, false, true};
// msm_soft's receiver-plane bias: the share of the plane's drop over a window
// (1: the receiver's whole plane in the window counts as lit), and its cap.
inline constexpr ParameterRange kPlaneBiasRange{"plane-bias", "plane-bias", 0, 16, false, false};
inline constexpr ParameterRange kPlaneBiasMaxRange{"plane-bias-max", "plane-bias-max", 0, 1, false, false};
// EVSM's warp exponents on the exact 48-bit tables: the warped variance floor
// must stay far above the storage's rounding (penumbra/moments.h,
// kEvsmMaxExponentExact, is this bound); the 16-bit storage lowers it.
inline constexpr ParameterRange kPositiveExponentRange{
    "positive-exponent", "positive exponent", 0, 10, true, false,
    ", the largest the exact 48-bit storage keeps within 2e-4 of the method (docs/moments.md); use a smaller "
    "exponent"};
inline constexpr ParameterRange kNegativeExponentRange{
    "negative-exponent", "negative exponent", kPositiveExponentRange.low, kPositiveExponentRange.high, true,
    false, kPositiveExponentRange.why_high};

// The percentage-closer family (penumbra/pcf.h). The grid and tap limits are
// the kernels' own (kernels/params.h, PN_PCF_MAX_GRID and PN_PCF_MAX_TAPS;
// host/src/pcf.cpp checks that they agree).
inline constexpr ParameterRange kPcfGridRange{
    "grid", "grid", 1, 16, false, false,
    ", the largest grid the kernel's weight arrays hold (a 17x17 texel footprint); use pcf-disc for wider filters"};
// Below 0.1 texel the Gaussian of an even grid underflows to 0 at every tap.
inline constexpr ParameterRange kPcfSigmaRange{"sigma", "sigma", 0.1, kNoUpperBound, false, true};
inline constexpr ParameterRange kPcfTapsRange{
    "taps", "taps", 1, 256, false, false,
    ", the stated limit of the disc (its 16 rotations already spread 4096 distinct taps over 4x4 receivers); "
    "use fewer taps"};
// pcf reads its box texel by texel, no table: the same limit as the tables'
// windows (one radius option for every method), for pcf's own reason.
inline constexpr ParameterRange kPcfRadiusRange{
    "radius", "radius", 0, kExactMaxRadius, false, false,
    ", the widest box pcf filters (255x255 texels, 65025 taps a receiver); for wider penumbrae use pcf-disc, "
    "pcss or vssm"};
inline constexpr ParameterRange kPcfDiscRadiusRange{"disc-radius", "disc radius", 0, kNoUpperBound, true, true};
inline constexpr ParameterRange kSlopeScaleRange{"slope-scale", "slope scale", 0, kNoUpperBound, false, true};
// Depth units: a bias beyond the whole depth range [0, 1] means nothing.
inline constexpr ParameterRange kBiasMinRange{"bias-min", "bias-min", -1, 1, false, false};
inline constexpr ParameterRange kBiasMaxRange{"bias-max", "bias-max", -1, 1, false, false};

// "[0, 1)", ">= 0", "(0, 10]".
std::string describe(const ParameterRange& range);
// False for NaN.
bool contains(const ParameterRange& range, double value);
// Throws Error(InvalidArgument, operation) naming range.name when `value` is
// outside: "radius 128 exceeds 127, <why>" above a storage bound, else
// "bleed must be in [0, 1) (got 1)".
void check(const ParameterRange& range, double value, std::string_view operation);

}  // namespace penumbra
