// What the Pismo tests share (tests/kernels/pismo_test.cpp, the pismo case of
// tests/kernels/receiver_lookup_test.cpp): the reference's maps as the
// library's PismoMaps, and a scene with a closed form.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "penumbra/image.h"

#include "penumbra/pismo.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/scene.h"

namespace penumbra::testing {

inline PismoMaps library_maps(const reference::PismoMaps& m, PismoDepths depths = PismoDepths::Layered,
                              bool surface_ids = false)
{
    std::vector<std::array<double, 3>> vertices;
    for (const reference::Vec3& v : m.mesh.vertices) vertices.push_back({v.x, v.y, v.z});
    return PismoMaps(vertices, m.mesh.triangles, m.maps, depths,
                     surface_ids ? m.surface_ids : std::vector<std::vector<std::int32_t>>{});
}

// A square light 2 x 2 at height 10 facing down, a thin blocker (4.99 <= y
// <= 5.01) over -4 <= x <= 0, |z| <= 3, the ground at 0 (a receiver only).
inline reference::Scene half_plane_scene()
{
    reference::Scene s;
    s.name = "half-plane";
    s.light.center = {0, 10, 0};
    s.light.normal = {0, -1, 0};
    s.light.up = {0, 0, 1};
    s.light.width = s.light.height = 2;
    s.light_camera.fov_degrees = 60;
    s.light_camera.near = 1;
    s.light_camera.far = 12;
    s.primitives.push_back(reference::Plane{{0, 0, 0}, {0, 1, 0}});
    s.primitives.push_back(reference::Box{{-2, 5, 0}, {4, 0.02, 6}, {0, 0, 0}});
    s.view.position = {0, 8, 0.01};
    s.view.target = {0, 0, 0};
    return s;
}

// The light's visible fraction at ground point (px, 0, pz), |px| <= 2,
// |pz| <= 0.5: the rays to light points (lx, 10, .) that pass the blocker's
// faces at x >= 0, lx >= -px (10 / y - 1) at both faces y = 4.99 and 5.01 (the
// rays cross them at |x| <= 1.5, |z| <= 0.75, inside its other edges).
inline double half_plane_visibility(double px)
{
    const double bound = std::max(-px * (10 / 4.99 - 1), -px * (10 / 5.01 - 1));
    return std::clamp((1 - bound) / 2, 0.0, 1.0);
}

// The receiver's own surface: the 2 x 2 light at height 10 of the half-plane
// scene over a unit sphere at (0, 3, 0) and a thin slab, 1 x 0.02 x 1, at
// (2, 5, 0). No plane: nothing else casts, and the sphere's rays (x <= 1 from
// x <= 1) pass beside the slab.
inline reference::Scene sphere_and_slab_scene()
{
    reference::Scene s = half_plane_scene();
    s.name = "sphere-and-slab";
    s.primitives.clear();
    s.primitives.push_back(reference::Sphere{{0, 3, 0}, 1});
    s.primitives.push_back(reference::Box{{2, 5, 0}, {1, 0.02, 1}, {0, 0, 0}});
    return s;
}

// Receivers on sphere_and_slab_scene's casters, one row of 6 planes
// (position, normal), and which of them have a closed form: lit, the whole
// light above the tangent plane (every corner at a cosine over 0.15 from it,
// within the slope bias's cap); dark, the whole light below it; the slab's
// faces, the far one dark (and listed again in slab_far_face), the near one lit.
struct OwnSurfaceReceivers {
    Image points;
    std::vector<int> lit, dark, slab_far_face;
};

inline OwnSurfaceReceivers own_surface_receivers(const reference::Scene& s)
{
    std::vector<std::array<double, 6>> rows;
    OwnSurfaceReceivers out;
    const reference::Vec3 centre{0, 3, 0};
    for (int i = 0; i < 24; ++i)
        for (int j = 0; j < 8; ++j) {
            const double polar = 3.14159265358979 * (i + 0.5) / 24, azimuth = 6.28318530717959 * (j + 0.25) / 8;
            const reference::Vec3 n{std::sin(polar) * std::cos(azimuth), std::cos(polar),
                                    std::sin(polar) * std::sin(azimuth)};
            const reference::Vec3 p = centre + n;
            double lowest = 1, highest = -1;
            for (double cx : {-1.0, 1.0})
                for (double cz : {-1.0, 1.0}) {
                    const reference::Vec3 corner = s.light.center + reference::Vec3{cx, 0, cz};
                    const double c = dot(n, normalize(corner - p));
                    lowest = std::min(lowest, c), highest = std::max(highest, c);
                }
            const int index = int(rows.size());
            if (lowest > 0.15) out.lit.push_back(index);
            if (highest < 0) out.dark.push_back(index);
            rows.push_back({p.x, p.y, p.z, n.x, n.y, n.z});
        }
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) {
            const double x = 1.7 + 0.15 * i, z = -0.3 + 0.15 * j;
            out.dark.push_back(int(rows.size()));
            out.slab_far_face.push_back(int(rows.size()));
            rows.push_back({x, 4.99, z, 0, -1, 0});
            out.lit.push_back(int(rows.size()));
            rows.push_back({x, 5.01, z, 0, 1, 0});
        }
    out.points = Image(int(rows.size()), 1, 6);
    for (int x = 0; x < int(rows.size()); ++x)
        for (int c = 0; c < 6; ++c) out.points.at(c, x, 0) = float(rows[std::size_t(x)][std::size_t(c)]);
    return out;
}

