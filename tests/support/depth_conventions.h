// The depth conventions' float64 reference (penumbra/depth_convention.h),
// written from their definitions, not from the kernels' rational forms:
// a normalised linear depth l is the distance d = near + l (far - near);
// linear stores d, perspective the D3D / Vulkan depth
// z = far (d - near) / (d (far - near)), reversed 1 - z. Back: d from the
// stored value (d = near far / (far - z (far - near))), then l.
#pragma once

#include <cmath>
#include <string>

#include "penumbra/depth_convention.h"
#include "penumbra/image.h"

namespace penumbra::testing {

inline double distance_of(double l, const DepthConvention& c) { return c.near + l * (double(c.far) - c.near); }

// The stored value of normalised depth l, in double.
inline double stored_from_normalized(double l, const DepthConvention& c)
{
    const double n = c.near, f = c.far, d = distance_of(l, c);
    const double projected = f * (d - n) / (d * (f - n));
    switch (c.kind) {
    case DepthConventionKind::Normalized: return l;
    case DepthConventionKind::Linear: return d;
    case DepthConventionKind::Perspective: return projected;
    case DepthConventionKind::Reversed: return 1.0 - projected;
    }
    return l;
}

// Normalised depth of a stored value, in double.
inline double normalized_from_stored(double s, const DepthConvention& c)
{
    const double n = c.near, f = c.far;
    const auto from_projected = [&](double z) { return (n * f / (f - z * (f - n)) - n) / (f - n); };
    switch (c.kind) {
    case DepthConventionKind::Normalized: return s;
    case DepthConventionKind::Linear: return (s - n) / (f - n);
    case DepthConventionKind::Perspective: return from_projected(s);
    case DepthConventionKind::Reversed: return from_projected(1.0 - s);
    }
    return s;
}

// `image` with channel `channel` mapped value by value through `f` (in
// double from the float32 values, stored float32).
template <class F>
Image with_channel_mapped(const Image& image, int channel, F&& f)
{
    Image out = image;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) out.at(channel, x, y) = float(f(double(image.at(channel, x, y))));
    return out;
}

// Channel `channel` of `image` rewritten in convention `c`.
inline Image in_convention(const Image& image, int channel, const DepthConvention& c)
{
    return with_channel_mapped(image, channel, [&](double l) { return stored_from_normalized(l, c); });
}

// The same channel brought back to normalised depth: the normalised map the
// convention's float32 storage actually holds.
inline Image back_to_normalized(const Image& image, int channel, const DepthConvention& c)
{
    return with_channel_mapped(image, channel, [&](double s) { return normalized_from_stored(s, c); });
}

// The conventions the tests run: each kind at a light of near 0.5, far 50
// (k = (far - near) / near = 99: perspective keeps the far half of the range
// in the last 1% of its values).
inline DepthConvention convention_of(DepthConventionKind kind)
{
    if (kind == DepthConventionKind::Normalized) return {};
    return DepthConvention{kind, 0.5f, 50.0f};
}

inline constexpr DepthConventionKind kAllConventions[] = {DepthConventionKind::Normalized, DepthConventionKind::Linear,
                                                           DepthConventionKind::Perspective,
                                                           DepthConventionKind::Reversed};

}  // namespace penumbra::testing
