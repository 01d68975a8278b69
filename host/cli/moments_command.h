// The moment family's methods of `penumbra shade` (msm, msm-soft, evsm2,
// evsm4): their options, checked before any file is read, and the run.
#pragma once

#include <optional>
#include <string>

#include "args.h"
#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"
#include "penumbra/moments.h"

namespace penumbra::cli {

// The options `shade` accepts for these methods (with its own).
inline constexpr const char* kMomentOptionNames[] = {"--moment-bias", "--depth-bias", "--quantize", "--exponents"};

bool is_moment_method(const std::string& method);

struct MomentShadeSettings {
    std::string method;
    Quantization quantization = Quantization::None;
    MsmOptions msm;
    MsmSoftOptions soft;
    EvsmWarp warp;
    EvsmOptions evsm;
};

// Throws UsageError naming the option.
MomentShadeSettings parse_moment_settings(const std::string& method, const Args& args);

// Builds the method's table from `map` and shades `receivers`.
Image shade_moments(Context& context, const MomentShadeSettings& settings, const Image& map, const Image& receivers);

}  // namespace penumbra::cli
