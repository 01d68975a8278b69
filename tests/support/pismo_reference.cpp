// Pismo's shadow-ray test in float64 (support/pismo_reference.h).
#include "support/pismo_reference.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdint>

#include "penumbra/reference/ground_truth.h"

namespace penumbra::testing {
namespace {

using reference::Ray;
using reference::Vec3;

Vec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

// Where p lands in a map: its pixel, its radial depth, and a texel's footprint there.
struct Landing {
    int x = 0, y = 0;
    double depth = 0, texel = 0;
};

std::optional<Landing> land(const LayeredDepthMap& map, Vec3 p)
{
    const MapCamera& c = map.camera();
    const Vec3 local = p - vec(c.position);
    const double d = dot(local, vec(c.forward));
    if (!(d > 0)) return std::nullopt;
    const double u = 0.5 + dot(local, vec(c.right)) / (2 * d * c.tan_half_fov);
    const double v = 0.5 + dot(local, vec(c.down)) / (2 * d * c.tan_half_fov);
    const double x = std::floor(u * map.width()), y = std::floor(v * map.height());
    if (!(x >= 0 && x < map.width() && y >= 0 && y < map.height())) return std::nullopt;
    const double depth = length(local);
    const double texel = 2 * c.tan_half_fov * depth / map.width();
    return Landing{int(x), int(y), depth, texel};
}

// The receiver: its position, its normal (zero: unknown), the options, and
// the point its maps test (`at`: p, or p lifted by options.lift_texels).
struct Receiver {
    Vec3 p, n;
    const PismoReferenceOptions& o;
    Vec3 at;
    int surface = -1;  // P's surface id, -1 unknown

