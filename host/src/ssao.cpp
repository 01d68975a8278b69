// Host operations of penumbra/ssao.h: check the options and the depth, pack
// the pattern and the rotation tile as the source of the lookup-shaped entry
// ssao_vo (kernels/ssao_vo.h), run it, name the first bad pixel of a
// flagged row; and the pipeline with the cross-bilateral blur.
#include <array>
#include <cmath>
#include <mutex>
#include <numbers>
#include <string>
#include <vector>

#include "host/backend/backend.h"
#include "penumbra/error.h"
#include "penumbra/ssao.h"

namespace penumbra {
namespace {

const std::string kSsaoOp = "ssao";

// The pattern of each size, built once per process (its brute-force volumes
// take tens of milliseconds, a frame's worth).
const SsaoPattern& cached_pattern(int pairs)
{
    static std::array<std::once_flag, kSsaoMaxPairs + 1> once;
    static std::array<SsaoPattern, kSsaoMaxPairs + 1> patterns;
    std::call_once(once[std::size_t(pairs)], [&] { patterns[std::size_t(pairs)] = ssao_pattern(pairs); });
    return patterns[std::size_t(pairs)];
}

// The source: per pair x, y, h = sqrt(1 - x^2 - y^2), weight; then the
// tile's 16 (cos, sin), as one row of floats.
Image pattern_source(const SsaoPattern& pattern)
{
    std::vector<float> v;
    for (const SsaoSample& s : pattern.pairs)
        v.insert(v.end(), {float(s.x), float(s.y), float(std::sqrt(1.0 - s.x * s.x - s.y * s.y)), float(s.weight)});
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const double a = ssao_tile_angle(x, y);
            v.insert(v.end(), {float(std::cos(a)), float(std::sin(a))});
        }
    Image image(int(v.size()), 1, 1);
    std::copy(v.begin(), v.end(), image.plane(0));
    return image;
}

int rule_of(SsaoUnusable u)
{
    switch (u) {
    case SsaoUnusable::Paired: return PN_SSAO_PAIRED;
    case SsaoUnusable::Zero: return PN_SSAO_ZERO;
    case SsaoUnusable::Half: return PN_SSAO_HALF;
    case SsaoUnusable::Renormalise: return PN_SSAO_RENORMALISE;
    }
    throw Error(ErrorCategory::InvalidArgument, kSsaoOp, "unusable", "not an SsaoUnusable value");
}

void check_options(const SsaoOptions& o, double fov_degrees)
{
    check(kSsaoRadiusRange, o.radius, kSsaoOp);
    check(kSsaoPairsRange, o.pairs, kSsaoOp);
    check(kSsaoMaxScreenRadiusRange, o.max_screen_radius, kSsaoOp);
    check(kSsaoFalloffRange, o.falloff, kSsaoOp);
    check(kSsaoFovRange, fov_degrees, kSsaoOp);
}

SsaoParams params_for(const SsaoOptions& o, double fov_degrees, const Image& depth, const Image& out,
                      const SsaoPattern& pattern)
{
    SsaoParams p{};
    p.depth = detail::dims_of(depth);
    p.out = detail::dims_of(out);
    p.pairs = o.pairs;
    p.unusable = rule_of(o.unusable);
    p.rotate = o.rotate ? 1 : 0;
    p.accessibility = o.output == SsaoOutput::Accessibility ? 1 : 0;
    const double focal = 0.5 * depth.height() / std::tan(fov_degrees * std::numbers::pi / 360.0);
    p.radius = float(o.radius);
    p.focal = float(focal);
    p.max_pixels = float(o.max_screen_radius * depth.height());
    p.falloff = float(o.falloff);
    p.centre_weight = float(pattern.centre_weight);
    return p;
}

// The first depth the kernel refused, in the flagged rows.
void report(const std::vector<int>& bad_rows, const Image& depth)
{
    for (int y = 0; y < depth.height(); ++y) {
        if (!bad_rows[std::size_t(y)]) continue;
        for (int x = 0; x < depth.width(); ++x) {
            const float z = depth.at(0, x, y);
            if (std::isfinite(z) && z >= 0.0f) continue;
            throw Error(ErrorCategory::InvalidData, kSsaoOp, "view_depth",
                        "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") of the view depth is " +
                            std::to_string(z) +
                            "; depths must be finite and >= 0 (the distance along the view axis, 0 where no "
                            "surface is seen)",
                        BadPixel{0, x, y, z});
        }
    }
}

}  // namespace

void ssao_obscurance(Context& context, const Image& view_depth, double fov_degrees, const SsaoOptions& options,
                     Image& out)
{
    check_options(options, fov_degrees);
    require(!view_depth.empty() && view_depth.channels() == 1, kSsaoOp, "view_depth",
            "the view depth must have 1 channel and at least one pixel");
    require(out.width() == view_depth.width() && out.height() == view_depth.height() && out.channels() == 1 &&
                out.plane(0) != view_depth.plane(0),
            kSsaoOp, "out", "the output must be another 1-channel image of the view depth's size");
    const SsaoPattern& pattern = cached_pattern(options.pairs);
    const SsaoParams p = params_for(options, fov_degrees, view_depth, out, pattern);
    std::vector<int> bad_rows(std::size_t(view_depth.height()), 0);
    detail::receiver_lookup<detail::KernelId::ssao_vo>(context.impl(), pattern_source(pattern), view_depth, p, out,
                                                       bad_rows.data());
    report(bad_rows, view_depth);
}

Image ssao_obscurance(Context& context, const Image& view_depth, double fov_degrees, const SsaoOptions& options)
{
    Image out(view_depth.width(), view_depth.height(), 1);
    ssao_obscurance(context, view_depth, fov_degrees, options, out);
    return out;
}

BilateralOptions ssao_blur_options()
{
    BilateralOptions b;
    b.radius = 2;
    b.range = BilateralRange::Threshold;
    b.relative = true;
    b.depth_threshold = 0.05f;
    return b;
}

Image ssao_blurred(Context& context, const Image& view_depth, double fov_degrees, const SsaoOptions& options,
                   const BilateralOptions& blur)
{
    const Image raw = ssao_obscurance(context, view_depth, fov_degrees, options);
    return cross_bilateral(context, raw, view_depth, blur);
}

}  // namespace penumbra
