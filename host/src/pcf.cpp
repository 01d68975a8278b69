// Host operations of the percentage-closer family (penumbra/pcf.h): check the
// options, fill PcfParams, run the entry through the family's checked lookup
// (pcf_family.h, whose checks live here).
#include "penumbra/pcf.h"

#include <string>

#include "pcf_family.h"
#include "receiver_plane.h"
#include "visibility_output.h"
#include "penumbra/error.h"
#include "penumbra/parameter_range.h"

namespace penumbra {
namespace detail {

void check_family_bias(const DepthBias& b, const std::string& op)
{
    check(kDepthBiasRange, b.constant, op);
    check(kSlopeScaleRange, b.slope_scale, op);
    check(kBiasMinRange, b.min, op);
    check(kBiasMaxRange, b.max, op);
    if (b.min > b.max)
        throw Error(ErrorCategory::InvalidArgument, op, "bias-min",
                    "bias-min " + std::to_string(b.min) + " exceeds bias-max " + std::to_string(b.max) +
                        "; the bias is clamped to [bias-min, bias-max]");
}

void check_family_receivers(const Image& receivers, const DepthBias& b, const std::string& op)
{
    require(!receivers.empty(), op, "receivers", "the receivers image is empty (0 pixels)");
    const bool channels = reads_derivatives(b) && b.derivatives == DerivativeSource::Channels;
    if (channels && receivers.channels() < 5)
        throw Error(ErrorCategory::InvalidArgument, op, "receivers",
                    "has no channels dzdu, dzdv, which the derivatives from channels read; add them or take "
                    "the derivatives by finite differences");
    require(receivers.channels() >= 3, op, "receivers",
            "receivers must have channels u, v, z, got " + std::to_string(receivers.channels()));
    if (channels) require_finite(receivers, op, "the receivers image", "receivers");
}
}  // namespace detail

static_assert(kPcfMaxGrid == PN_PCF_MAX_GRID && kPcfGridRange.high == PN_PCF_MAX_GRID);
static_assert(kPcfMaxTaps == PN_PCF_MAX_TAPS && kPcfTapsRange.high == PN_PCF_MAX_TAPS);

Image pcf_receivers(const Image& receivers, const DepthBias& bias, const std::string& op)
{
    detail::check_family_bias(bias, op);
    detail::check_family_receivers(receivers, bias, op);
    if (!detail::reads_derivatives(bias)) return receivers;
    return bias.derivatives == DerivativeSource::Channels ? detail::receivers_with_channels(receivers)
                                                          : detail::receivers_with_differences(receivers);
}

PN_ALLOCATING_VISIBILITY(pcf, Image, PcfOptions)
PN_ALLOCATING_VISIBILITY(pcf_gauss, Image, PcfGaussOptions)
PN_ALLOCATING_VISIBILITY(pcf_disc, Image, PcfDiscOptions)

void pcf(Context& context, const Image& map, const Image& receivers, const PcfOptions& o, Image& out)
{
    const std::string op = "pcf";
    check(kPcfRadiusRange, o.radius, op);
    PcfParams p{};
    p.radius = o.radius;
    detail::family_lookup<detail::KernelId::pcf>(context, op, map, receivers, o.bias, o.depth_convention, p,
                                                       out);
}

void pcf_gauss(Context& context, const Image& map, const Image& receivers, const PcfGaussOptions& o, Image& out)
{
    const std::string op = "pcf-gauss";
    check(kPcfGridRange, o.grid, op);
    check(kPcfSigmaRange, o.sigma, op);
    PcfParams p{};
    p.grid = o.grid;
    p.sigma = o.sigma;
    detail::family_lookup<detail::KernelId::pcf_gauss>(context, op, map, receivers, o.bias, o.depth_convention, p,
                                                       out);
}

void pcf_disc(Context& context, const Image& map, const Image& receivers, const PcfDiscOptions& o, Image& out)
{
    const std::string op = "pcf-disc";
    check(kPcfTapsRange, o.taps, op);
    check(kPcfDiscRadiusRange, o.radius, op);
    PcfParams p{};
    p.taps = o.taps;
    p.disc_radius = o.radius;
    p.rotate = o.rotate ? 1 : 0;
    detail::family_lookup<detail::KernelId::pcf_disc>(context, op, map, receivers, o.bias, o.depth_convention, p,
                                                       out);
}

}  // namespace penumbra
