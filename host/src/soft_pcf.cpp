// Host operations pcss() and burley(): validate, fill SoftPcfParams, run the
// lookup (kernels/pcss.h, kernels/burley.h) on the shadow map itself.
#include "penumbra/soft_pcf.h"

#include <string>

#include "checked_lookup.h"
#include "visibility_output.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

// The map and receivers every soft member reads. The map is scanned for
// values outside [0, 1] up front: the kernels do not flag them (a NaN depth
// would silently count as neither blocker nor lit).
void check_inputs(const std::string& op, const Image& map, const Image& receivers)
{
    require(!map.empty(), op, "depth", "the shadow map is empty (0 pixels)");
    require(map.channels() == 1, op, "depth",
            "the shadow map must have one channel (depth), got " + std::to_string(map.channels()));
    require_unit_depths(map, op);
    require(!receivers.empty(), op, "receivers", "the receivers image is empty (0 pixels)");
    require(receivers.channels() == 3, op, "receivers",
            "receivers must have 3 channels (u, v, z), got " + std::to_string(receivers.channels()));
}

void check_samples(const std::string& op, int blocker_samples, int filter_samples)
{
    check(kBlockerSamplesRange, blocker_samples, op);
    check(kFilterSamplesRange, filter_samples, op);
}

// The inputs' geometry and the family's constant bias (kernels/depth_bias.h);
// run() adds the output's.
SoftPcfParams base_params(const Image& map, const Image& receivers, float bias, int blocker_samples,
                          int filter_samples)
{
    SoftPcfParams p{};
    p.depth = detail::dims_of(map);
    p.receivers = detail::dims_of(receivers);
    p.bias.mode = PN_BIAS_CONSTANT;
    p.bias.depth_bias = bias;
    p.blocker_samples = blocker_samples;
    p.filter_samples = filter_samples;
    return p;
}

template <detail::KernelId K>
Image run(Context& context, const std::string& op, const Image& map, const Image& receivers,
          SoftPcfParams p)
{
    return detail::visibility_output(receivers, [&](Image& out) {
        p.out = detail::dims_of(out);
        detail::checked_lookup(op, receivers, [&](int* bad_rows) {
            detail::receiver_lookup<K>(context.impl(), map, receivers, p, out, bad_rows);
        });
    });
}

}  // namespace

Image pcss(Context& context, const Image& map, const Image& receivers, const PcssOptions& options)
{
    const std::string op = "pcss";
    check_inputs(op, map, receivers);
    check(kPcssLightSizeRange, options.light_size, op);
    check(kDepthBiasRange, options.depth_bias, op);
    check_samples(op, options.blocker_samples, options.filter_samples);
    SoftPcfParams p = base_params(map, receivers, options.depth_bias, options.blocker_samples,
                                  options.filter_samples);
    p.light_size = options.light_size;
    return run<detail::KernelId::pcss>(context, op, map, receivers, p);
}

Image burley(Context& context, const Image& map, const Image& receivers, const BurleyOptions& options)
{
    const std::string op = "burley";
    check_inputs(op, map, receivers);
    check(kMinRadiusRange, options.min_radius, op);
    check(kMaxRadiusRange, options.max_radius, op);
    require(options.min_radius <= options.max_radius, op, "min-radius",
            "min-radius " + std::to_string(options.min_radius) + " exceeds max-radius " +
                std::to_string(options.max_radius));
    check(kDepthBiasRange, options.base_bias, op);
    check(kBiasSlopeRange, options.bias_slope, op);
    check(kFalloffRange, options.falloff, op);
    check_samples(op, options.blocker_samples, options.filter_samples);
    SoftPcfParams p = base_params(map, receivers, options.base_bias, options.blocker_samples,
                                  options.filter_samples);
    p.min_radius = options.min_radius;
    p.max_radius = options.max_radius;
    p.bias_slope = options.bias_slope;
    p.falloff = options.falloff;
    return run<detail::KernelId::burley>(context, op, map, receivers, p);
}

}  // namespace penumbra
