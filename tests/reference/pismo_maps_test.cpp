// Pismo's maps (penumbra/reference/pismo_maps.h): the light mesh's counts,
// areas and weights against closed forms; which surfaces are casters; the
// vertex cameras hold the light's frustum; layered depths are the exact
// crossings of the rays (spheres in a row, a thin capsule pruned) and lie on
// the scene's surfaces (its signed distance), whatever the thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>
#include <type_traits>
#include <variant>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/render.h"
#include "support/errors.h"

namespace penumbra::reference {
namespace {

using testing::expect_error;

AreaLight disk_light(double diameter)
{
    AreaLight light;
    light.shape = LightShape::Disk;
    light.center = {0, 10, 0};
    light.width = light.height = diameter;
    return light;
}

TEST(LightMesh, RectangleCountsAreaAndWeights)
{
    AreaLight light;  // 1 x 1 at (0, 10, 0) facing down
    light.width = 1.5;
    light.height = 0.5;
    for (int level = 0; level <= kMaxLightLevel; ++level) {
        const LightMesh mesh = light_mesh(light, level);
        const std::size_t side = (1u << level) + 1;
        EXPECT_EQ(mesh.vertices.size(), side * side) << level;
        EXPECT_EQ(mesh.triangles.size(), 2u << (2 * level)) << level;
        EXPECT_NEAR(mesh.area(), 0.75, 1e-12) << level;
        const std::vector<double> w = mesh.vertex_weights();
        EXPECT_NEAR(std::accumulate(w.begin(), w.end(), 0.0), 1.0, 1e-12);
        for (const Vec3& v : mesh.vertices) {
            EXPECT_NEAR(v.y, 10, 1e-12);
            EXPECT_LE(std::fabs(v.x), 0.75 + 1e-12);
            EXPECT_LE(std::fabs(v.z), 0.25 + 1e-12);
        }
    }
}

TEST(LightMesh, DiskConvergesToTheCircle)
{
    const AreaLight light = disk_light(2);  // r = 1
    double last_error = INFINITY;
    for (int level = 0; level <= kMaxLightLevel; ++level) {
        const LightMesh mesh = light_mesh(light, level);
        EXPECT_EQ(mesh.triangles.size(), 6u << (2 * level));
        if (level == 0) {
            EXPECT_NEAR(mesh.area(), 1.5 * std::sqrt(3.0), 1e-12);  // the hexagon
        }
        const double error = std::numbers::pi - mesh.area();
        EXPECT_GT(error, 0) << "an inscribed mesh";
        EXPECT_LT(error, last_error) << level;
        last_error = error;
        for (const Vec3& v : mesh.vertices) EXPECT_LE(length(v - light.center), 1 + 1e-12);
    }
    EXPECT_LT(last_error / std::numbers::pi, 1e-3) << "level 5 within 0.1% of the disk's area";
}

TEST(LightMesh, BadLevelsAndPointLightsAreRefused)
{
    expect_error([] { light_mesh(AreaLight{}, -1); }, ErrorCategory::InvalidArgument, "light_mesh", "light level");
    expect_error([] { light_mesh(AreaLight{}, kMaxLightLevel + 1); }, ErrorCategory::InvalidArgument, "light_mesh",
                 "light level");
    AreaLight point;
    point.shape = LightShape::Point;
    expect_error([&] { light_mesh(point, 0); }, ErrorCategory::InvalidArgument, "light_mesh", "point light");
}

TEST(PismoCasters, GroundUnderTheLightIsOnlyAReceiver)
{
    Scene scene = builtin_scene("contact");
    const std::vector<Primitive> casters = pismo_casters(scene);
    EXPECT_EQ(casters.size(), scene.primitives.size() - 1);
    for (const Primitive& p : casters) EXPECT_FALSE(std::holds_alternative<Plane>(p));
    // A plane whose solid holds a corner of the light can shadow: it stays.
    scene.primitives.push_back(Plane{{0, 9, 0}, {0, -1, 0}});
    EXPECT_TRUE(std::holds_alternative<Plane>(pismo_casters(scene).back()));
}

TEST(PismoFixation, CentreOfTheCastersBounds)
{
    const Scene scene = builtin_scene("overlap");
    Bounds b;
    for (const Primitive& p : scene.primitives)
        if (const auto* box = std::get_if<Box>(&p)) b.grow(bounds_of(OrientedBox::from(*box)));
    const Vec3 f = pismo_fixation_point(scene);
    EXPECT_NEAR(length(f - b.centre()), 0, 1e-12);
}

// (u, v) of a world point in a map camera, by the header's formula.
std::pair<double, double> map_uv(const MapCamera& c, Vec3 p)
{
    const Vec3 o{c.position[0], c.position[1], c.position[2]};
    const auto along = [&](const std::array<double, 3>& a) { return dot(p - o, Vec3{a[0], a[1], a[2]}); };
    const double d = along(c.forward);
    return {0.5 + along(c.right) / (2 * d * c.tan_half_fov), 0.5 + along(c.down) / (2 * d * c.tan_half_fov)};
}

TEST(PismoVertexCamera, HoldsTheLightsFrustumBehindTheCasters)
{
    for (const char* name : {"contact", "overlap", "fence"}) {
        const Scene scene = builtin_scene(name);
        const LightProjection light(scene);
        const Vec3 fixation = pismo_fixation_point(scene);
        std::mt19937_64 random(3);
        std::uniform_real_distribution<double> unit(0, 1);
        for (const Vec3& vertex : light_mesh(scene.light, 2).vertices) {
            const MapCamera camera = pismo_vertex_camera(scene, vertex, fixation);
            const Vec3 forward{camera.forward[0], camera.forward[1], camera.forward[2]};
            EXPECT_NEAR(dot(forward, normalize(fixation - vertex)), 1, 1e-12) << name;
            // Receivers the light camera sees, from the casters' top to the far plane.
            for (int k = 0; k < 200; ++k) {
                const double depth = std::lerp(scene.light_camera.far * 0.5, scene.light_camera.far, unit(random));
                const auto [u, v] = map_uv(camera, light.ray_through(unit(random), unit(random)).at(depth));
                EXPECT_TRUE(u > 0 && u < 1 && v > 0 && v < 1) << name << " (" << u << ", " << v << ")";
            }
        }
    }
}

// Fitted to the view's receivers: every receiver and the casters' box inside
// every map, and a narrower field of view than the frustum's camera.
TEST(PismoFittedCamera, HoldsTheReceiversAndTheCastersNarrowerThanTheFrustum)
{
    for (const char* name : {"contact", "overlap", "fence"}) {
        const Scene scene = builtin_scene(name);
        const std::vector<Vec3> region = receiver_region(render_receivers(scene, 32, 24));
        ASSERT_FALSE(region.empty()) << name;
        const Vec3 fixation = pismo_fixation_point(scene);
        for (const Vec3& vertex : light_mesh(scene.light, 1).vertices) {
            const MapCamera fitted = pismo_fitted_camera(scene, vertex, fixation, region);
            EXPECT_LT(fitted.tan_half_fov, pismo_vertex_camera(scene, vertex, fixation).tan_half_fov) << name;
            for (const Vec3& p : region) {
                const auto [u, v] = map_uv(fitted, p);
                EXPECT_TRUE(u > 0 && u < 1 && v > 0 && v < 1) << name << " (" << u << ", " << v << ")";
            }
        }
    }
}

TEST(PismoFittedCamera, APointBehindTheLightIsRefused)
{
    const Scene scene = builtin_scene("contact");
    const Vec3 behind = scene.light.center - scene.light.normal * 5.0;
    const std::vector<Vec3> region = {behind};
    expect_error([&] { (void)pismo_fitted_camera(scene, scene.light.center, pismo_fixation_point(scene), region); },
                 ErrorCategory::InvalidArgument, "pismo_maps", {"behind a light vertex"});
}

MapCamera looking_along_z(double tan_half_fov)
{
    MapCamera c;  // at the origin: right +x, down +y, forward +z
    c.tan_half_fov = tan_half_fov;
    return c;
}

LayeredMapOptions options(int size, int layers = 8, double prune = 1e-3)
{
    LayeredMapOptions o;
    o.size = size;
    o.max_layers = layers;
    o.prune = prune;
    return o;
}

TEST(LayeredDepthRender, SpheresInARowGiveTheirEntriesAndExits)
{
    const PreparedScene row({Sphere{{0, 0, 5}, 1}, Sphere{{0, 0, 10}, 1}});
    const LayeredDepthMap map = render_layered_depth_map(row, looking_along_z(0.5), options(9));
    const auto centre = map.layers(4, 4);  // its ray is the z axis
    ASSERT_EQ(centre.size(), 4u);
    EXPECT_EQ(centre[0], 4.0f);
    EXPECT_EQ(centre[1], 6.0f);
    EXPECT_EQ(centre[2], 9.0f);
    EXPECT_EQ(centre[3], 11.0f);
    EXPECT_TRUE(map.layers(0, 0).empty());  // 32 degrees off the axis: misses both
    const LayeredDepthMap capped = render_layered_depth_map(row, looking_along_z(0.5), options(9, 2));
    ASSERT_EQ(capped.layers(4, 4).size(), 2u);
    EXPECT_EQ(capped.layers(4, 4)[1], 6.0f);
}

TEST(LayeredDepthRender, ProximityPruningMergesAThinStrandsFaces)
{
    const PreparedScene strand({Capsule{{-1, 0, 5}, {1, 0, 5}, 1e-4}});
    EXPECT_EQ(render_layered_depth_map(strand, looking_along_z(0.5), options(9)).layers(4, 4).size(), 1u);
    EXPECT_EQ(render_layered_depth_map(strand, looking_along_z(0.5), options(9, 8, 0)).layers(4, 4).size(), 2u);
}

// The distance from p to the nearest primitive's surface (inside or out: a
// crossing inside another solid is still on its own primitive's surface).
double distance_to_a_surface(const std::vector<Primitive>& surfaces, Vec3 p)
{
    double nearest = INFINITY;
    for (const Primitive& surface : surfaces)
        std::visit(
            [&](const auto& shape) {
                using Shape = std::decay_t<decltype(shape)>;
                if constexpr (std::is_same_v<Shape, Box>)
                    nearest = std::fmin(nearest, std::fabs(signed_distance(p, OrientedBox::from(shape))));
                else
                    nearest = std::fmin(nearest, std::fabs(signed_distance(p, shape)));
            },
            surface);
    return nearest;
}

TEST(LayeredDepthRender, EveryLayerLiesOnASurfaceWhateverTheThreads)
{
    const Scene scene = builtin_scene("contact");
    const std::vector<Primitive> surfaces = pismo_casters(scene);
    const PreparedScene casters(surfaces);
    const Vec3 fixation = pismo_fixation_point(scene);
    const MapCamera camera = pismo_vertex_camera(scene, light_mesh(scene.light, 0).vertices[1], fixation);
    const LayeredDepthMap map = render_layered_depth_map(casters, camera, options(48));
    const Vec3 o{camera.position[0], camera.position[1], camera.position[2]};
    const Vec3 r{camera.right[0], camera.right[1], camera.right[2]}, dn{camera.down[0], camera.down[1], camera.down[2]},
               f{camera.forward[0], camera.forward[1], camera.forward[2]};
    int hits = 0;
    for (int j = 0; j < map.height(); ++j)
        for (int i = 0; i < map.width(); ++i) {
            const double x = (2 * (i + 0.5) / 48 - 1) * camera.tan_half_fov,
                         y = (2 * (j + 0.5) / 48 - 1) * camera.tan_half_fov;
            const Vec3 dir = normalize(f + r * x + dn * y);
            for (float d : map.layers(i, j)) {
                EXPECT_LT(distance_to_a_surface(surfaces, o + dir * double(d)), 4e-6 * d) << i << ", " << j;
                ++hits;
            }
        }
    EXPECT_GT(hits, 20) << "the casters fill part of the map";
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const LayeredDepthMap serial = render_layered_depth_map(casters, camera, options(48));
    EXPECT_EQ(serial.offsets(), map.offsets());
    EXPECT_EQ(serial.depths(), map.depths());
}

TEST(LayeredDepthRender, BadOptionsNameTheOption)
{
    const PreparedScene empty(std::vector<Primitive>{});
    expect_error([&] { render_layered_depth_map(empty, looking_along_z(1), options(0)); },
                 ErrorCategory::InvalidArgument, "pismo_maps", "map size");
    expect_error([&] { render_layered_depth_map(empty, looking_along_z(1), options(4, 0)); },
                 ErrorCategory::InvalidArgument, "pismo_maps", "layers per pixel");
    expect_error([&] { render_layered_depth_map(empty, looking_along_z(1), options(4, 8, -1)); },
                 ErrorCategory::InvalidArgument, "pismo_maps", "pruning");
}

// The distance from p to one surface.
double distance_to(const Primitive& surface, Vec3 p) { return distance_to_a_surface({surface}, p); }

// Surface ids (docs/pismo.md, "A surface id per layer"): on fence, where the
// rails touch the pickets' backs, each layer lies on the surface its id names,
// a caster (not the ground, which the maps leave out); each receiver on its own.
TEST(PismoMaps, EachLayerAndReceiverNamesTheSurfaceItLiesOn)
{
    const Scene scene = builtin_scene("fence");
    const std::vector<Primitive> surfaces = scene_surfaces(scene);
    const std::vector<int> casters = pismo_caster_surfaces(scene);
    ASSERT_EQ(casters.size(), surfaces.size() - 1) << "every surface but the ground";
    EXPECT_EQ(casters.front(), 1);
    const PismoMaps maps = render_pismo_maps(scene, 0, options(40));
    ASSERT_EQ(maps.surface_ids.size(), maps.maps.size());
    std::size_t layers = 0;
    for (std::size_t k = 0; k < maps.maps.size(); ++k) {
        const LayeredDepthMap& map = maps.maps[k];
        ASSERT_EQ(maps.surface_ids[k].size(), map.depths().size());
        layers += map.depths().size();
        const MapCamera& c = map.camera();
        const Vec3 o{c.position[0], c.position[1], c.position[2]}, r{c.right[0], c.right[1], c.right[2]},
                   dn{c.down[0], c.down[1], c.down[2]}, f{c.forward[0], c.forward[1], c.forward[2]};
        for (int j = 0; j < map.height(); ++j)
            for (int i = 0; i < map.width(); ++i) {
                const double x = (2 * (i + 0.5) / map.width() - 1) * c.tan_half_fov,
                             y = (2 * (j + 0.5) / map.height() - 1) * c.tan_half_fov;
                const Vec3 dir = normalize(f + r * x + dn * y);
                const std::size_t pixel = std::size_t(j) * std::size_t(map.width()) + std::size_t(i);
                for (std::uint32_t l = map.offsets()[pixel]; l < map.offsets()[pixel + 1]; ++l) {
                    const int id = maps.surface_ids[k][l];
                    ASSERT_TRUE(std::find(casters.begin(), casters.end(), id) != casters.end()) << id;
                    const double d = map.depths()[l];
                    EXPECT_LT(distance_to(surfaces[std::size_t(id)], o + dir * d), 4e-6 * d) << k << ": " << i << ", " << j;
                }
            }
    }
    EXPECT_GT(layers, 100u) << "the maps see the fence";
    const Receivers rx = render_receivers(scene, 33, 19);
    int on_casters = 0;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            const int id = int(rx.surface.at(0, x, y));
            if (rx.hit.at(0, x, y) == 0) {
                EXPECT_EQ(id, -1);
                continue;
            }
            ASSERT_TRUE(id >= 0 && id < int(surfaces.size())) << id;
            const Vec3 p{rx.world_position.at(0, x, y), rx.world_position.at(1, x, y), rx.world_position.at(2, x, y)};
            EXPECT_LT(distance_to(surfaces[std::size_t(id)], p), 1e-5) << x << ", " << y;  // positions are floats
            on_casters += id > 0;
        }
    EXPECT_GT(on_casters, 20) << "the view sees the pickets";
}

TEST(PismoMaps, OneMapPerVertex)
{
    const PismoMaps maps = render_pismo_maps(builtin_scene("overlap"), 1, options(16));
    EXPECT_EQ(maps.maps.size(), 9u);
    for (const LayeredDepthMap& map : maps.maps) EXPECT_GT(map.depths().size(), 0u);
}

}  // namespace
}  // namespace penumbra::reference
