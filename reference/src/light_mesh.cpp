// The area light as a triangle mesh for Pismo (penumbra/reference/pismo_maps.h).
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "penumbra/error.h"
#include "penumbra/reference/pismo_maps.h"

namespace penumbra::reference {
namespace {

constexpr int kDiskFanTriangles = 6;

LightMesh level_zero(const AreaLight& light)
{
    const Basis frame = basis_looking_along(light.normal, light.up);
    LightMesh mesh;
    if (light.shape == LightShape::Rectangle) {
        const Vec3 s = frame.s * (0.5 * light.width), t = frame.t * (0.5 * light.height);
        mesh.vertices = {light.center - s - t, light.center + s - t, light.center + s + t, light.center - s + t};
        mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
        return mesh;
    }
    mesh.vertices.push_back(light.center);
    for (int k = 0; k < kDiskFanTriangles; ++k) {
        const double angle = 2 * std::numbers::pi * k / kDiskFanTriangles;
        mesh.vertices.push_back(light.center +
                                (frame.s * std::cos(angle) + frame.t * std::sin(angle)) * (0.5 * light.width));
        mesh.triangles.push_back({0, 1 + k, 1 + (k + 1) % kDiskFanTriangles});
    }
    return mesh;
}

// Splits every triangle into four. An edge that only one triangle holds is on
// the mesh's boundary; for a disk its midpoint moves out onto the circle.
LightMesh subdivide(const LightMesh& mesh, const AreaLight& light)
{
    std::map<std::pair<int, int>, int> edge_uses;
    for (const auto& tri : mesh.triangles)
        for (int e = 0; e < 3; ++e) ++edge_uses[std::minmax(tri[e], tri[(e + 1) % 3])];
    LightMesh finer;
    finer.vertices = mesh.vertices;
    std::map<std::pair<int, int>, int> midpoint_of;
    const auto midpoint = [&](int a, int b) {
        const auto edge = std::minmax(a, b);
        if (const auto found = midpoint_of.find(edge); found != midpoint_of.end()) return found->second;
        Vec3 m = (mesh.vertices[a] + mesh.vertices[b]) * 0.5;
        if (light.shape == LightShape::Disk && edge_uses[edge] == 1)
            m = light.center + normalize(m - light.center) * (0.5 * light.width);
        finer.vertices.push_back(m);
        return midpoint_of[edge] = int(finer.vertices.size()) - 1;
    };
    for (const auto& [a, b, c] : mesh.triangles) {
        const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        finer.triangles.insert(finer.triangles.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
    }
    return finer;
}

}  // namespace

double LightMesh::triangle_area(int triangle) const
{
    const auto& [a, b, c] = triangles[std::size_t(triangle)];
    return 0.5 * length(cross(vertices[b] - vertices[a], vertices[c] - vertices[a]));
}

double LightMesh::area() const
{
    double sum = 0;
    for (int i = 0; i < int(triangles.size()); ++i) sum += triangle_area(i);
    return sum;
}

std::vector<double> LightMesh::vertex_weights() const
{
    std::vector<double> weights(vertices.size(), 0.0);
    const double total = area();
    for (int i = 0; i < int(triangles.size()); ++i)
        for (int corner : triangles[std::size_t(i)]) weights[std::size_t(corner)] += triangle_area(i) / (3 * total);
    return weights;
}

LightMesh light_mesh(const AreaLight& light, int level)
{
    require(light.shape != LightShape::Point, "light_mesh", "light",
            "a point light has no area to mesh; Pismo needs a rectangle or disk light");
    require(level >= 0 && level <= kMaxLightLevel, "light_mesh", "light-level",
            "the light level must be in [0, " + std::to_string(kMaxLightLevel) + "], not " + std::to_string(level));
    LightMesh mesh = level_zero(light);
    for (int l = 0; l < level; ++l) mesh = subdivide(mesh, light);
    return mesh;
}

}  // namespace penumbra::reference
