// Pismo's shadow-ray test (penumbra/pismo.h, kernels/pismo.h) on every
// backend: against its float64 reference (support/pismo_reference.h: the same
// maps, the same ray pattern) receiver by receiver; a ray ending at a light
// vertex against that vertex's hard shadow-map test; a blocker half-plane
// parallel to the light against the closed form, fully lit beside its
// penumbra and fully dark under it; odd receiver sizes and many chunks of
// rows giving the same values; bad input refused with a typed Error.
//
// Tolerance against float64: the kernel lands points in float32, so a
// point within a rounding of a pixel's edge may land in the neighbour, and a
// depth within a rounding of the bias limit may compare the other way. Each
// such flip moves one ray, at most its weight (1/rays for a small triangle's
// single ray, share/n^2 in general) times its corner's weight. The test
// bounds how many receivers differ at all (kMaxFlippedShare) and by how much.
// Measured: none of 1872 receivers differs by more than 1e-4 in any of the
// eight cases, on scalar, AVX-512 and PoCL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "kernels/params.h"
#include "penumbra/pismo.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "pismo_rays.h"
#include "support/backends.h"
#include "support/errors.h"
#include "support/pismo_reference.h"
#include "support/pismo_scenes.h"

namespace penumbra {
namespace {

using reference::Vec3;
using testing::backend_names;
using testing::backend_test_name;
using testing::library_maps;

constexpr double kAgree = 1e-4;           // float32 sums of up to a few hundred ray weights
constexpr double kMaxFlippedShare = 0.01;  // receivers with any ray landing otherwise than in float64

Vec3 position(const Image& world, int x, int y) { return {world.at(0, x, y), world.at(1, x, y), world.at(2, x, y)}; }

// A scene with its receivers and maps, made once per test process.
struct PismoCase {
    reference::Scene scene;
    reference::Receivers receivers;
    reference::PismoMaps maps;
};

const PismoCase& scene_case(const std::string& name, int level, int map_size = 128)
{
    static std::map<std::string, PismoCase> cases;
    const std::string key = name + "/" + std::to_string(level) + "/" + std::to_string(map_size);
    auto it = cases.find(key);
    if (it == cases.end()) {
        const reference::Scene scene = reference::builtin_scene(name);
        reference::LayeredMapOptions mo;
        mo.size = map_size;
        it = cases.emplace(key, PismoCase{scene, reference::render_receivers(scene, 52, 36),
                                     reference::render_pismo_maps(scene, level, mo)})
                 .first;
    }
    return it->second;
}

void expect_in_unit_range(const Image& v, const std::string& what)
{
    for (int y = 0; y < v.height(); ++y)
        for (int x = 0; x < v.width(); ++x)
            ASSERT_TRUE(v.at(0, x, y) >= 0.0f && v.at(0, x, y) <= 1.0f) << what << " (" << x << ", " << y << ") "
                                                                        << v.at(0, x, y);
}

using Pismo = ::testing::TestWithParam<std::string>;

PN_BACKEND_TEST(Pismo, AgreesWithTheFloat64ReferenceReceiverByReceiver)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const char* name : {"contact", "overlap"})
        for (int level : {0, 1})
            for (PismoDepths depths : {PismoDepths::Layered, PismoDepths::MaximumDepth}) {
                const PismoCase& c = scene_case(name, level);
                const bool layered = depths == PismoDepths::Layered;
                const auto ref = layered ? testing::PismoReferenceMaps::layered(c.maps)
                                         : testing::PismoReferenceMaps::maximum_depth(c.maps);
                const Image& world = c.receivers.world_position;
                PismoOptions o;
                o.rays = 48;
                const Image got = pismo_shade(ctx, library_maps(c.maps, depths), world, o);
                testing::PismoReferenceOptions ro;
                ro.rays = o.rays;
                int flipped = 0, lit = 0, dark = 0;
                double worst = 0;
                for (int y = 0; y < world.height(); ++y)
                    for (int x = 0; x < world.width(); ++x) {
                        const double want = testing::pismo_visibility(ref, position(world, x, y), ro);
                        const double d = std::abs(got.at(0, x, y) - want);
                        flipped += d > kAgree;
                        worst = std::max(worst, d);
                        lit += want > 0.99;
                        dark += want < 0.01;
                    }
                const std::string what = std::string(name) + " level " + std::to_string(level) +
                                         (layered ? " layered" : " maximum-depth") + " on " + backend;
                EXPECT_LE(flipped, kMaxFlippedShare * world.width() * world.height()) << what << ", worst " << worst;
                EXPECT_LE(worst, 0.05) << what;  // one ray of the 4 x 8 at level 1 weighs 1/32
                EXPECT_GT(lit, 0) << what;
                EXPECT_GT(dark, 0) << what;
                expect_in_unit_range(got, what);
            }
}

