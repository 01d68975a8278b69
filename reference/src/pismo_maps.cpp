// Pismo's casters, fixation point, vertex cameras and layered depth maps
// (penumbra/reference/pismo_maps.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "penumbra/error.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/pismo_maps.h"

namespace penumbra::reference {
namespace {

constexpr std::string_view kPismoMapsOp = "pismo_maps";
constexpr double kFovMargin = 1.02;
// A ray crosses at most this many surfaces before the render gives up on a
// pixel: a bound on work for rays along thousands of strands, far above any
// cap on kept layers.
constexpr int kMaxCrossings = 4096;

// Whether some point of the light lies in the plane's solid, dot(p - point,
// normal) <= 0: the lowest value over a rectangle is at a corner, over a disk
// it is the centre's minus the radius times the normal's part in the disk's plane.
bool plane_holds_light(const Plane& plane, const AreaLight& light)
{
    const Basis frame = basis_looking_along(light.normal, light.up);
    const double at_centre = dot(light.center - plane.point, plane.normal);
    const double along_s = std::fabs(dot(frame.s, plane.normal)), along_t = std::fabs(dot(frame.t, plane.normal));
    const double reach = light.shape == LightShape::Disk
                             ? 0.5 * light.width * std::hypot(along_s, along_t)
                             : 0.5 * (light.width * along_s + light.height * along_t);
    return at_centre - reach <= 0;
}

std::optional<Bounds> bounded_extent(const Primitive& surface)
{
    if (opacity_of(surface) <= 0) return std::nullopt;
    if (const auto* s = std::get_if<Sphere>(&surface)) return bounds_of(*s);
    if (const auto* b = std::get_if<Box>(&surface)) return bounds_of(OrientedBox::from(*b));
    if (const auto* c = std::get_if<Capsule>(&surface)) return bounds_of(*c);
    return std::nullopt;  // a plane
}

std::optional<Bounds> casters_bounds(const Scene& scene)
{
    std::optional<Bounds> all;
    for (const Primitive& surface : scene_surfaces(scene))
        if (const auto b = bounded_extent(surface)) {
            if (!all) all = Bounds{};
            all->grow(*b);
        }
    return all;
}

Vec3 to_vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
std::array<double, 3> to_array(Vec3 v) { return {v.x, v.y, v.z}; }

// The depth along the light's axis at which the casters' bounding box begins
// (the light camera's near plane when no caster is bounded or it begins sooner).
double nearest_caster_depth(const Scene& scene, const Basis& light)
{
    double nearest = scene.light_camera.far;
    if (const auto b = casters_bounds(scene))
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 p{corner & 1 ? b->hi.x : b->lo.x, corner & 2 ? b->hi.y : b->lo.y,
                         corner & 4 ? b->hi.z : b->lo.z};
            nearest = std::min(nearest, dot(p - scene.light.center, light.n));
        }
    return std::clamp(nearest, scene.light_camera.near, scene.light_camera.far);
}

void check(const LayeredMapOptions& o)
{
    require(o.size >= 1 && o.size <= 8192, kPismoMapsOp, "map-size",
            "the map size must be in [1, 8192], not " + std::to_string(o.size));
    require(o.max_layers >= 1 && o.max_layers <= 64, kPismoMapsOp, "layers",
            "the layers per pixel must be in [1, 64], not " + std::to_string(o.max_layers));
    require(o.prune >= 0 && o.prune <= 0.1, kPismoMapsOp, "prune", "the pruning distance must be in [0, 0.1] (a fraction of the depth)");
}

// The kept depths along one ray (unit direction: t is the distance), and the
// caster each kept layer crosses (a pruned crossing keeps the kept layer's).
void trace_layers(const PreparedScene& casters, const Ray& ray, const LayeredMapOptions& o, std::vector<float>& out,
                  std::vector<std::int32_t>& crossed)
{
    const std::size_t first = out.size();
    double t = 0;
    for (int crossing = 0; crossing < kMaxCrossings && int(out.size() - first) < o.max_layers; ++crossing) {
        const std::optional<Hit> hit = casters.closest_hit(ray, t, std::numeric_limits<double>::infinity());
        if (!hit) break;
        t = hit->t;
        const float depth = float(t);
        if (!(depth > 0)) continue;  // at the camera itself: no distance to store
        if (out.size() == first || (t - out.back() > o.prune * t && depth > out.back())) {
            out.push_back(depth);
            crossed.push_back(hit->primitive);
        }
    }
}

// The largest |x| / z and |y| / z of the points of `held` in `frame` at `vertex`.
double widest_slope(Vec3 vertex, const Basis& frame, const std::vector<Vec3>& held)
{
    double widest = 0;
    for (const Vec3& p : held) {
        const Vec3 local = frame.to_local(p - vertex);
        require(local.z > 0, kPismoMapsOp, "light",
                "a point the maps must hold lies behind a light vertex; move the light camera's near plane out "
                "or the light away from the scene");
        widest = std::max({widest, std::fabs(local.x) / local.z, std::fabs(local.y) / local.z});
    }
    require(widest > 0, kPismoMapsOp, "light", "the maps have nothing to hold: no receiver and no caster");
    return widest;
}

// The camera at `vertex` looking at `fixation` with the narrowest square field
// of view (times kFovMargin) that holds every point of `held`; a pyramid is
// convex, so it then holds their convex hull. With a shift, it then looks at
// the fixation point moved by the shift's texels (the fixation lands that far
// the other way) and is fitted again, so it still holds them.
MapCamera camera_holding(const Scene& scene, Vec3 vertex, Vec3 fixation, const std::vector<Vec3>& held,
                         SubTexelShift shift)
{
    Basis frame = basis_looking_along(fixation - vertex, scene.light.up);
    double widest = widest_slope(vertex, frame, held);
    if (shift.size > 0) {
        const double texel = 2 * kFovMargin * widest / shift.size;  // at unit depth
        frame = basis_looking_along(frame.n + frame.s * (shift.x * texel) + frame.t * (shift.y * texel), scene.light.up);
        widest = widest_slope(vertex, frame, held);
    }
    return MapCamera{to_array(vertex), to_array(frame.s), to_array(frame.t), to_array(frame.n), kFovMargin * widest};
}

}  // namespace

