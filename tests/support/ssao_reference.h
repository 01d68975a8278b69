// The float64 mathematics of ssao-vo (kernels/ssao_vo.h) applied to a float32
// view depth, for the fidelity tests and the accuracy tool; and the depth
// images of the closed-form cases (planes, a right-angle groove).
#pragma once

#include <algorithm>
#include <map>
#include <mutex>
#include <cmath>
#include <numbers>

#include "penumbra/image.h"
#include "penumbra/ssao.h"

namespace penumbra::testing {

inline double ssao_focal(int height, double fov_degrees)
{
    return 0.5 * height / std::tan(fov_degrees * std::numbers::pi / 360.0);
}

// The pattern of each size, built once (its raster costs tens of ms).
inline const SsaoPattern& ssao_reference_pattern(int pairs)
{
    static std::mutex lock;
    static std::map<int, SsaoPattern> patterns;
    const std::lock_guard<std::mutex> hold(lock);
    auto found = patterns.find(pairs);
    if (found == patterns.end()) found = patterns.emplace(pairs, ssao_pattern(pairs)).first;
    return found->second;
}

// o (obscurance) at pixel (x, y), as the kernel defines it, in double.
inline double ssao_reference(const Image& depth, double fov_degrees, const SsaoOptions& o, int x, int y)
{
    const double z = depth.at(0, x, y);
    if (!(z > 0)) return 0.0;
    const SsaoPattern& pattern = ssao_reference_pattern(o.pairs);
    const double focal = ssao_focal(depth.height(), fov_degrees);
    const double pixels = std::min(o.radius * focal / z, o.max_screen_radius * depth.height());
    const double sphere = pixels * z / focal;
    const double angle = o.rotate ? ssao_tile_angle(x, y) : 0.0;
    const double c = std::cos(angle), s = std::sin(angle);
    auto round_sym = [](double v) { return v < 0 ? -std::floor(-v + 0.5) : std::floor(v + 0.5); };
    struct Tap {
        double e, u;
    };
    auto tap = [&](double ox, double oy, double h) {
        const double tx = x + ox, ty = y + oy;
        const bool on = tx >= 0 && tx < depth.width() && ty >= 0 && ty < depth.height();
        double zs = on ? depth.at(0, int(tx), int(ty)) : 0.0;
        if (!(zs > 0)) zs = 1e30;
        const double d = z - zs;
        const double fall = std::clamp((o.falloff * sphere - d) / ((o.falloff - 1) * sphere), 0.0, 1.0);
        return Tap{std::clamp(d / (2 * sphere * h), -0.5, 0.5), on ? fall : 0.0};
    };
    auto estimate = [&](Tap a, Tap b) {
        switch (o.unusable) {
        case SsaoUnusable::Paired: return a.u * a.e - (1 - a.u) * b.u * b.e;
        case SsaoUnusable::Zero: return a.u * (a.e + 0.5) - 0.5;
        default: return a.u * a.e;
        }
    };
    double sum = 0, weight = pattern.centre_weight;
    for (const SsaoSample& p : pattern.pairs) {
        const double h = std::sqrt(1 - p.x * p.x - p.y * p.y);
        const double ox = round_sym((c * p.x - s * p.y) * pixels), oy = round_sym((s * p.x + c * p.y) * pixels);
        const Tap a = tap(ox, oy, h), b = tap(-ox, -oy, h);
        sum += p.weight * (estimate(a, b) + estimate(b, a));
        weight += p.weight * (a.u + b.u);
    }
    const double v = std::clamp(0.5 + (o.unusable == SsaoUnusable::Renormalise ? sum / weight : sum), 0.0, 1.0);
    return o.output == SsaoOutput::Accessibility ? 1 - std::clamp(2 * v - 1, 0.0, 1.0) : v;
}

// A plane through the view point at depth z0 in the middle of the image,
// turned `tilt` radians from facing the camera about the screen direction at
// `azimuth`: depth rises by tan(tilt) per world unit across (the kernel's
// model: lines parallel to the view axis, a pixel z0 / focal wide).
inline Image ssao_plane_depth(int w, int h, double fov_degrees, double z0, double tilt, double azimuth)
{
    Image d(w, h, 1);
    const double step = z0 / ssao_focal(h, fov_degrees) * std::tan(tilt);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double along = (x - w / 2) * std::cos(azimuth) + (y - h / 2) * std::sin(azimuth);
            d.at(0, x, y) = float(z0 + step * along);
        }
    return d;
}

// The inside of a right-angle corner seen along its bisector: two walls at
// 45 degrees to the view axis meeting at column `edge`, the edge farthest.
inline Image ssao_corner_depth(int w, int h, double fov_degrees, double z0, int edge)
{
    Image d(w, h, 1);
    const double step = z0 / ssao_focal(h, fov_degrees);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) d.at(0, x, y) = float(z0 - step * std::abs(x - edge));
    return d;
}

}  // namespace penumbra::testing
