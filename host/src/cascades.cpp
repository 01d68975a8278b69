// The cascaded shadow mask (penumbra/cascades.h): checks, CascadeParams, and
// the lookup kernels/cascades.h, the stacked maps as its source.
#include "penumbra/cascades.h"

#include <cmath>
#include <string>

#include "checked_lookup.h"
#include "penumbra/error.h"
#include "penumbra/parameter_range.h"

namespace penumbra {
namespace {

const std::string kCascadeMaskOp = "cascade-mask";

static_assert(kMaxCascades == PN_CASCADES_MAX && kCascadeReceiverChannels == PN_CASCADE_PLANES);

bool finite_frame(const CascadeFrame& f)
{
    for (float v : {f.u_scale, f.u_offset, f.v_scale, f.v_offset, f.z_scale, f.z_offset, f.split_far})
        if (!std::isfinite(v)) return false;
    return f.u_scale != 0 && f.v_scale != 0 && f.z_scale != 0;
}

void check_shadows(const CascadeShadows& s)
{
    const int k = int(s.cascades.size());
    require(k >= 1, kCascadeMaskOp, "cascades", "no cascades: give 1 to " + std::to_string(kMaxCascades));
    require(k <= kMaxCascades, kCascadeMaskOp, "cascades",
            std::to_string(k) + " cascades given; at most " + std::to_string(kMaxCascades) +
                " are supported (the kernel's parameter arrays)");
    for (int c = 0; c < k; ++c)
        require(finite_frame(s.cascades[std::size_t(c)]), kCascadeMaskOp, "cascades",
                "cascade " + std::to_string(c) + " has a non-finite or zero scale or offset");
    require(s.maps.channels() == 1 && !s.maps.empty(), kCascadeMaskOp, "maps",
            "the maps must be one non-empty channel of stacked cascades");
    require(s.maps.height() % k == 0, kCascadeMaskOp, "maps",
            "the maps' height " + std::to_string(s.maps.height()) + " is not a multiple of the " +
                std::to_string(k) + " cascades (stack them, each W x H, cascade c in rows [c H, (c + 1) H))");
    detail::check_shadow_map(s.maps, kCascadeMaskOp);
}

void check_options(const CascadeOptions& o)
{
    check(kPcfGridRange, o.grid, kCascadeMaskOp);
    check(kPcfSigmaRange, o.sigma, kCascadeMaskOp);
    auto nonnegative = [](float v, const char* name) {
        require(std::isfinite(v) && v >= 0, kCascadeMaskOp, name,
                std::string(name) + " must be a finite number of texels >= 0 (got " + std::to_string(v) + ")");
    };
    nonnegative(o.static_bias, "static-bias");
    nonnegative(o.bias_min, "bias-min");
    nonnegative(o.bias_max, "bias-max");
    require(o.bias_min <= o.bias_max, kCascadeMaskOp, "bias-min",
            "bias-min " + std::to_string(o.bias_min) + " exceeds bias-max " + std::to_string(o.bias_max));
}

void copy3(const std::array<float, 3>& from, float* to)
{
    for (int i = 0; i < 3; ++i) to[i] = from[std::size_t(i)];
}

CascadeParams cascade_params(const CascadeShadows& s, const CascadeOptions& o)
{
    CascadeParams p{};
    p.cascades = int(s.cascades.size());
    p.map_height = s.maps.height() / p.cascades;
    p.select = o.selection == CascadeSelection::SplitDepth ? PN_CASCADE_SELECT_SPLIT : PN_CASCADE_SELECT_BOX;
    p.grid = o.grid;
    p.sigma = o.sigma;
    copy3(s.axis_u, p.axis_u);
    copy3(s.axis_v, p.axis_v);
    copy3(s.axis_z, p.axis_z);
    const float width = float(s.maps.width());
    for (int c = 0; c < p.cascades; ++c) {
        const CascadeFrame& f = s.cascades[std::size_t(c)];
        p.u_scale[c] = f.u_scale, p.u_offset[c] = f.u_offset;
        p.v_scale[c] = f.v_scale, p.v_offset[c] = f.v_offset;
        p.z_scale[c] = f.z_scale, p.z_offset[c] = f.z_offset;
        p.split_far[c] = f.split_far;
        // The footprint's (grid + 1) texels around the receiver, half of it each side.
        p.margin[c] = 0.5f * float(o.grid + 1) / width;
        // One texel's world size along u, as depth of a 45-degree plane, in z units.
        const float texel = std::abs(f.z_scale / (f.u_scale * width));
        p.static_bias[c] = o.static_bias * texel;
        p.bias_min[c] = o.bias_min * texel;
        p.bias_max[c] = o.bias_max * texel;
    }
    return p;
}

}  // namespace

void cascade_mask(Context& context, const CascadeShadows& shadows, const Image& receivers,
                  const CascadeOptions& options, Image& out)
{
    check_shadows(shadows);
    check_options(options);
    require(!receivers.empty() && receivers.channels() == kCascadeReceiverChannels, kCascadeMaskOp, "receivers",
            "the receivers must be a non-empty image of 5 channels (world x, y, z, view depth, surface flag), got " +
                std::to_string(receivers.channels()));
    require(out.channels() == 2 && out.width() == receivers.width() && out.height() == receivers.height(),
            kCascadeMaskOp, "out",
            "the output must be a 2-channel image (visibility, cascade) of the receivers' size (" +
                std::to_string(receivers.width()) + "x" + std::to_string(receivers.height()) + ")");
    CascadeParams p = cascade_params(shadows, options);
    p.maps = detail::dims_of(shadows.maps);
    p.receivers = detail::dims_of(receivers);
    p.out = detail::dims_of(out);
    detail::checked_lookup(kCascadeMaskOp, receivers, [&](int* bad_rows) {
        detail::receiver_lookup<detail::KernelId::cascade_mask>(context.impl(), shadows.maps, receivers, p, out,
                                                                bad_rows);
    });
}

Image cascade_mask(Context& context, const CascadeShadows& shadows, const Image& receivers,
                   const CascadeOptions& options)
{
    Image out(receivers.width(), receivers.height(), 2, Image::Uninitialized{});
    cascade_mask(context, shadows, receivers, options, out);
    return out;
}

}  // namespace penumbra
