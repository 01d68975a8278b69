// The float64 reference of PCSS and Burley's soft shadows (soft_pcf_reference.h).
#include "support/soft_pcf_reference.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace penumbra::testing {
namespace {

// phi_2(k): the binary digits of k mirrored about the point, digit by digit.
double radical_inverse(int k)
{
    double value = 0, digit = 0.5;
    for (int rest = k; rest > 0; rest /= 2, digit /= 2)
        if (rest % 2) value += digit;
    return value;
}

// Where one tap lands: the texel it reads (clamped into the map) and how far
// its position is from the nearest edge between two texels.
struct TapTexel {
    int tx, ty;
    double edge;
};

// Only the edges between texels decide anything: a position near 0 or near
// `size` reads the edge texel from either side (clamp to edge).
double edge_distance(double t, int size)
{
    const double edge = std::round(t);
    return edge >= 1 && edge <= size - 1 ? std::abs(t - edge) : 1e30;
}

TapTexel tap_texel(const Image& map, const RefReceiver& r, const UnitDiscTap& t, double radius)
{
    const int W = map.width(), H = map.height();
    const double x = std::clamp(r.u, 0.0, 1.0) * W + t.dx * radius * W;
    const double y = std::clamp(r.v, 0.0, 1.0) * H + t.dy * radius * H;
    return {int(std::clamp(std::floor(x), 0.0, W - 1.0)), int(std::clamp(std::floor(y), 0.0, H - 1.0)),
            std::min(edge_distance(x, W), edge_distance(y, H))};
}

// A tap's stored depth and comparison depth (the family's bias, then `cone`
// lower), recording the margins.
struct TapTest {
    double depth, compare;
};

TapTest test_tap(const Image& map, const RefReceiver& r, const RefBias& bias, const UnitDiscTap& t, double radius,
                 double cone, SoftLookup& out)
{
    const TapTexel texel = tap_texel(map, r, t, radius);
    const double depth = map.at(0, texel.tx, texel.ty);
    const double compare = tap_reference(map, r, bias, texel.tx, texel.ty) - cone;
    out.margin = std::min({out.margin, texel.edge, std::abs(depth - compare)});
    return {depth, compare};
}

// Percentage-closer filtering over the uniform disc: the fraction of taps
// lit, tap k lowered by slope * (its radius in texture units).
double disc_visibility(const Image& map, const RefReceiver& r, const RefBias& bias, int n, double radius,
                       double slope, SoftLookup& out)
{
    int lit = 0;
    for (const UnitDiscTap& t : hammersley_disc(n, true)) {
        const TapTest tap = test_tap(map, r, bias, t, radius, slope * t.radius * radius, out);
        lit += tap.depth >= tap.compare;
    }
    return double(lit) / n;
}

}  // namespace

std::vector<UnitDiscTap> hammersley_disc(int n, bool uniform_density)
{
    std::vector<UnitDiscTap> taps;
    for (int k = 0; k < n; ++k) {
        const double angle = 2 * std::numbers::pi * k / n, y = radical_inverse(k);
        const double radius = uniform_density ? std::sqrt(y) : y;
        taps.push_back({radius * std::cos(angle), radius * std::sin(angle), radius});
    }
    return taps;
}

SoftLookup pcss_lookup(const Image& map, const RefReceiver& r, const RefBias& bias, const PcssSettings& s)
{
    SoftLookup out;
    // Step 1, blocker search: the plain mean of the blocking taps' depths over
    // a disc of diameter light_size (Fernando's search width with the near
    // plane at the model light's depth, z = 0).
    double sum = 0;
    int blockers = 0;
    for (const UnitDiscTap& t : hammersley_disc(s.blocker_samples, true)) {
        const TapTest tap = test_tap(map, r, bias, t, 0.5 * s.light_size, 0, out);
        if (tap.depth < tap.compare) sum += tap.depth, ++blockers;
    }
    if (blockers == 0) return out;  // no blocker: fully lit
    out.found = true;
    out.blocker_depth = sum / blockers;
    // Step 2, the penumbra width; step 3, PCF over a disc of diameter w.
    const double occluder = std::max(out.blocker_depth, 1e-4 * r.z);
    out.filter_radius = 0.5 * s.light_size * (r.z - occluder) / occluder;
    out.visibility = disc_visibility(map, r, bias, s.filter_samples, out.filter_radius, 0, out);
    return out;
}

SoftLookup burley_lookup(const Image& map, const RefReceiver& r, const RefBias& bias, const BurleySettings& s)
{
    SoftLookup out;
    const double slope = s.bias_slope + s.bias_slope_per_depth * std::clamp(r.z, 0.0, 1.0);
    // sampleDepth: taps concentrated at the centre (radius y), on the cone,
    // weighted 1 - 0.9 r / R.
    double weighted = 0, total = 0;
    for (const UnitDiscTap& t : hammersley_disc(s.blocker_samples, false)) {
        const TapTest tap = test_tap(map, r, bias, t, s.max_radius, slope * t.radius * s.max_radius, out);
        if (tap.depth < tap.compare) {
            const double weight = 1 - 0.9 * t.radius;
            weighted += weight * tap.depth, total += weight;
        }
    }
    if (total == 0) return out;
    out.found = true;
    out.blocker_depth = weighted / total;
    out.filter_radius = s.min_radius + (s.max_radius - s.min_radius) * (1 - out.blocker_depth / r.z);
    const double occlusion =
        1 - disc_visibility(map, r, bias, s.filter_samples, out.filter_radius, slope, out);
    const double opacity = s.falloff > 0 ? std::clamp(1 - (r.z - out.blocker_depth) / s.falloff, 0.0, 1.0) : 1.0;
    out.visibility = 1 - occlusion * opacity;
    return out;
}

}  // namespace penumbra::testing