std::vector<int> pismo_caster_surfaces(const Scene& scene)
{
    std::vector<int> kept;
    const std::vector<Primitive> surfaces = scene_surfaces(scene);
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        const auto* plane = std::get_if<Plane>(&surfaces[i]);
        if (!plane || plane_holds_light(*plane, scene.light)) kept.push_back(int(i));
    }
    return kept;
}

std::vector<Primitive> pismo_casters(const Scene& scene)
{
    const std::vector<Primitive> surfaces = scene_surfaces(scene);
    std::vector<Primitive> casters;
    for (int i : pismo_caster_surfaces(scene)) casters.push_back(surfaces[std::size_t(i)]);
    return casters;
}

Vec3 pismo_fixation_point(const Scene& scene)
{
    if (const auto b = casters_bounds(scene)) return b->centre();
    const Basis light = basis_looking_along(scene.light.normal, scene.light.up);
    return scene.light.center + light.n * (0.5 * (scene.light_camera.near + scene.light_camera.far));
}

SubTexelShift pismo_subtexel_shift(int vertex, int size)
{
    constexpr double a1 = 0.7548776662466927, a2 = 0.5698402909980532;  // 1/g and 1/g^2, g^3 = g + 1
    const auto wrap = [](double v) { return v - std::floor(v) - 0.5; };
    return {wrap(0.5 + vertex * a1), wrap(0.5 + vertex * a2), size};
}

MapCamera pismo_vertex_camera(const Scene& scene, Vec3 vertex, Vec3 fixation, SubTexelShift shift)
{
    const LightProjection light(scene);
    const double slab[2] = {nearest_caster_depth(scene, light.basis()), scene.light_camera.far};
    std::vector<Vec3> corners;
    for (double depth : slab)
        for (int corner = 0; corner < 4; ++corner) corners.push_back(light.ray_through(corner & 1, corner >> 1).at(depth));
    return camera_holding(scene, vertex, fixation, corners, shift);
}