Vec3 normal_of(const Image& rx6, int x, int y) { return {rx6.at(3, x, y), rx6.at(4, x, y), rx6.at(5, x, y)}; }

// The same with normals (kernels/pismo.h, the receiver's own surface). A
// slope-scaled bias puts more limits within a rounding of a layer, so the
// flips are counted as above.
PN_BACKEND_TEST(Pismo, WithNormalsAgreesWithTheFloat64ReferenceReceiverByReceiver)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const char* name : {"contact", "overlap"}) {
        const PismoCase& c = scene_case(name, 1);
        const auto ref = testing::PismoReferenceMaps::layered(c.maps);
        const Image rx6 = c.receivers.positions_and_normals();
        PismoOptions o;
        o.rays = 48;
        const Image got = pismo_shade(ctx, library_maps(c.maps), rx6, o);
        testing::PismoReferenceOptions ro;
        ro.rays = o.rays;
        ro.max_slope = kPismoMaxSlopeTexels;
        int flipped = 0;
        double worst = 0;
        for (int y = 0; y < rx6.height(); ++y)
            for (int x = 0; x < rx6.width(); ++x) {
                const double want = testing::pismo_visibility(ref, position(rx6, x, y), ro, normal_of(rx6, x, y));
                const double d = std::abs(got.at(0, x, y) - want);
                flipped += d > kAgree;
                worst = std::max(worst, d);
            }
        const std::string what = std::string(name) + " with normals on " + backend;
        EXPECT_LE(flipped, kMaxFlippedShare * rx6.width() * rx6.height()) << what << ", worst " << worst;
        EXPECT_LE(worst, 0.05) << what;
        expect_in_unit_range(got, what);
    }
}

// The same with surface ids (kernels/pismo.h; docs/pismo.md, "A surface id
// per layer"): a layer of the receiver's own surface never occludes it, any
// other with a bias of 1 texel. On fence the ids change the answer most (the
// pickets under the rails), so it is tested beside contact and overlap.
// Receivers with the 7th plane and maps without ids shade as with 6 planes.
PN_BACKEND_TEST(Pismo, WithSurfaceIdsAgreesWithTheFloat64ReferenceReceiverByReceiver)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const char* name : {"fence", "contact", "overlap"}) {
        const PismoCase& c = scene_case(name, 1);
        const auto ref = testing::PismoReferenceMaps::layered(c.maps);
        const Image rx7 = c.receivers.positions_normals_and_surface();
        PismoOptions o;
        o.rays = 48;
        const Image got = pismo_shade(ctx, library_maps(c.maps, PismoDepths::Layered, true), rx7, o);
        testing::PismoReferenceOptions ro;
        ro.rays = o.rays;
        ro.max_slope = kPismoMaxSlopeTexels;
        ro.surface_ids = true;
        ro.other_bias_texels = kPismoOtherSurfaceBiasTexels;
        int flipped = 0, changed = 0;
        double worst = 0;
        for (int y = 0; y < rx7.height(); ++y)
            for (int x = 0; x < rx7.width(); ++x) {
                const int surface = int(rx7.at(6, x, y));
                const double want =
                    testing::pismo_visibility(ref, position(rx7, x, y), ro, normal_of(rx7, x, y), surface);
                const double d = std::abs(got.at(0, x, y) - want);
                flipped += d > kAgree;
                worst = std::max(worst, d);
                changed += std::abs(want - testing::pismo_visibility(ref, position(rx7, x, y), ro, normal_of(rx7, x, y))) > 0.01;
            }
        const std::string what = std::string(name) + " with surface ids on " + backend;
        EXPECT_LE(flipped, kMaxFlippedShare * rx7.width() * rx7.height()) << what << ", worst " << worst;
        EXPECT_LE(worst, 0.05) << what;
        expect_in_unit_range(got, what);
        if (std::string(name) == "fence") {
            EXPECT_GT(changed, 10) << "the ids change fence's answer";
        }
        const Image without = pismo_shade(ctx, library_maps(c.maps), rx7, o);
        const Image six = pismo_shade(ctx, library_maps(c.maps), c.receivers.positions_and_normals(), o);
        EXPECT_EQ(0, std::memcmp(without.plane(0), six.plane(0), sizeof(float) * std::size_t(six.plane_pitch())))
            << what << ": maps without ids ignore the 7th plane";
    }
}

