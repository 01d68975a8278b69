// What the Pismo tests share (tests/kernels/pismo_test.cpp, the pismo case of
// tests/kernels/receiver_lookup_test.cpp): the reference's maps as the
// library's PismoMaps, and a scene with a closed form.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "penumbra/pismo.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/scene.h"

namespace penumbra::testing {

inline PismoMaps library_maps(const reference::PismoMaps& m, PismoDepths depths = PismoDepths::Layered)
{
    std::vector<std::array<double, 3>> vertices;
    for (const reference::Vec3& v : m.mesh.vertices) vertices.push_back({v.x, v.y, v.z});
    return PismoMaps(vertices, m.mesh.triangles, m.maps, depths);
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

}  // namespace penumbra::testing