    bool has_normal() const { return dot(n, n) > 0; }
    bool lifted() const { return at.x != p.x || at.y != p.y || at.z != p.z; }
    // Whether P's own surface faces away from `towards`: a ray there enters P's solid.
    bool faces_away(Vec3 towards) const { return has_normal() && dot(n, towards - p) <= 0; }
    // The bias in texels in `map`: the fixed one, plus the depth P's own
    // surface spans across a texel seen from the map's vertex (tan theta).
    double bias_texels(const LayeredDepthMap& map) const
    {
        if (!has_normal() || lifted()) return o.bias_texels;
        const double c = dot(normalize(n), normalize(vec(map.camera().position) - p));
        if (c <= 0) return o.bias_texels;
        return o.bias_texels + std::min(std::sqrt(std::max(0.0, 1 - c * c)) / c, o.max_slope);
    }
};

// The depth limits of a hard test at P: a layer of P's own surface occludes
// nearer than `own` (none with skip_own_layers), any other nearer than `other`.
// Without ids (either side), every layer is P's own as far as the test knows.
struct Limits {
    double own, other;
    int surface;  // P's id when the ids take part, else -1
};

Limits limits(const LayeredDepthMap& map, const Landing& at_p, std::span<const std::int32_t> ids, const Receiver& r)
{
    const double own = at_p.depth - r.bias_texels(map) * at_p.texel;
    if (!(r.o.surface_ids && r.surface >= 0 && !ids.empty())) return {own, own, -1};
    return {r.o.skip_own_layers ? -INFINITY : own, at_p.depth - r.o.other_bias_texels * at_p.texel, r.surface};
}

bool within(const Limits& l, double depth, int surface)
{
    return l.surface >= 0 && surface != l.surface ? depth < l.other : depth < l.own;
}

// The exact test along the ray from `vertex` through q: a caster crossing
// within the limits (exact_casters' hits name surfaces as the ids do).
bool exactly_occluded(Vec3 vertex, Vec3 q, const Limits& l, const Receiver& r)
{
    const Ray ray{vertex, normalize(q - vertex)};
    if (l.surface < 0) return r.o.exact_casters->occluded(ray, 0, l.own);
    for (double t = 0;;) {
        const std::optional<reference::Hit> hit = r.o.exact_casters->closest_hit(ray, t, std::max(l.own, l.other));
        if (!hit) return false;
        if (within(l, hit->t, hit->primitive)) return true;
        t = hit->t;
    }
}

// Whether a layer of `map` at q's pixel lies nearer than P's depth (minus the
// bias); P's own solid blocks a map whose vertex its surface faces away from.
// With options.exact_tests, the ray from the map's vertex through q itself
// answers (a caster nearer than the same limit), not the ray through the
// centre of q's pixel.
bool occludes(const LayeredDepthMap& map, std::span<const std::int32_t> ids, Vec3 q, const Receiver& r)
{
    const Vec3 vertex = vec(map.camera().position);
    if (r.faces_away(vertex)) return true;
    const std::optional<Landing> at_q = land(map, q);
    const std::optional<Landing> at_p = land(map, r.at);
    if (!at_q || !at_p) return false;  // outside the map: no caster was seen there
    const Limits l = limits(map, *at_p, ids, r);
    if (r.o.exact_tests) return exactly_occluded(vertex, q, l, r);
    const std::size_t pixel = std::size_t(at_q->y) * std::size_t(map.width()) + std::size_t(at_q->x);
    for (std::uint32_t i = map.offsets()[pixel]; i < map.offsets()[pixel + 1]; ++i)
        if (within(l, double(map.depths()[i]), l.surface < 0 ? -1 : ids[i])) return true;
    return false;
}

std::span<const std::int32_t> ids_of(const PismoReferenceMaps& maps, std::size_t j)
{
    return maps.test_ids.empty() ? std::span<const std::int32_t>{} : std::span<const std::int32_t>(maps.test_ids[j]);
}

// With options.exact_estimate: the putative occluder of the ray to `light` is
// the caster crossing nearest P on it (traced from P lifted as the truth
// lifts it), or P itself when the ray is clear.
Vec3 exact_occluder(Vec3 light, const Receiver& r)
{
    const double lift = reference::kNormalOffset * (1 + max_abs_component(r.at));
    const Vec3 origin = r.has_normal() ? r.at + normalize(r.n) * lift : r.at;
    const Vec3 to_light = light - origin;
    const std::optional<reference::Hit> hit =
        r.o.exact_casters->closest_hit({origin, normalize(to_light)}, lift, length(to_light));
    return hit ? origin + normalize(to_light) * hit->t : r.at;
}

// The first estimate of one map: the depth of the farthest bled layer nearer
// than p (the occluder nearest p), if any.
std::optional<double> nearest_occluder_depth(const LayeredDepthMap& bled, const Receiver& r)
{
    const std::optional<Landing> at = land(bled, r.at);
    if (!at) return std::nullopt;
    std::optional<double> nearest;
    for (float layer : bled.layers(at->x, at->y))
        if (double(layer) < at->depth - r.bias_texels(bled) * at->texel) nearest = double(layer);
    return nearest;
}

// The ray pattern (host/src/pismo_rays.h states it; written here again from
// that statement): stratum (i, j) of triangle t, index q = j n + i, jittered
// by (lowbias32(k) >> 8) / 2^24 with k = 2 (4096 t + q) and k + 1, mod 2^32.
double jitter(std::uint32_t k)
{
    k = (k ^ (k >> 16)) * 0x7feb352du;
    k = (k ^ (k >> 15)) * 0x846ca68bu;
    k ^= k >> 16;
    return std::ldexp(double(k >> 8), -24);
}

// A point of the unit square to barycentric weights, area-preserving.
std::array<double, 3> barycentric(double a, double b)
{
    const double r = std::sqrt(a);
    return {1 - r, r * (1 - b), r * b};
}

}  // namespace

bool hard_shadow_test(const LayeredDepthMap& map, Vec3 p, double bias_texels)
{
    PismoReferenceOptions o;
    o.bias_texels = bias_texels;
    return occludes(map, {}, p, Receiver{p, {}, o, p});
}

bool hard_shadow_test(const LayeredDepthMap& map, Vec3 p, Vec3 normal, const PismoReferenceOptions& options)
{
    return occludes(map, {}, p, Receiver{p, normal, options, p});
}

bool hard_shadow_test(const LayeredDepthMap& map, std::span<const std::int32_t> ids, Vec3 p, Vec3 normal, int surface,
                      const PismoReferenceOptions& options)
{
    return occludes(map, ids, p, Receiver{p, normal, options, p, surface});
}

PismoReferenceMaps PismoReferenceMaps::layered(const reference::PismoMaps& maps)
{
    PismoReferenceMaps out{&maps, maps.maps, {}, maps.surface_ids};
    for (const LayeredDepthMap& map : maps.maps) out.bled.push_back(bleed_empty_pixels(map));
    return out;
}

PismoReferenceMaps PismoReferenceMaps::maximum_depth(const reference::PismoMaps& maps)
{
    PismoReferenceMaps out{&maps, {}, {}, {}};
    for (const LayeredDepthMap& map : maps.maps) {
        out.test.push_back(maximum_depth_map(map));
        out.bled.push_back(bleed_empty_pixels(out.test.back()));
    }
    return out;
}

// The point P's maps test: P, or with options.lift_texels, where P's surface
// is grazing from the light (tan theta above kLiftAboveSlope), P lifted
// along its normal; the slope term stays below that.
constexpr double kLiftAboveSlope = 2;

Vec3 tested_point(const PismoReferenceMaps& maps, Vec3 p, Vec3 n, const PismoReferenceOptions& o)
{
    if (!(o.lift_texels > 0) || !(dot(n, n) > 0)) return p;
    const LayeredDepthMap& first = maps.test.front();
    const MapCamera& c = first.camera();
    const double texel = 2 * c.tan_half_fov * length(p - vec(c.position)) / first.width();
    Vec3 centre{};
    for (const Vec3& v : maps.source->mesh.vertices) centre = centre + v * (1.0 / double(maps.source->mesh.vertices.size()));
    const double cosine = dot(normalize(n), normalize(centre - p));
    const double sine = std::sqrt(std::max(0.0, 1 - cosine * cosine));
    if (sine <= kLiftAboveSlope * cosine) return p;  // not grazing: the slope term, as the method
    return p + normalize(n) * (o.lift_texels * texel * sine);
}

double pismo_visibility(const PismoReferenceMaps& maps, Vec3 p, const PismoReferenceOptions& o, Vec3 normal,
                        int surface)
{
    const reference::LightMesh& mesh = maps.source->mesh;
    const Receiver r{p, normal, o, tested_point(maps, p, normal, o), surface};
    std::vector<std::optional<double>> estimate(mesh.vertices.size());
    for (std::size_t j = 0; j < estimate.size(); ++j) estimate[j] = nearest_occluder_depth(maps.bled[j], r);
    const double total_area = mesh.area();
    double occlusion = 0;
    for (int t = 0; t < int(mesh.triangles.size()); ++t) {
        const auto& corners = mesh.triangles[std::size_t(t)];
        const double share = mesh.triangle_area(t) / total_area;
        const int n = std::max(1, int(std::lround(std::sqrt(o.rays * share))));
        for (int sj = 0; sj < n; ++sj)
            for (int si = 0; si < n; ++si) {
                const std::uint32_t k = 2u * (4096u * std::uint32_t(t) + std::uint32_t(sj * n + si));
                const auto w = barycentric((si + jitter(k)) / n, (sj + jitter(k + 1)) / n);
                Vec3 light{};
                for (int k = 0; k < 3; ++k) light = light + mesh.vertices[std::size_t(corners[k])] * w[k];
                if (r.faces_away(light)) {  // the ray enters P's own solid
                    occlusion += share / (n * n);
                    continue;
                }
                double distance = 0, weight = 0;
                for (int k = 0; k < 3; ++k)
                    if (const auto& d = estimate[std::size_t(corners[k])]) {
                        distance += w[k] * *d;
                        weight += w[k];
                    }
                const Vec3 to_p = r.at - light;
                const Vec3 occluder = o.exact_estimate ? exact_occluder(light, r)
                                      : weight > 0     ? light + to_p * (distance / weight / length(to_p))
                                                       : r.at;
                // A corner whose vertex P's surface faces away from sees P's own
                // solid, not what this ray (above P's tangent plane) passes: the
                // other corners answer, renormalised; none left: the ray is lit.
                double blocked = 0, answering = 0;
                for (int k = 0; k < 3; ++k) {
                    const auto j = std::size_t(corners[k]);
                    const LayeredDepthMap& map = maps.test[j];
                    if (r.faces_away(vec(map.camera().position))) continue;
                    blocked += w[k] * occludes(map, ids_of(maps, j), occluder, r);
                    answering += w[k];
                }
                occlusion += answering > 0 ? share * blocked / answering / (n * n) : 0;
            }
    }
    return std::clamp(1 - occlusion, 0.0, 1.0);
}

double averaged_hard_shadows(const PismoReferenceMaps& maps, Vec3 p, const PismoReferenceOptions& o, Vec3 normal,
                             int surface)
{
    const std::vector<double> weights = maps.source->mesh.vertex_weights();
    const Receiver r{p, normal, o, tested_point(maps, p, normal, o), surface};
    double occlusion = 0;
    for (std::size_t j = 0; j < weights.size(); ++j)
        occlusion += weights[j] * occludes(maps.test[j], ids_of(maps, j), r.at, r);
    return std::clamp(1 - occlusion, 0.0, 1.0);
}

}  // namespace penumbra::testing