// The receiver's own surface against closed forms (support/pismo_scenes.h,
// sphere_and_slab_scene): a thin slab's face turned from the light is dark
// and its face toward it lit; a point of the sphere whose tangent plane has
// the whole light above it is fully lit (no acne: the slope-scaled bias),
// one with the whole light below fully dark. Without normals the fixed bias
// of 2 texels (more than the slab's 2 cm at 128^2) lets its far face leak.
PN_BACKEND_TEST(Pismo, TheReceiversOwnSurfaceMeetsTheClosedForms)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    static const reference::Scene scene = testing::sphere_and_slab_scene();
    reference::LayeredMapOptions mo;
    mo.size = 128;
    static const reference::PismoMaps m = reference::render_pismo_maps(scene, 1, mo);
    const testing::OwnSurfaceReceivers rx = testing::own_surface_receivers(scene);
    PismoOptions o;
    o.rays = 64;
    const Image got = pismo_shade(ctx, library_maps(m), rx.points, o);
    ASSERT_GT(rx.lit.size(), 20u);
    ASSERT_GT(rx.dark.size(), 20u);
    for (const int x : rx.lit) EXPECT_EQ(got.at(0, x, 0), 1.0f) << "lit receiver " << x << " on " << backend;
    for (const int x : rx.dark) EXPECT_EQ(got.at(0, x, 0), 0.0f) << "dark receiver " << x << " on " << backend;
    // The same points without their normals: the slab's far face leaks.
    Image positions(rx.points.width(), 1, 3);
    for (int x = 0; x < positions.width(); ++x)
        for (int c = 0; c < 3; ++c) positions.at(c, x, 0) = rx.points.at(c, x, 0);
    const Image fixed = pismo_shade(ctx, library_maps(m), positions, o);
    int leaks = 0;
    for (const int x : rx.slab_far_face) leaks += fixed.at(0, x, 0) > 0.5f;
    EXPECT_GT(leaks, int(rx.slab_far_face.size()) / 2) << backend;
}

// The sphere and capsule of `contact` shadow themselves inside their convex
// hull, where a maximum-depth map holds the far side of a caster, not the
// surface that occludes a point on it (the source's warning, item 4).
PN_BACKEND_TEST(Pismo, MaximumDepthMapsFailWhereTheCastersShadowThemselves)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const PismoCase& c = scene_case("contact", 1, 384);
    static const Image truth = [&] {
        reference::GroundTruthOptions go;
        go.strata = 8;
        return reference::ground_truth(c.scene, c.receivers, go);
    }();
    const Image& world = c.receivers.world_position;
    double error[2] = {0, 0};
    int on_casters = 0;
    for (PismoDepths depths : {PismoDepths::Layered, PismoDepths::MaximumDepth}) {
        const Image got = pismo_shade(ctx, library_maps(c.maps, depths), world);
        double& e = error[depths == PismoDepths::MaximumDepth];
        on_casters = 0;
        for (int y = 0; y < world.height(); ++y)
            for (int x = 0; x < world.width(); ++x) {
                if (c.receivers.mask.at(0, x, y) == 0 || world.at(1, x, y) < 0.01f) continue;  // the ground
                const double d = got.at(0, x, y) - truth.at(0, x, y);
                e += d * d;
                ++on_casters;
            }
        e = std::sqrt(e / on_casters);
    }
    std::printf("contact, receivers on the casters (%d): RMSE layered %.4f, maximum depth %.4f (%s)\n", on_casters,
                error[0], error[1], backend.c_str());
    ASSERT_GT(on_casters, 100);
    // Measured 0.1325 and 0.5778 (maps of 384^2, level 1, shifted grids;
    // centred 0.143 and 0.579); what remains of the
    // layered error sits at the sphere's terminator (docs/pismo.md).
    EXPECT_LT(error[0], 0.2) << backend;
    EXPECT_GT(error[1], 3 * error[0]) << backend;
}

