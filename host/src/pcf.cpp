// Host operations of the percentage-closer family (penumbra/pcf.h): check the
// options and inputs, prepare the receivers' derivative planes when the bias
// mode reads them, fill PcfParams, run the entry through the generic lookup.
#include "penumbra/pcf.h"

#include <string>

#include "checked_lookup.h"
#include "pcf_bias.h"
#include "host/backend/backend.h"
#include "receiver_plane.h"
#include "penumbra/error.h"
#include "penumbra/parameter_range.h"

namespace penumbra {
namespace {

static_assert(kPcfMaxGrid == PN_PCF_MAX_GRID && kPcfGridRange.high == PN_PCF_MAX_GRID);
static_assert(kPcfMaxTaps == PN_PCF_MAX_TAPS && kPcfTapsRange.high == PN_PCF_MAX_TAPS);

void check_bias(const DepthBias& b, const std::string& op)
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

bool reads_derivatives(const DepthBias& b) { return b.mode != BiasMode::Constant; }

void check_receivers(const Image& receivers, const DepthBias& b, const std::string& op)
{
    require(!receivers.empty(), op, "receivers", "the receivers image is empty (0 pixels)");
    const bool channels = reads_derivatives(b) && b.derivatives == DerivativeSource::Channels;
    if (channels && receivers.channels() < 5)
        throw Error(ErrorCategory::InvalidArgument, op, "receivers",
                    "has no channels dzdu, dzdv, which the derivatives from channels read; add them or take "
                    "the derivatives by finite differences");
    require(receivers.channels() >= 3, op, "receivers",
            "receivers must have channels u, v, z, got " + std::to_string(receivers.channels()));
}

// Checks the map, the receivers and the bias; runs K over the prepared receivers.
template <detail::KernelId K>
Image run(Context& context, const Image& map, const Image& receivers, const DepthBias& bias, PcfParams p,
          const std::string& op)
{
    require(!map.empty(), op, "depth", "the shadow map is empty (0 texels)");
    require(map.channels() == 1, op, "depth", "the shadow map must have one channel (depth)");
    check_bias(bias, op);
    check_receivers(receivers, bias, op);
    require_unit_depths(map, op);
    if (reads_derivatives(bias) && bias.derivatives == DerivativeSource::Channels)
        require_finite(receivers, op, "the receivers image", "receivers");
    const Image prepared = reads_derivatives(bias) ? pcf_receivers(receivers, bias, op) : Image{};
    const Image& rx = reads_derivatives(bias) ? prepared : receivers;
    Image out(receivers.width(), receivers.height(), 1);
    p.depth = detail::dims_of(map);
    p.receivers = detail::dims_of(rx);
    p.out = detail::dims_of(out);
    p.bias = detail::kernel_bias(bias);
    detail::checked_lookup(op, rx, [&](int* bad_rows) {
        detail::receiver_lookup<K>(context.impl(), map, rx, p, out, bad_rows);
    });
    return out;
}

}  // namespace

Image pcf_receivers(const Image& receivers, const DepthBias& bias, const std::string& op)
{
    check_bias(bias, op);
    check_receivers(receivers, bias, op);
    if (!reads_derivatives(bias)) return receivers;
    return bias.derivatives == DerivativeSource::Channels ? detail::receivers_with_channels(receivers)
                                                          : detail::receivers_with_differences(receivers);
}

Image pcf(Context& context, const Image& map, const Image& receivers, const PcfOptions& o)
{
    const std::string op = "pcf";
    check(kRadiusRange, o.radius, op);
    PcfParams p{};
    p.radius = o.radius;
    return run<detail::KernelId::pcf>(context, map, receivers, o.bias, p, op);
}

Image pcf_gauss(Context& context, const Image& map, const Image& receivers, const PcfGaussOptions& o)
{
    const std::string op = "pcf-gauss";
    check(kPcfGridRange, o.grid, op);
    check(kPcfSigmaRange, o.sigma, op);
    PcfParams p{};
    p.grid = o.grid;
    p.sigma = o.sigma;
    return run<detail::KernelId::pcf_gauss>(context, map, receivers, o.bias, p, op);
}

Image pcf_disc(Context& context, const Image& map, const Image& receivers, const PcfDiscOptions& o)
{
    const std::string op = "pcf-disc";
    check(kPcfTapsRange, o.taps, op);
    check(kPcfDiscRadiusRange, o.radius, op);
    PcfParams p{};
    p.taps = o.taps;
    p.disc_radius = o.radius;
    p.rotate = o.rotate ? 1 : 0;
    return run<detail::KernelId::pcf_disc>(context, map, receivers, o.bias, p, op);
}

}  // namespace penumbra
