// Depth conventions (penumbra/depth_convention.h): their checks, their
// stored ranges and the kernels' conversion block.
#include "penumbra/depth_convention.h"

#include <cmath>
#include <sstream>

#include "depth_conversion.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

constexpr const char* kNames[] = {"normalized", "linear", "perspective", "reversed"};  // the kind's order

bool reads_near_far(DepthConventionKind kind) { return kind != DepthConventionKind::Normalized; }

std::string number(float value)
{
    if (std::isnan(value)) return "none";
    std::ostringstream text;
    text << value;
    return text.str();
}

}  // namespace

bool same_convention(const DepthConvention& a, const DepthConvention& b)
{
    if (a.kind != b.kind) return false;
    return !reads_near_far(a.kind) || (a.near == b.near && a.far == b.far);
}

void check_depth_convention(const DepthConvention& c, const std::string& op)
{
    if (!reads_near_far(c.kind)) return;
    const std::string kind = to_string(c.kind);
    require(std::isfinite(c.near), op, "near",
            kind + " depth needs a finite near (got " + number(c.near) + "); give the light's near distance");
    require(std::isfinite(c.far), op, "far",
            kind + " depth needs a finite far (got " + number(c.far) +
                "); an infinite far plane maps every finite distance to normalised depth 0: give the scene's "
                "farthest distance from the light");
    if (c.kind != DepthConventionKind::Linear)
        require(c.near > 0.0f, op, "near",
                kind + " depth needs near > 0 (got " + number(c.near) + "): the projection divides by the distance");
    require(c.far > c.near, op, "far",
            kind + " depth needs far > near (got near " + number(c.near) + ", far " + number(c.far) + ")");
}

StoredDepthRange stored_depth_range(const DepthConvention& c)
{
    if (c.kind == DepthConventionKind::Linear) return {c.near, c.far};
    return {};
}

void require_depths_in(const Image& depth, const DepthConvention& c, const std::string& op)
{
    if (c.kind == DepthConventionKind::Normalized) return require_unit_depths(depth, op);
    const StoredDepthRange range = stored_depth_range(c);
    // One parallel pass for the common case; only a bad map pays the scan that names the texel.
    if (depth.channels() == 1 && channel_within(depth, 0, range.low, range.high)) return;
    require_finite(depth, op, "the shadow map", "depth");
    const std::string bounds = "[" + number(range.low) + ", " + number(range.high) + "]";
    for (int y = 0; y < depth.height(); ++y) {
        const float* row = depth.row(0, y);
        for (int x = 0; x < depth.width(); ++x)
            if (row[x] < range.low || row[x] > range.high)
                throw Error(ErrorCategory::InvalidData, op, "depth",
                            "shadow-map depth " + number(row[x]) + " at (" + std::to_string(x) + ", " +
                                std::to_string(y) + ") is outside " + bounds + ", the range of " + describe(c) +
                                "; check the convention, near and far",
                            BadPixel{0, x, y, row[x]});
    }
}

std::string to_string(DepthConventionKind kind) { return kNames[int(kind)]; }

DepthConventionKind parse_depth_convention(const std::string& name)
{
    for (int i = 0; i < 4; ++i)
        if (name == kNames[i]) return DepthConventionKind(i);
    throw Error(ErrorCategory::InvalidArgument, "depth-convention", "depth-convention",
                "'" + name + "' is not normalized, linear, perspective or reversed");
}

std::string describe(const DepthConvention& c)
{
    if (!reads_near_far(c.kind)) return to_string(c.kind) + " depth";
    return to_string(c.kind) + " depth (near " + number(c.near) + ", far " + number(c.far) + ")";
}

namespace detail {

DepthConversion kernel_conversion(const DepthConvention& c)
{
    check_depth_convention(c, "depth-convention");
    DepthConversion k{};
    k.kind = int(c.kind);  // PN_DEPTH_* in DepthConventionKind's order
    const StoredDepthRange range = stored_depth_range(c);
    k.low = range.low;
    k.high = range.high;
    const double near = c.near, far = c.far;
    if (c.kind == DepthConventionKind::Linear) k.scale = float(1.0 / (far - near));
    if (c.kind == DepthConventionKind::Perspective || c.kind == DepthConventionKind::Reversed)
        k.scale = float((far - near) / near);
    return k;
}

DepthConversion receivers_conversion(const std::string& op, const DepthConvention& table,
                                     const DepthConvention& options)
{
    require(same_convention(table, options), op, "depth-convention",
            "the table holds a map of " + describe(table) + " but the receivers are given as " + describe(options) +
                "; the receivers' z is in the map's convention: build the table and shade with the same one");
    return kernel_conversion(options);
}

}  // namespace detail

static_assert(PN_DEPTH_NORMALIZED == int(DepthConventionKind::Normalized) &&
              PN_DEPTH_LINEAR == int(DepthConventionKind::Linear) &&
              PN_DEPTH_PERSPECTIVE == int(DepthConventionKind::Perspective) &&
              PN_DEPTH_REVERSED == int(DepthConventionKind::Reversed));

}  // namespace penumbra
