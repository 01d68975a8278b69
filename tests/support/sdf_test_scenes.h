// Scenes, receivers and independent references shared by the SDF tests
// (tests/sdf_*_test.cpp). Everything here is double precision and written
// from the definitions in kernels/sdf.h, not from the kernel's code.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/scene.h"
#include "penumbra/reference/tracer.h"
#include "penumbra/sdf.h"

namespace penumbra::testing {

using reference::Vec3;

// A 1 m square light 6 m above the ground, looking down, over a sphere of
// radius 0.5 whose bottom is 1 m above the ground.
inline reference::Scene sphere_over_plane()
{
    reference::Scene s;
    s.name = "sphere_over_plane";
    s.primitives = {reference::Plane{{0, 0, 0}, {0, 1, 0}}, reference::Sphere{{0, 1.5, 0}, 0.5}};
    s.light.center = {0, 6, 0};
    s.light.normal = {0, -1, 0};
    s.light.up = {0, 0, 1};
    s.light.width = s.light.height = 1.0;
    s.light_camera.near = 0.5;
    s.light_camera.far = 10;
    s.view = {{0, 4, 6}, {0, 0, 0}, {0, 1, 0}, 45};
    return s;
}

// `points` row by row into a width x ceil(n / width) image of 3 channels; the
// last row is padded with copies of the last point.
inline Image points_image(const std::vector<Vec3>& points, int width)
{
    const int height = int((points.size() + width - 1) / width);
    Image image(width, height, 3);
    for (int i = 0; i < width * height; ++i) {
        const Vec3 p = points[std::min<std::size_t>(i, points.size() - 1)];
        image.at(0, i % width, i / width) = float(p.x);
        image.at(1, i % width, i / width) = float(p.y);
        image.at(2, i % width, i / width) = float(p.z);
    }
    return image;
}

// Receivers on the ground along x (from x0 to x1, n of them, at z), normals up.
struct Profile {
    std::vector<Vec3> points;
    Image positions, normals;
};

inline Profile ground_profile(double x0, double x1, int n, double z)
{
    Profile p;
    for (int i = 0; i < n; ++i) p.points.push_back({x0 + (x1 - x0) * i / (n - 1), 0.0, z});
    p.positions = points_image(p.points, n);
    p.normals = points_image(std::vector<Vec3>(p.points.size(), Vec3{0, 1, 0}), n);
    return p;
}

// The ground truth at each receiver of `p` (64^2 rays each, seed = index).
inline std::vector<double> profile_truth(const reference::PreparedScene& scene, const reference::AreaLight& light,
                                         const Profile& p)
{
    std::vector<double> truth;
    for (std::size_t i = 0; i < p.points.size(); ++i)
        truth.push_back(reference::light_visibility(scene, light, p.points[i], {0, 1, 0}, 64, int(i)));
    return truth;
}

inline const char* name_of(SdfEstimate e)
{
    return e == SdfEstimate::Classic ? "classic" : e == SdfEstimate::Improved ? "improved" : "inner";
}

inline Vec3 pixel(const Image& image, int x, int y)
{
    return {image.at(0, x, y), image.at(1, x, y), image.at(2, x, y)};
}

// The ray a receiver marches (kernels/sdf.h, header comment): origin lifted
// along the normal, direction to the light's centre, the interval [t0, t1].
struct MarchRay {
    Vec3 origin, dir;
    double t0, t1;
};

inline MarchRay march_ray(const SdfOptions& o, Vec3 position, Vec3 normal)
{
    MarchRay r;
    r.origin = position + normal * double(o.normal_offset);
    if (o.light.directional) {
        r.dir = reference::normalize(reference::from_sdf(o.light.vector));
        r.t1 = o.t_max;
    } else {
        const Vec3 to_light = reference::from_sdf(o.light.vector) - r.origin;
        r.dir = reference::normalize(to_light);
        r.t1 = std::min(double(o.t_max), reference::length(to_light));
    }
    r.t0 = o.t_min;
    return r;
}

// The narrowest clearance angle along the whole ray, min over t in [t0, t1] of
// d(o + t w) / t, for the exact signed distance: 0 if the ray touches a solid.
// Dense samples (uniform in log t, where d / t changes fastest near the
// receiver, and uniform in t), then golden-section refinement about the best.
// Sphere tracing samples the ray at its own steps, so a kernel's classic
// estimate is never below k times this (up to float rounding).
inline double ideal_clearance(const reference::PreparedScene& scene, const MarchRay& r, double hit_epsilon)
{
    const double t0 = std::max(r.t0, 1e-9), t1 = r.t1;
    auto ratio = [&](double t) { return scene.signed_distance(r.origin + r.dir * t) / t; };
    double best = INFINITY, best_t = t0;
    auto sample = [&](double t) {
        const double d = scene.signed_distance(r.origin + r.dir * t);
        if (d < hit_epsilon) best = -INFINITY;
        if (d / t < best) {
            best = d / t;
            best_t = t;
        }
    };
    const int n = 4000;
    for (int i = 0; i <= n; ++i) {
        sample(t0 * std::pow(t1 / t0, double(i) / n));
        sample(t0 + (t1 - t0) * i / n);
    }
    if (best == -INFINITY) return 0.0;
    double lo = std::max(t0, best_t * 0.98 - (t1 - t0) / n), hi = std::min(t1, best_t * 1.02 + (t1 - t0) / n);
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int i = 0; i < 80; ++i) {
        const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
        if (ratio(a) < ratio(b))
            hi = b;
        else
            lo = a;
    }
    return std::max(0.0, std::min(best, ratio((lo + hi) / 2)));
}

// The hardness a receiver uses: k, or with a light width k 2 D / W for its
// distance D to the light's centre (SdfOptions::light_width).
inline double receiver_k(const SdfOptions& o, Vec3 position, Vec3 normal)
{
    if (o.light_width == 0.0f) return o.k;
    const Vec3 origin = position + normal * double(o.normal_offset);
    return o.k * 2.0 * reference::length(reference::from_sdf(o.light.vector) - origin) / o.light_width;
}

inline double ideal_visibility(const reference::PreparedScene& scene, const SdfOptions& o, Vec3 position,
                               Vec3 normal)
{
    const double clearance = ideal_clearance(scene, march_ray(o, position, normal), o.hit_epsilon);
    return std::clamp(receiver_k(o, position, normal) * clearance, 0.0, 1.0);
}

// The inner-penumbra estimate's ideal (SdfEstimate::InnerPenumbra, docs/sdf.md):
// the signed clearance s = min over t in [t0, t1] of d(o + t w) / t, the ray
// continuing through solids, then x = clamp(k s, -1, 1) and smoothstep from
// -1 to 1, (1 + x)^2 (2 - x) / 4. Dense samples uniform in log t and in t.
inline double ideal_inner_visibility(const reference::PreparedScene& scene, const SdfOptions& o, Vec3 position,
                                     Vec3 normal)
{
    const MarchRay r = march_ray(o, position, normal);
    const double t0 = std::max(r.t0, 1e-9);
    double best = INFINITY;
    const int n = 20000;
    for (int i = 0; i <= n; ++i)
        for (double t : {t0 * std::pow(r.t1 / t0, double(i) / n), t0 + (r.t1 - t0) * i / n})
            best = std::min(best, scene.signed_distance(r.origin + r.dir * t) / t);
    const double x = std::clamp(receiver_k(o, position, normal) * best, -1.0, 1.0);
    return (1 + x) * (1 + x) * (2 - x) / 4;
}

}  // namespace penumbra::testing