// One ray, ending at corner k of triangle t (w_k = 1, weight 1); the other
// triangles cast none (the kernel loops over the table's triangles only).
detail::PismoRayTable ray_at_vertex(const reference::LightMesh& mesh, int t, int k)
{
    detail::PismoRayTable table;
    const auto& tri = mesh.triangles[std::size_t(t)];
    table.triangles = {std::uint32_t(tri[0]), std::uint32_t(tri[1]), std::uint32_t(tri[2]), 0, 1};
    table.rays = {0, 0, 0, 1};
    table.rays[std::size_t(k)] = 1;
    return table;
}

PN_BACKEND_TEST(Pismo, ARayEndingAtALightVertexIsThatVertexsHardShadowTest)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const PismoCase& c = scene_case("contact", 1);
    const PismoMaps maps = library_maps(c.maps);
    const Image& world = c.receivers.world_position;
    for (int t : {0, 5})
        for (int k = 0; k < 3; ++k) {
            Image got(world.width(), world.height(), 1);
            const detail::PismoRayTable table = ray_at_vertex(c.maps.mesh, t, k);
            detail::pismo_shade_rays(ctx, maps, table, 2.0f, world, got);
            const int vertex = c.maps.mesh.triangles[std::size_t(t)][std::size_t(k)];
            int shadowed = 0, differ = 0;
            for (int y = 0; y < world.height(); ++y)
                for (int x = 0; x < world.width(); ++x) {
                    const bool hard =
                        testing::hard_shadow_test(c.maps.maps[std::size_t(vertex)], position(world, x, y), 2);
                    shadowed += hard;
                    differ += got.at(0, x, y) != (hard ? 0.0f : 1.0f);
                }
            // A receiver within a float32 rounding of a pixel's edge may land in the neighbour.
            EXPECT_LE(differ, 2) << "triangle " << t << " corner " << k << " on " << backend;
            EXPECT_GT(shadowed, 0);
        }
}

PN_BACKEND_TEST(Pismo, ABlockerPlaneParallelToTheLightMeetsTheClosedForm)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    static const reference::Scene scene = testing::half_plane_scene();
    reference::LayeredMapOptions mo;
    mo.size = 256;
    static const reference::PismoMaps m = reference::render_pismo_maps(scene, 0, mo);
    const PismoMaps maps = library_maps(m, PismoDepths::Layered);
    // Ground points across the penumbra (x in [-1, 1]) and past both ends of it.
    const int n = 81;
    Image world(n, 2, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < n; ++x) {
            world.at(0, x, y) = float(-2 + 4.0 * x / (n - 1));
            world.at(2, x, y) = float(0.3 * y - 0.15);
        }
    PismoOptions o;
    o.rays = 256;
    const Image got = pismo_shade(ctx, maps, world, o);
    double sum = 0;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < n; ++x) {
            const double px = world.at(0, x, y), want = testing::half_plane_visibility(px);
            const double d = got.at(0, x, y) - want;
            sum += d * d;
            EXPECT_NEAR(got.at(0, x, y), want, 0.03) << "x = " << px << " on " << backend;
            if (px > 1.3) {
                EXPECT_EQ(got.at(0, x, y), 1.0f) << "outside the shadow, x = " << px;
            }
            if (px < -1.3) {
                EXPECT_EQ(got.at(0, x, y), 0.0f) << "under the blocker, x = " << px;
            }
        }
    EXPECT_LT(std::sqrt(sum / (2 * n)), 0.01) << backend;
}

