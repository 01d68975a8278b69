// Host operations pcss() and burley(): validate, fill SoftPcfParams, run the
// lookup (kernels/pcss.h, kernels/burley.h) on the shadow map itself, with
// the family's bias (penumbra/pcf.h; its receiver preparation, pcf_receivers).
#include "penumbra/soft_pcf.h"

#include <string>

#include "checked_lookup.h"
#include "pcf_bias.h"
#include "visibility_output.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

// The map every soft member reads. It is scanned for values outside [0, 1]
// up front: the kernels do not flag them (a NaN depth would silently count
// as neither blocker nor lit).
void check_map(const std::string& op, const Image& map)
{
    require(!map.empty(), op, "depth", "the shadow map is empty (0 pixels)");
    require(map.channels() == 1, op, "depth",
            "the shadow map must have one channel (depth), got " + std::to_string(map.channels()));
    require_unit_depths(map, op);
}

void check_samples(const std::string& op, int blocker_samples, int filter_samples)
{
    check(kBlockerSamplesRange, blocker_samples, op);
    check(kFilterSamplesRange, filter_samples, op);
}

// Checks the map and the bias, prepares the receivers (derivative planes when
// the bias mode reads them, pcf_receivers) and runs K.
template <detail::KernelId K>
void run(Context& context, const std::string& op, const Image& map, const Image& receivers, const DepthBias& bias,
         SoftPcfParams p, Image& out)
{
    check_map(op, map);
    require(!receivers.empty(), op, "receivers", "the receivers image is empty (0 pixels)");
    require(receivers.channels() >= 3, op, "receivers",
            "receivers must have channels u, v, z, got " + std::to_string(receivers.channels()));
    // The constant bias reads u, v, z only: no copy of the receivers for it.
    check(kDepthBiasRange, bias.constant, op);
    const bool derivatives = bias.mode != BiasMode::Constant;
    const Image planes = derivatives ? pcf_receivers(receivers, bias, op) : Image{};
    const Image& prepared = derivatives ? planes : receivers;
    require(out.channels() == 1 && out.width() == receivers.width() && out.height() == receivers.height(), op,
            "the output must be a 1-channel image of the receivers' size (" + std::to_string(receivers.width()) +
                "x" + std::to_string(receivers.height()) + ")");
    p.depth = detail::dims_of(map);
    p.receivers = detail::dims_of(prepared);
    p.out = detail::dims_of(out);
    p.bias = detail::kernel_bias(bias);
    detail::checked_lookup(op, prepared, [&](int* bad_rows) {
        detail::receiver_lookup<K>(context.impl(), map, prepared, p, out, bad_rows);
    });
}

}  // namespace

Image pcss(Context& context, const Image& map, const Image& receivers, const PcssOptions& options)
{
    return detail::visibility_output(receivers, [&](Image& out) { pcss(context, map, receivers, options, out); });
}

Image burley(Context& context, const Image& map, const Image& receivers, const BurleyOptions& options)
{
    return detail::visibility_output(receivers, [&](Image& out) { burley(context, map, receivers, options, out); });
}

void pcss(Context& context, const Image& map, const Image& receivers, const PcssOptions& options, Image& out)
{
    const std::string op = "pcss";
    check(kPcssLightSizeRange, options.light_size, op);
    check_samples(op, options.blocker_samples, options.filter_samples);
    SoftPcfParams p{};
    p.blocker_samples = options.blocker_samples;
    p.filter_samples = options.filter_samples;
    p.light_size = options.light_size;
    run<detail::KernelId::pcss>(context, op, map, receivers, options.bias, p, out);
}

void burley(Context& context, const Image& map, const Image& receivers, const BurleyOptions& options, Image& out)
{
    const std::string op = "burley";
    check(kMinRadiusRange, options.min_radius, op);
    check(kMaxRadiusRange, options.max_radius, op);
    require(options.min_radius <= options.max_radius, op, "min-radius",
            "min-radius " + std::to_string(options.min_radius) + " exceeds max-radius " +
                std::to_string(options.max_radius));
    check(kBiasSlopeRange, options.bias_slope, op);
    check(kFalloffRange, options.falloff, op);
    check_samples(op, options.blocker_samples, options.filter_samples);
    SoftPcfParams p{};
    p.blocker_samples = options.blocker_samples;
    p.filter_samples = options.filter_samples;
    p.min_radius = options.min_radius;
    p.max_radius = options.max_radius;
    p.bias_slope = options.bias_slope;
    p.falloff = options.falloff;
    run<detail::KernelId::burley>(context, op, map, receivers, options.bias, p, out);
}

}  // namespace penumbra
