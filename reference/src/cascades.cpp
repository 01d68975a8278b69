// Cascaded shadow maps of a directional light fitted to the view (cascades.h).
#include "penumbra/reference/cascades.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "penumbra/error.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

const char* const kRenderCascadesOp = "render_cascades";

const DirectionalLight& directional_light(const Scene& scene, int light, const char* op)
{
    if (light < 0 || light >= int(scene.directional_lights.size()))
        throw Error(ErrorCategory::InvalidArgument, op, "light",
                    "scene '" + scene.name + "' has " + std::to_string(scene.directional_lights.size()) +
                        " directional light(s); light " + std::to_string(light) +
                        " does not exist (add \"directional_lights\" to the scene)");
    return scene.directional_lights[std::size_t(light)];
}

Basis light_basis(const DirectionalLight& light) { return basis_looking_along(light.direction, light.up); }

// The view depth range of the surfaces the receivers see.
std::array<double, 2> seen_depths(const Receivers& r)
{
    double lo = INFINITY, hi = 0;
    for (int y = 0; y < r.height(); ++y)
        for (int x = 0; x < r.width(); ++x)
            if (r.hit.at(0, x, y) > 0) {
                lo = std::min(lo, double(r.view_depth.at(0, x, y)));
                hi = std::max(hi, double(r.view_depth.at(0, x, y)));
            }
    require(hi > 0, kRenderCascadesOp, "receivers", "the view sees no surface; give the shadowed range (near, far)");
    return {std::max(lo * 0.99, 1e-3), std::max(hi * 1.01, lo * 1.02)};
}

// The eight corners of the view frustum between view depths d0 and d1.
std::array<Vec3, 8> split_corners(const ViewCamera& view, double aspect, double d0, double d1)
{
    const Basis b = basis_looking_along(view.target - view.position, view.up);
    const double tan_half = std::tan(view.fov_degrees * M_PI / 360);
    std::array<Vec3, 8> corners;
    int k = 0;
    for (double d : {d0, d1})
        for (double sy : {-1.0, 1.0})
            for (double sx : {-1.0, 1.0})
                corners[std::size_t(k++)] =
                    view.position + b.n * d + b.s * (sx * d * tan_half * aspect) + b.t * (sy * d * tan_half);
    return corners;
}

// The orthographic box of one split in the light's frame: square across the
// light, widened so that (grid + 1) texels of margin lie inside the map.
struct LightBox {
    double x0, y0, side, near, far;
};

LightBox fit_box(const Basis& light, const std::array<Vec3, 8>& corners, int map_size, int grid)
{
    Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (const Vec3& c : corners) {
        const Vec3 l = light.to_local(c);
        lo = {std::min(lo.x, l.x), std::min(lo.y, l.y), std::min(lo.z, l.z)};
        hi = {std::max(hi.x, l.x), std::max(hi.y, l.y), std::max(hi.z, l.z)};
    }
    const double tight = std::max(hi.x - lo.x, hi.y - lo.y);
    const double side = tight * map_size / std::max(1.0, double(map_size - (grid + 1)));
    return {0.5 * (lo.x + hi.x) - side / 2, 0.5 * (lo.y + hi.y) - side / 2, side, lo.z, hi.z};
}

CascadeFrame frame_of(const LightBox& box, double split_far)
{
    CascadeFrame f;
    f.u_scale = float(1 / box.side), f.u_offset = float(-box.x0 / box.side);
    f.v_scale = float(1 / box.side), f.v_offset = float(-box.y0 / box.side);
    const double range = box.far - box.near;
    f.z_scale = float(1 / range), f.z_offset = float(-box.near / range);
    f.split_far = float(split_far);
    return f;
}

// The nearest light depth any bounded solid reaches (planes are unbounded;
// the scenes' planes are grounds facing the light).
double casters_start(const Scene& scene, const Basis& light)
{
    double start = INFINITY;
    auto grow = [&](const Bounds& b) {
        for (int i = 0; i < 8; ++i) {
            const Vec3 corner{i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z};
            start = std::min(start, dot(corner, light.n));
        }
    };
    for (const Primitive& p : scene_surfaces(scene)) {
        if (const auto* s = std::get_if<Sphere>(&p)) grow(bounds_of(*s));
        if (const auto* b = std::get_if<Box>(&p)) grow(bounds_of(OrientedBox::from(*b)));
        if (const auto* c = std::get_if<Capsule>(&p)) grow(bounds_of(*c));
    }
    return start;
}

// The light depth stored for one texel ray, which starts at depth `start`.
double texel_depth(const PreparedScene& prepared, const Ray& ray, double start, const LightBox& box, NearPlane near)
{
    const double t_far = box.far - start;
    double t = near == NearPlane::Clip ? box.near - start : 0;
    for (;;) {
        const auto hit = prepared.closest_hit(ray, t, t_far);
        if (!hit) return box.far;
        // Clip draws faces towards the light only: a face the ray leaves through is culled.
        if (near == NearPlane::Pancake || dot(hit->normal, ray.direction) < 0) return start + hit->t;
        t = hit->t;
    }
}