// The claim of the maps' shifted grids (docs/pismo.md, "Where fence's error
// comes from"): slats 1 to 2 texels wide on the plane of the maps' common
// fixation point are rounded to whole pixels alike in every map when every
// grid is centred on that point, so more maps do not lower the error; with
// each grid shifted by its own fraction of a texel the roundings differ and
// average out, and the error against the closed form falls with the level.
PN_BACKEND_TEST(Pismo, ShiftedGridsLetThinSlatsConvergeToTheClosedForm)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    static const reference::Scene scene = testing::slats_scene();
    const int n = 201;
    Image points(n, 1, 3);  // a row under the slats, 1 m below them
    std::vector<Vec3> region;
    for (int x = 0; x < n; ++x) {
        region.push_back({-1 + 2.0 * x / (n - 1), 4, 0});
        points.at(0, x, 0) = float(region.back().x);
        points.at(1, x, 0) = 4;
    }
    static std::map<std::pair<bool, int>, reference::PismoMaps> made;
    double rmse[2][4] = {};
    for (const bool shifted : {false, true})
        for (const int level : {0, 1, 2, 3}) {
            auto it = made.find({shifted, level});
            if (it == made.end()) {
                reference::LayeredMapOptions mo;
                mo.size = 128;
                mo.shift_grids = shifted;
                it = made.emplace(std::pair{shifted, level}, reference::render_pismo_maps(scene, level, mo, region)).first;
            }
            PismoOptions o;
            o.rays = 1024;
            const Image got = pismo_shade(ctx, library_maps(it->second), points, o);
            double sum = 0;
            for (int x = 0; x < n; ++x) {
                const double d = got.at(0, x, 0) - testing::slats_visibility(region[std::size_t(x)].x, 4);
                sum += d * d;
            }
            rmse[shifted][level] = std::sqrt(sum / n);
        }
    std::printf("slats, RMSE against the closed form at levels 0..3, centred grids %.4f %.4f %.4f %.4f, shifted "
                "%.4f %.4f %.4f %.4f (%s)\n",
                rmse[0][0], rmse[0][1], rmse[0][2], rmse[0][3], rmse[1][0], rmse[1][1], rmse[1][2], rmse[1][3],
                backend.c_str());
    // Measured (every backend alike): centred 0.0274 0.0228 0.0152 0.0170,
    // shifted 0.0262 0.0168 0.0154 0.0097. Centred grids stall from level 2
    // on; shifted ones keep falling.
    EXPECT_LT(rmse[1][3], 0.7 * rmse[0][3]) << backend;
    EXPECT_LT(rmse[1][3], 0.5 * rmse[1][0]) << backend;
    EXPECT_GT(rmse[0][3], 0.5 * rmse[0][0]) << backend;
}

// Crops of the contact receivers at every strip shape, and many chunks of
// rows, give the values of the whole image.
PN_BACKEND_TEST(Pismo, OddSizesAndChunksGiveTheWholeImagesValues)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    // Positions only, and fence with normals and surface ids (the layer walk).
    for (const bool ids : {false, true}) {
        const PismoCase& c = scene_case(ids ? "fence" : "contact", 0);
        const PismoMaps maps = library_maps(c.maps, PismoDepths::Layered, ids);
        const Image world = ids ? c.receivers.positions_normals_and_surface() : c.receivers.world_position;
        PismoOptions o;
        o.rays = 16;
        const Image whole = pismo_shade(ctx, maps, world, o);
        expect_in_unit_range(whole, "whole");
        std::vector<int> widths = testing::lane_edge_widths();
        widths.push_back(7);
        for (int w : widths)
            for (int h : {1, 3}) {
                if (w > world.width()) continue;
                const int x0 = 5 % (world.width() - w + 1);
                Image crop(w, h, world.channels());
                for (int ch = 0; ch < world.channels(); ++ch)
                    for (int y = 0; y < h; ++y)
                        for (int x = 0; x < w; ++x) crop.at(ch, x, y) = world.at(ch, x + x0, y + 10);
                const Image got = pismo_shade(ctx, maps, crop, o);
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x)
                        EXPECT_EQ(got.at(0, x, y), whole.at(0, x + x0, y + 10))
                            << w << "x" << h << " at " << x << ", " << y << " on " << backend << (ids ? ", ids" : "");
            }
        // One row a chunk: the estimates of 4 maps of one row are 4 W floats.
        Image chunked(world.width(), world.height(), 1);
        detail::pismo_shade_rays(ctx, maps, detail::pismo_ray_table(maps.vertices(), maps.triangles(), o.rays),
                                 o.bias_texels, world, chunked, 1);
        for (int y = 0; y < world.height(); ++y)
            for (int x = 0; x < world.width(); ++x) ASSERT_EQ(chunked.at(0, x, y), whole.at(0, x, y)) << x << ", " << y;
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, Pismo, ::testing::ValuesIn(backend_names()), backend_test_name);

