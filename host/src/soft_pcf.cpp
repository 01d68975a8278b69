// Host operations pcss() and burley(): check their options, fill
// SoftPcfParams, run the lookup (kernels/pcss.h, kernels/burley.h) on the
// shadow map itself through the family's checked lookup (pcf_family.h).
#include "penumbra/soft_pcf.h"

#include <cmath>
#include <string>

#include "pcf_family.h"
#include "visibility_output.h"
#include "penumbra/error.h"
#include "penumbra/parameter_range.h"

namespace penumbra {
namespace {

void check_samples(const std::string& op, int blocker_samples, int filter_samples)
{
    check(kBlockerSamplesRange, blocker_samples, op);
    check(kFilterSamplesRange, filter_samples, op);
}

}  // namespace

PN_ALLOCATING_VISIBILITY(pcss, Image, PcssOptions)
PN_ALLOCATING_VISIBILITY(burley, Image, BurleyOptions)

void pcss(Context& context, const Image& map, const Image& receivers, const PcssOptions& options, Image& out)
{
    const std::string op = "pcss";
    check(kPcssLightSizeRange, options.light_size, op);
    check_samples(op, options.blocker_samples, options.filter_samples);
    SoftPcfParams p{};
    p.blocker_samples = options.blocker_samples;
    p.filter_samples = options.filter_samples;
    p.light_size = options.light_size;
    detail::family_lookup<detail::KernelId::pcss>(context, op, map, receivers, options.bias,
                                                 options.depth_convention, p, out);
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
    check(kSlopeAtFarRange, double(options.bias_slope) + double(options.bias_slope_per_depth), op);
    check(kFalloffRange, options.falloff, op);
    check_samples(op, options.blocker_samples, options.filter_samples);
    SoftPcfParams p{};
    p.blocker_samples = options.blocker_samples;
    p.filter_samples = options.filter_samples;
    p.min_radius = options.min_radius;
    p.max_radius = options.max_radius;
    p.bias_slope = options.bias_slope;
    p.bias_slope_per_depth = options.bias_slope_per_depth;
    p.falloff = options.falloff;
    detail::family_lookup<detail::KernelId::burley>(context, op, map, receivers, options.bias,
                                                 options.depth_convention, p, out);
}

BurleyOptions world_cone(BurleyOptions options, float world_slope, const LightFrustum& light)
{
    const std::string op = "world_cone";
    check(kBiasSlopeRange, world_slope, op);
    const auto positive_width = [](float w) { return std::isfinite(w) && w > 0.0f; };
    require(positive_width(light.width_at_near) && positive_width(light.width_at_far), op, "light",
            "the frustum's widths must be finite and > 0 (the map's world width at the near and far planes)");
    require(std::isfinite(light.near) && std::isfinite(light.far) && light.near >= 0.0f && light.far > light.near, op,
            "light", "the frustum needs 0 <= near < far, both finite");
    // In double: the two products are the slope at z = 0 and at z = 1.
    const double per_depth_unit = double(world_slope) / (double(light.far) - double(light.near));
    const double at_near = per_depth_unit * light.width_at_near, at_far = per_depth_unit * light.width_at_far;
    check(kBiasSlopeRange, at_near, op);
    check(kSlopeAtFarRange, at_far, op);
    options.bias_slope = float(at_near);
    options.bias_slope_per_depth = float(at_far - at_near);
    return options;
}

}  // namespace penumbra