void render_map(const PreparedScene& prepared, const Basis& light, double start, const LightBox& box, NearPlane near,
                int size, Image& maps, int row0)
{
    tbb::parallel_for(tbb::blocked_range<int>(0, size), [&](const tbb::blocked_range<int>& rows) {
        for (int j = rows.begin(); j != rows.end(); ++j) {
            float* out = maps.row(0, row0 + j);
            for (int i = 0; i < size; ++i) {
                const double x = box.x0 + (i + 0.5) / size * box.side, y = box.y0 + (j + 0.5) / size * box.side;
                const Ray ray{light.s * x + light.t * y + light.n * start, light.n};
                const double d = texel_depth(prepared, ray, start, box, near);
                out[i] = float(std::clamp((d - box.near) / (box.far - box.near), 0.0, 1.0));
            }
        }
    });
}

std::array<float, 3> to_floats(Vec3 v) { return {float(v.x), float(v.y), float(v.z)}; }

}  // namespace

std::vector<double> split_depths(double near, double far, int count, double lambda)
{
    require(count >= 1 && count <= kMaxCascades, "split_depths", "cascades",
            std::to_string(count) + " cascades asked for; give 1 to " + std::to_string(kMaxCascades));
    require(near > 0 && far > near && std::isfinite(far), "split_depths", "near",
            "the shadowed range must satisfy 0 < near < far (got " + std::to_string(near) + ", " +
                std::to_string(far) + ")");
    require(lambda >= 0 && lambda <= 1, "split_depths", "lambda", "lambda must lie in [0, 1]");
    std::vector<double> d(std::size_t(count) + 1);
    for (int i = 0; i <= count; ++i) {
        const double f = double(i) / count;
        d[std::size_t(i)] = lambda * near * std::pow(far / near, f) + (1 - lambda) * (near + (far - near) * f);
    }
    d.front() = near, d.back() = far;
    return d;
}

CascadeShadows render_cascades(const Scene& scene, int light, const Receivers& receivers, const CascadeSetup& setup)
{
    validate_scene(scene, kRenderCascadesOp);
    const Basis basis = light_basis(directional_light(scene, light, kRenderCascadesOp));
    require(setup.map_size >= 8 && setup.map_size <= 8192, kRenderCascadesOp, "map_size",
            "each cascade's side must be in [8, 8192]");
    require(!receivers.mask.empty(), kRenderCascadesOp, "receivers", "the receivers are empty");
    const std::array<double, 2> range =
        setup.near == 0 && setup.far == 0 ? seen_depths(receivers) : std::array<double, 2>{setup.near, setup.far};
    const std::vector<double> splits = split_depths(range[0], range[1], setup.count, setup.lambda);
    const double aspect = double(receivers.width()) / receivers.height();
    const PreparedScene prepared(scene);
    CascadeShadows shadows;
    shadows.axis_u = to_floats(basis.s), shadows.axis_v = to_floats(basis.t), shadows.axis_z = to_floats(basis.n);
    shadows.maps = Image(setup.map_size, setup.map_size * setup.count, 1);
    for (int c = 0; c < setup.count; ++c) {
        const double d0 = splits[std::size_t(c)], d1 = splits[std::size_t(c) + 1];
        const LightBox box = fit_box(basis, split_corners(scene.view, aspect, d0, d1), setup.map_size, setup.grid);
        const double start = std::min(casters_start(scene, basis), box.near) - 1;
        render_map(prepared, basis, start, box, setup.near_plane, setup.map_size, shadows.maps, c * setup.map_size);
        shadows.cascades.push_back(frame_of(box, d1));
    }
    return shadows;
}

Image cascade_receivers(const Receivers& r)
{
    Image out(r.width(), r.height(), kCascadeReceiverChannels);
    for (int y = 0; y < r.height(); ++y)
        for (int x = 0; x < r.width(); ++x) {
            for (int c = 0; c < 3; ++c) out.at(c, x, y) = r.world_position.at(c, x, y);
            out.at(3, x, y) = r.view_depth.at(0, x, y);
            out.at(4, x, y) = r.hit.at(0, x, y);
        }
    return out;
}

Image directional_truth(const Scene& scene, int light, const Receivers& r)
{
    validate_scene(scene, "directional_truth");
    const Vec3 towards = normalize(directional_light(scene, light, "directional_truth").direction) * -1.0;
    const PreparedScene prepared(scene);
    const std::vector<bool> opaque = opaque_surfaces(scene);
    Image truth(r.width(), r.height(), 1);
    tbb::parallel_for(tbb::blocked_range<int>(0, r.height()), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < r.width(); ++x) {
                if (r.hit.at(0, x, y) == 0) {
                    truth.at(0, x, y) = 1;
                    continue;
                }
                const Vec3 p{r.world_position.at(0, x, y), r.world_position.at(1, x, y), r.world_position.at(2, x, y)};
                const Vec3 n{r.normal.at(0, x, y), r.normal.at(1, x, y), r.normal.at(2, x, y)};
                const ReceiverRays rays(p, n, receiver_own_surface(r, opaque, x, y));
                truth.at(0, x, y) = float(rays.transmittance(prepared, towards, 1e9));
            }
    });
    return truth;
}

}  // namespace penumbra::reference