TEST(PismoRays, StratifyEachTriangleByItsShareOfTheArea)
{
    const std::vector<std::array<double, 3>> v{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {2, 2, 0}, {4, 0, 0}};
    // Two triangles of area 2 and one of area 4: shares 1/4, 1/4, 1/2.
    const std::vector<std::array<int, 3>> t{{0, 1, 2}, {1, 3, 2}, {1, 4, 3}};
    const auto table = detail::pismo_ray_table(v, {t[0], t[1]}, 64);
    ASSERT_EQ(table.triangles.size(), 2u * PN_PISMO_TRIANGLE_UINTS);
    EXPECT_EQ(table.triangles[4] - table.triangles[3], 32u / 32u * 36u);  // n = round(sqrt(32)) = 6
    double total = 0;
    for (std::size_t r = 0; r < table.rays.size(); r += PN_PISMO_RAY_FLOATS) {
        EXPECT_NEAR(table.rays[r] + table.rays[r + 1] + table.rays[r + 2], 1.0, 1e-6);
        for (int k = 0; k < 3; ++k) EXPECT_GE(table.rays[r + std::size_t(k)], 0.0f);
        total += table.rays[r + 3];
    }
    EXPECT_NEAR(total, 1.0, 1e-6);
    const auto small = detail::pismo_ray_table(v, t, 1);
    EXPECT_EQ(small.rays.size(), 3u * PN_PISMO_RAY_FLOATS) << "at least one ray through every triangle";
}

// PismoMaps holds its maps packed for the kernel; they come back as made.
TEST(PismoMapsHeld, TestAndBledMapsComeBackAsMade)
{
    const PismoCase& c = scene_case("contact", 0, 16);
    for (PismoDepths depths : {PismoDepths::Layered, PismoDepths::MaximumDepth}) {
        const PismoMaps maps = library_maps(c.maps, depths);
        const std::vector<LayeredDepthMap> test = maps.test_maps(), bled = maps.bled_maps();
        ASSERT_EQ(test.size(), c.maps.maps.size());
        ASSERT_EQ(bled.size(), c.maps.maps.size());
        std::size_t bytes = 0;
        for (std::size_t j = 0; j < test.size(); ++j) {
            const LayeredDepthMap made =
                depths == PismoDepths::Layered ? c.maps.maps[j] : maximum_depth_map(c.maps.maps[j]);
            const LayeredDepthMap made_bled = bleed_empty_pixels(made);
            EXPECT_EQ(test[j].offsets(), made.offsets()) << j;
            EXPECT_EQ(test[j].depths(), made.depths()) << j;
            EXPECT_EQ(bled[j].offsets(), made_bled.offsets()) << j;
            EXPECT_EQ(bled[j].depths(), made_bled.depths()) << j;
            EXPECT_EQ(test[j].camera().position, made.camera().position) << j;
            bytes += made.bytes() + made_bled.bytes();
        }
        // One end entry per set instead of one per map.
        EXPECT_EQ(maps.bytes(), bytes - 2 * 4 * (test.size() - 1));
    }
    EXPECT_TRUE(PismoMaps().test_maps().empty());
    EXPECT_EQ(PismoMaps().bytes(), 0u);
}

class PismoBadInput : public ::testing::Test {
protected:
    Context& ctx = PN_CONTEXT_OR_SKIP("scalar");
    const PismoCase& c = scene_case("contact", 0, 16);
    std::vector<std::array<double, 3>> vertices()
    {
        std::vector<std::array<double, 3>> v;
        for (const Vec3& p : c.maps.mesh.vertices) v.push_back({p.x, p.y, p.z});
        return v;
    }
};

TEST_F(PismoBadInput, OptionsOutOfRange)
{
    const PismoMaps maps(vertices(), c.maps.mesh.triangles, c.maps.maps);
    const Image& rx = c.receivers.world_position;
    for (int rays : {0, -3, kPismoMaxRays + 1}) {
        PismoOptions o;
        o.rays = rays;
        testing::expect_error([&] { pismo_shade(ctx, maps, rx, o); }, ErrorCategory::InvalidArgument, "pismo",
                              {"rays"});
    }
    PismoOptions o;
    o.bias_texels = -1;
    testing::expect_error([&] { pismo_shade(ctx, maps, rx, o); }, ErrorCategory::InvalidArgument, "pismo",
                          {"bias-texels"});
}