// Thin slats (issue 15's fence, reduced to a closed form): the 2 x 2 light at
// height 10 of the half-plane scene over slats kSlatWidth wide every
// kSlatPeriod along x (|x| <= 1.5), 0.02 thick (4.99 <= y <= 5.01), |z| <= 1.
// At maps of 128^2 fitted to a row of points under them a slat is 1 to 2
// texels wide, and the maps' common fixation point lies on the slats' plane.
inline constexpr double kSlatWidth = 0.05, kSlatPeriod = 0.17;
inline constexpr int kSlats = 17;

inline reference::Scene slats_scene()
{
    reference::Scene s = half_plane_scene();
    s.name = "slats";
    s.primitives.clear();
    for (int i = 0; i < kSlats; ++i)
        s.primitives.push_back(reference::Box{{(i - kSlats / 2) * kSlatPeriod, 5, 0}, {kSlatWidth, 0.02, 2}, {0, 0, 0}});
    return s;
}

// The light's visible fraction at (px, py, 0), py < 4.99, |px| <= 1: the ray
// to light point (lx, 10, .) crosses the slab 4.99 <= y <= 5.01 at x(y) = px +
// (lx - px)(y - py)/(10 - py), increasing in lx; it meets slat [a, b] when
// x(4.99) or x(5.01) reaches a and the other or it is at most b: lx between
// the smaller of the two lx that put a face's crossing at a and the larger of
// the two that put it at b. The light's x-extent is [-1, 1] (the rays' z stays
// within |z| <= 1); visibility = 1 - (the union of those intervals in [-1, 1]) / 2.
inline double slats_visibility(double px, double py)
{
    std::vector<std::array<double, 2>> blocked;
    const auto at = [&](double c, double y) { return px + (c - px) * (10 - py) / (y - py); };
    for (int i = 0; i < kSlats; ++i) {
        const double a = (i - kSlats / 2) * kSlatPeriod - kSlatWidth / 2, b = a + kSlatWidth;
        const double lo = std::max(std::min(at(a, 4.99), at(a, 5.01)), -1.0);
        const double hi = std::min(std::max(at(b, 4.99), at(b, 5.01)), 1.0);
        if (lo < hi) blocked.push_back({lo, hi});
    }
    std::sort(blocked.begin(), blocked.end());
    double covered = 0, reach = -1;
    for (const auto& [lo, hi] : blocked) {
        covered += std::max(0.0, hi - std::max(lo, reach));
        reach = std::max(reach, hi);
    }
    return 1 - covered / 2;
}

}  // namespace penumbra::testing