MapCamera pismo_fitted_camera(const Scene& scene, Vec3 vertex, Vec3 fixation, std::span<const Vec3> region,
                              SubTexelShift shift)
{
    std::vector<Vec3> held(region.begin(), region.end());
    if (const auto b = casters_bounds(scene))
        for (int corner = 0; corner < 8; ++corner)
            held.push_back({corner & 1 ? b->hi.x : b->lo.x, corner & 2 ? b->hi.y : b->lo.y, corner & 4 ? b->hi.z : b->lo.z});
    return camera_holding(scene, vertex, fixation, held, shift);
}

std::vector<Vec3> receiver_region(const Receivers& rx)
{
    std::vector<Vec3> region;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x)
            if (rx.mask.at(0, x, y) > 0.5f)
                region.push_back({rx.world_position.at(0, x, y), rx.world_position.at(1, x, y),
                                  rx.world_position.at(2, x, y)});
    return region;
}

LayeredDepthMap render_layered_depth_map(const PreparedScene& casters, const MapCamera& camera,
                                         const LayeredMapOptions& options, std::vector<std::int32_t>* crossed)
{
    check(options);
    const int n = options.size;
    const Vec3 origin = to_vec(camera.position), right = to_vec(camera.right), down = to_vec(camera.down),
               forward = to_vec(camera.forward);
    struct Row {
        std::vector<float> depths;
        std::vector<std::int32_t> crossed;
        std::vector<std::uint32_t> counts;
    };
    std::vector<Row> rows(static_cast<std::size_t>(n));
    tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& range) {
        for (int j = range.begin(); j != range.end(); ++j) {
            Row& row = rows[std::size_t(j)];
            const double y = (2 * (j + 0.5) / n - 1) * camera.tan_half_fov;
            for (int i = 0; i < n; ++i) {
                const double x = (2 * (i + 0.5) / n - 1) * camera.tan_half_fov;
                const std::size_t before = row.depths.size();
                trace_layers(casters, {origin, normalize(forward + right * x + down * y)}, options, row.depths,
                             row.crossed);
                row.counts.push_back(std::uint32_t(row.depths.size() - before));
            }
        }
    });
    LayeredDepthMapBuilder builder(n, n, camera);
    if (crossed) crossed->clear();
    for (const Row& row : rows) {
        if (crossed) crossed->insert(crossed->end(), row.crossed.begin(), row.crossed.end());
        std::size_t at = 0;
        for (std::uint32_t count : row.counts) {
            builder.add_pixel(std::span(row.depths).subspan(at, count));
            at += count;
        }
    }
    return builder.build();
}

PismoMaps render_pismo_maps(const Scene& scene, int level, const LayeredMapOptions& options,
                            std::span<const Vec3> region)
{
    validate_scene(scene, kPismoMapsOp);
    check(options);
    PismoMaps out{light_mesh(scene.light, level), pismo_fixation_point(scene), {}, {}};
    const std::vector<int> surface_of = pismo_caster_surfaces(scene);
    const PreparedScene casters(pismo_casters(scene));
    out.maps.reserve(out.mesh.vertices.size());
    for (std::size_t j = 0; j < out.mesh.vertices.size(); ++j) {
        const Vec3 vertex = out.mesh.vertices[j];
        const SubTexelShift shift = options.shift_grids ? pismo_subtexel_shift(int(j), options.size) : SubTexelShift{};
        std::vector<std::int32_t>& ids = out.surface_ids.emplace_back();
        out.maps.push_back(render_layered_depth_map(
            casters, region.empty() ? pismo_vertex_camera(scene, vertex, out.fixation, shift)
                                    : pismo_fitted_camera(scene, vertex, out.fixation, region, shift),
            options, &ids));
        for (std::int32_t& id : ids) id = surface_of[std::size_t(id)];
    }
    return out;
}

PismoMapSet render_pismo_map_set(const Scene& scene, int level, const LayeredMapOptions& options,
                                 std::span<const Vec3> region)
{
    PismoMaps maps = render_pismo_maps(scene, level, options, region);
    PismoMapSet set;
    for (const Vec3& v : maps.mesh.vertices) set.vertices.push_back(to_array(v));
    set.triangles = std::move(maps.mesh.triangles);
    set.maps = std::move(maps.maps);
    set.surface_ids = std::move(maps.surface_ids);
    set.surface_count = int(scene_surfaces(scene).size());
    set.scene = scene.name, set.level = level, set.fixation = to_array(maps.fixation);
    return set;
}

}  // namespace penumbra::reference