TEST_F(PismoBadInput, MapsAndMeshThatDisagree)
{
    const auto& tris = c.maps.mesh.triangles;
    const auto& maps = c.maps.maps;
    const auto refused = [&](auto make, const std::string& needle) {
        testing::expect_error(make, ErrorCategory::InvalidArgument, "pismo", {needle});
    };
    refused([&] { PismoMaps(vertices(), tris, {maps.begin(), maps.end() - 1}); }, "one map per vertex");
    refused([&] { PismoMaps({}, {}, {}); }, "the light mesh is empty");
    refused([&] { PismoMaps(vertices(), {{0, 1, 9}}, maps); }, "names vertex 9");
    refused([&] { PismoMaps(vertices(), {{0, 1, 1}}, maps); }, "has no area");
    auto moved = vertices();
    moved[2][0] += 0.5;
    refused([&] { PismoMaps(moved, tris, maps); }, "the camera of map 2");
    std::vector<LayeredDepthMap> sizes = maps;
    sizes[1] = reference::render_pismo_maps(c.scene, 0, {.size = 8}).maps[1];
    refused([&] { PismoMaps(vertices(), tris, sizes); }, "render every map at one size");
    std::vector<LayeredDepthMap> empty(maps.size());
    refused([&] { PismoMaps(vertices(), tris, empty); }, "has no pixels");
    refused([&] { pismo_shade(ctx, PismoMaps(), c.receivers.world_position); }, "no maps");
    const auto& ids = c.maps.surface_ids;
    refused([&] { PismoMaps(vertices(), tris, maps, PismoDepths::Layered, {ids.begin(), ids.end() - 1}); },
            "lists of surface ids");
    const std::size_t j = std::size_t(std::find_if(ids.begin(), ids.end(), [](const auto& l) { return !l.empty(); }) -
                                      ids.begin());
    ASSERT_LT(j, ids.size()) << "a map with layers";
    auto short_list = ids;
    short_list[j].pop_back();
    refused([&] { PismoMaps(vertices(), tris, maps, PismoDepths::Layered, short_list); }, "give one id a layer");
    auto negative = ids;
    negative[j][0] = -3;
    refused([&] { PismoMaps(vertices(), tris, maps, PismoDepths::Layered, negative); }, "surface id -3");
    refused([&] { PismoMaps(vertices(), tris, maps, PismoDepths::MaximumDepth, ids); }, "give no surface ids");
}

TEST_F(PismoBadInput, ReceiversAndOutput)
{
    const PismoMaps maps(vertices(), c.maps.mesh.triangles, c.maps.maps);
    testing::expect_error([&] { pismo_shade(ctx, maps, Image(4, 4, 2)); }, ErrorCategory::InvalidArgument, "pismo",
                          {"receivers", "x, y, z"});
    testing::expect_error([&] { pismo_shade(ctx, maps, Image()); }, ErrorCategory::InvalidArgument, "pismo",
                          {"receivers"});
    Image wrong(3, 3, 1);
    testing::expect_error([&] { pismo_shade(ctx, maps, Image(4, 4, 3), {}, wrong); }, ErrorCategory::InvalidArgument,
                          "pismo", {"1-channel image of the receivers' size"});
    Image rx = c.receivers.world_position;
    rx.at(1, 3, 7) = std::nanf("");
    testing::expect_error([&] { pismo_shade(ctx, maps, rx); }, ErrorCategory::InvalidData, "pismo", {"(3, 7)"});
    // A 7th plane of surface ids: -1 or an integer a float holds exactly, else the pixel is named.
    for (float id : {-2.0f, 2.5f, std::nanf(""), float(kPismoMaxSurfaceId) + 1.0f}) {
        Image rx7 = c.receivers.positions_normals_and_surface();
        rx7.at(6, 2, 5) = id;
        testing::expect_error([&] { pismo_shade(ctx, maps, rx7); }, ErrorCategory::InvalidData, "pismo",
                              {"surface id at pixel (2, 5)"});
    }
}

}  // namespace
}  // namespace penumbra
