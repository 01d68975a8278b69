// The SDF host side: bad options, grids and receivers (penumbra::Error with
// its category and a message naming the parameter), grid files, baking,
// packing, k from the light's size, and the lane-utilisation count.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>

#include "penumbra/error.h"
#include "penumbra/reference.h"
#include "penumbra/reference/sdf_scene.h"
#include "penumbra/sdf.h"
#include "support/errors.h"
#include "support/sdf_test_scenes.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using reference::Vec3;

using testing::expect_error;

struct Fixture {
    Context ctx{ContextOptions{Backend::Scalar, {}}};
    reference::Scene scene = testing::sphere_over_plane();
    AnalyticScene analytic = reference::analytic_scene(scene.primitives);
    DistanceGrid grid = bake_distance_grid(scene, distance_grid_box(scene, 0.2), 0.1);
    Image positions = testing::points_image({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, 3);
    Image normals = testing::points_image({{0, 1, 0}, {0, 1, 0}, {0, 1, 0}}, 3);
    SdfOptions options = sdf_options_for(scene);
};

TEST(SdfInput, RejectsBadOptions)
{
    Fixture f;
    auto with = [&](const std::function<void(SdfOptions&)>& change, const std::string& needle) {
        SdfOptions o = f.options;
        change(o);
        expect_error([&] { sdf_shadows(f.ctx, f.analytic, f.positions, &f.normals, o); },
                     ErrorCategory::InvalidArgument, needle);
        expect_error([&] { sdf_shadows(f.ctx, f.grid, f.positions, &f.normals, o); }, ErrorCategory::InvalidArgument,
                     needle);
    };
    for (float k : {0.0f, -1.0f, NAN, INFINITY}) with([&](SdfOptions& o) { o.k = k; }, "k must be");
    with([](SdfOptions& o) { o.t_max = o.t_min; }, "t_max must be finite and > t_min");
    with([](SdfOptions& o) { o.t_min = 2.0f, o.t_max = 1.0f; }, "t_max must be finite and > t_min");
    with([](SdfOptions& o) { o.t_max = INFINITY; }, "t_max");
    with([](SdfOptions& o) { o.t_min = -0.1f; }, "t_min must be");
    with([](SdfOptions& o) { o.max_steps = 0; }, "max_steps");
    with([](SdfOptions& o) { o.hit_epsilon = 0.0f; }, "hit_epsilon");
    with([](SdfOptions& o) { o.hit_epsilon = NAN; }, "hit_epsilon");
    with([](SdfOptions& o) { o.normal_offset = -1e-3f; }, "normal_offset");
    with([](SdfOptions& o) { o.light = SdfLight::towards({0, 0, 0}), o.light_width = 0.0f; }, "direction is zero");
    with([](SdfOptions& o) { o.light = SdfLight::at({0, NAN, 0}); }, "centre is not finite");
    with([](SdfOptions& o) { o.light_width = -1.0f; }, "light_width must be");
    with([](SdfOptions& o) { o.light = SdfLight::towards({0, 1, 0}); }, "light_width applies to a light at a point");
    expect_error([&] { sdf_shadows(f.ctx, f.analytic, f.positions, nullptr, f.options); },
                 ErrorCategory::InvalidArgument, "needs the receivers' normals");
}

TEST(SdfInput, RejectsBadShapes)
{
    Fixture f;
    const Image two(3, 1, 2), small_normals(2, 1, 3), empty;
    expect_error([&] { sdf_shadows(f.ctx, f.analytic, two, &f.normals, f.options); }, ErrorCategory::InvalidArgument,
                 "positions must have 3 channels");
    expect_error([&] { sdf_shadows(f.ctx, f.analytic, empty, &f.normals, f.options); },
                 ErrorCategory::InvalidArgument, "empty");
    expect_error([&] { sdf_shadows(f.ctx, f.analytic, f.positions, &small_normals, f.options); },
                 ErrorCategory::InvalidArgument, "normals must have 3 channels and the positions' size (3x1)");
    Image out(3, 1, 3);
    expect_error([&] { sdf_shadows(f.ctx, f.analytic, f.positions, &f.normals, f.options, out); },
                 ErrorCategory::InvalidArgument, "1 or 2 channels");
    expect_error([&] { sdf_shadows(f.ctx, DistanceGrid(), f.positions, &f.normals, f.options); },
                 ErrorCategory::InvalidArgument, "grid is empty");
}

TEST(SdfInput, RejectsBadGrids)
{
    const SdfVec3 o{0, 0, 0};
    for (double voxel : {0.0, -0.1, double(NAN), double(INFINITY), 1e-50})
        expect_error([&] { DistanceGrid(4, 4, 4, o, voxel); }, ErrorCategory::InvalidArgument, "voxel size");
    expect_error([&] { DistanceGrid(1, 4, 4, o, 0.1); }, ErrorCategory::InvalidArgument, "at least 2 nodes");
    expect_error([&] { DistanceGrid(4, 4, 4, {0, NAN, 0}, 0.1); }, ErrorCategory::InvalidArgument, "origin");
    expect_error([&] { DistanceGrid(2048, 2048, 1024, o, 0.1); }, ErrorCategory::InvalidArgument, "2^31");

    Fixture f;
    f.grid.at(3, 2, 1) = NAN;
    expect_error([&] { sdf_shadows(f.ctx, f.grid, f.positions, &f.normals, f.options); }, ErrorCategory::InvalidData,
                 "node (3, 2, 1) is nan");
    f.grid.at(3, 2, 1) = 0.0f;
    f.grid.at(0, 0, 2) = -INFINITY;
    expect_error([&] { sdf_shadows(f.ctx, f.grid, f.positions, &f.normals, f.options); }, ErrorCategory::InvalidData,
                 "node (0, 0, 2) is -inf");
}

TEST(SdfInput, RejectsBadPrimitives)
{
    expect_error([] { AnalyticScene({SdfPlane{}, SdfSphere{{0, 0, 0}, 0.0}}); }, ErrorCategory::InvalidArgument,
                 "primitives[1].radius");
    expect_error([] { AnalyticScene({SdfPlane{{0, 0, 0}, {0, 0, 0}}}); }, ErrorCategory::InvalidArgument,
                 "primitives[0].normal");
    expect_error([] { AnalyticScene({SdfBox{{0, NAN, 0}}}); }, ErrorCategory::InvalidArgument,
                 "primitives[0].center");
    expect_error([] { AnalyticScene({SdfSphere{}, SdfBox{{0, 0, 0}, {0.5, -0.5, 0.5}}}); },
                 ErrorCategory::InvalidArgument, "primitives[1].half_size");
    expect_error([] { AnalyticScene({SdfCapsule{{0, 0, 0}, {0, 1, 0}, -0.5}}); }, ErrorCategory::InvalidArgument,
                 "primitives[0].radius");
    // The kernel inverts a box's rotation by its transpose: sheared, scaled
    // or non-finite axes would give wrong distances, so they are refused.
    const SdfVec3 half{0.5, 0.5, 0.5};
    expect_error([&] { AnalyticScene({SdfBox{{}, half, {1, 0, 0}, {0, 2, 0}, {0, 0, 1}}}); },
                 ErrorCategory::InvalidArgument, "primitives[0].axis_x, axis_y, axis_z: must be orthonormal");
    expect_error([&] { AnalyticScene({SdfBox{{}, half, {1, 0, 0}, {0.6, 0.8, 0}, {0, 0, 1}}}); },
                 ErrorCategory::InvalidArgument, "must be orthonormal");
    expect_error([&] { AnalyticScene({SdfBox{{}, half, {1, 0, 0}, {0, 1, 0}, {0, 0, NAN}}}); },
                 ErrorCategory::InvalidArgument, "primitives[0].axis_z: must be finite");
    // Axes from a float matrix (rounded to ~1e-7) are accepted.
    const double c = double(float(std::sqrt(0.5)));
    EXPECT_EQ(AnalyticScene({SdfBox{{}, half, {c, c, 0}, {-c, c, 0}, {0, 0, 1}}}).boxes(), 1);
}

// A reference box becomes an SdfBox with half its sides and the columns of
// its Euler rotation as axes; the other kinds copy their fields.
TEST(SdfInput, ConvertsReferencePrimitives)
{
    using namespace reference;
    const SdfBox b = std::get<SdfBox>(to_sdf(Box{{1, 2, 3}, {2, 4, 6}, {0, 90, 0}}));
    EXPECT_EQ(b.center, (SdfVec3{1, 2, 3}));
    EXPECT_EQ(b.half_size, (SdfVec3{1, 2, 3}));
    const Rotation r = rotation_from_euler_degrees({0, 90, 0});
    EXPECT_EQ(b.axis_x, to_sdf(r.x));
    EXPECT_EQ(b.axis_y, to_sdf(r.y));
    EXPECT_EQ(b.axis_z, to_sdf(r.z));
    const SdfCapsule c = std::get<SdfCapsule>(to_sdf(Capsule{{1, 2, 3}, {4, 5, 6}, 0.25}));
    EXPECT_EQ(c.a, (SdfVec3{1, 2, 3}));
    EXPECT_EQ(c.b, (SdfVec3{4, 5, 6}));
    EXPECT_EQ(c.radius, 0.25);
    EXPECT_EQ(std::get<SdfPlane>(to_sdf(Plane{{0, 1, 0}, {0, 2, 0}})).normal, (SdfVec3{0, 2, 0}));
    EXPECT_EQ(std::get<SdfSphere>(to_sdf(Sphere{{0, 1, 0}, 3})).radius, 3.0);
}

// Records grouped by kind in the order plane, sphere, box, capsule, with the
// layout of kernels/params.h.
TEST(SdfInput, PacksPrimitivesByKind)
{
    using namespace reference;
    const AnalyticScene s = analytic_scene({Capsule{{1, 2, 3}, {1, 4, 3}, 0.5}, Sphere{{0, 1, 0}, 2},
                                            Plane{{0, 2, 0}, {0, 3, 0}}, Box{{1, 1, 1}, {2, 4, 6}, {0, 90, 0}}});
    ASSERT_EQ(s.planes(), 1);
    ASSERT_EQ(s.spheres(), 1);
    ASSERT_EQ(s.boxes(), 1);
    ASSERT_EQ(s.capsules(), 1);
    const std::vector<float>& r = s.records();
    ASSERT_EQ(r.size(), 4u + 4u + 16u + 8u);
    const std::vector<float> plane = {0, 1, 0, 2}, sphere = {0, 1, 0, 2}, capsule = {1, 2, 3, 0, 2, 0, 0.25f, 0.5f};
    for (int i = 0; i < 4; ++i) EXPECT_EQ(r[i], plane[i]) << i;
    for (int i = 0; i < 4; ++i) EXPECT_EQ(r[4 + i], sphere[i]) << i;
    const std::vector<float> box_head = {1, 1, 1, 1, 2, 3};
    for (int i = 0; i < 6; ++i) EXPECT_EQ(r[8 + i], box_head[i]) << i;
    // 90 degrees about y: the local x axis points along world -z.
    EXPECT_NEAR(r[14], 0.0f, 1e-7f);
    EXPECT_NEAR(r[16], -1.0f, 1e-7f);
    for (int i = 0; i < 8; ++i) EXPECT_EQ(r[24 + i], capsule[i]) << i;
}

TEST(SdfInput, BakedNodesHoldTheSceneDistance)
{
    const reference::Scene scene = reference::builtin_scene("contact");
    const reference::GridBox box = distance_grid_box(scene, 0.25);
    const DistanceGrid grid = bake_distance_grid(scene, box, 0.1);
    EXPECT_EQ(grid.origin().x, float(box.lo.x));
    EXPECT_GE(grid.upper().x, box.hi.x - 1e-6);
    EXPECT_LT(grid.upper().x, box.hi.x + grid.voxel_size());
    const reference::PreparedScene prepared(scene.primitives);
    for (int k = 0; k < grid.nz(); k += 3)
        for (int j = 0; j < grid.ny(); j += 2)
            for (int i = 0; i < grid.nx(); i += 5) {
                const Vec3 p = reference::from_sdf(grid.origin()) + Vec3{double(i), double(j), double(k)} * grid.voxel_size();
                ASSERT_EQ(grid.at(i, j, k), float(prepared.signed_distance(p))) << i << "," << j << "," << k;
            }
    // The box holds the bounded primitives with the margin: the sphere's top
    // (y = 2) plus 0.25.
    EXPECT_NEAR(box.hi.y, 2.25, 1e-9);
    expect_error([&] { bake_distance_grid(scene, box, 0.0); }, ErrorCategory::InvalidArgument, "voxel size");
    expect_error([&] { distance_grid_box(scene, -1.0); }, ErrorCategory::InvalidArgument, "margin");
}

// k = fit 2 D / W, D the distance to where the light's axis meets the ground.
TEST(SdfInput, HardnessFollowsTheLightsSize)
{
    EXPECT_DOUBLE_EQ(sdf_hardness(0.5, 10.0, 1.0), 40.0);
    EXPECT_DOUBLE_EQ(sdf_hardness(0.5, 10.0), kSdfHardnessFit * 40.0);
    const reference::Scene s = testing::sphere_over_plane();  // 1 m light 6 m above the ground
    EXPECT_NEAR(sdf_hardness(s, 1.0), 12.0, 1e-9);
    const reference::Scene contact = reference::builtin_scene("contact");
    const reference::LightProjection projection(contact);
    const double d = projection.depth_of(reference::reference_depths(contact).z_receiver);
    EXPECT_NEAR(sdf_hardness(contact, 1.0), 2.0 * d / 1.5, 1e-9);
    const SdfOptions o = sdf_options_for(contact, SdfEstimate::Improved);
    EXPECT_EQ(o.k, float(kSdfHardnessFit));
    EXPECT_EQ(o.light_width, 1.5f);  // so each receiver's k is sdf_hardness(1.5, its distance)
    EXPECT_EQ(o.estimate, SdfEstimate::Improved);
    // The inner-penumbra estimate (the default) spans the square light's mean breadth 4 W / pi.
    const SdfOptions inner = sdf_options_for(contact);
    EXPECT_EQ(inner.estimate, SdfEstimate::InnerPenumbra);
    EXPECT_FLOAT_EQ(inner.k, float(kSdfInnerHardnessFit * std::numbers::pi / 4));
    EXPECT_FALSE(o.light.directional);
    EXPECT_EQ(o.light.vector, reference::to_sdf(contact.light.center));
    expect_error([] { sdf_hardness(0.0, 1.0); }, ErrorCategory::InvalidArgument, "width");
}

// Steps 1 2 3 / 4 5 6. Strips of 2 along rows: (1,2) (3,pad) (4,5) (6,pad)
// cost 2 (2 + 3 + 5 + 6) = 32; 2 x 2 tiles: (1,2,4,5) (3,6,pad,pad) cost
// 4 (5 + 6) = 44; active 21 either way.
TEST(SdfInput, LaneUtilisationCountsWholeStrips)
{
    Image steps(3, 2, 2);
    for (int i = 0; i < 6; ++i) steps.at(1, i % 3, i / 3) = float(i + 1);
    const LaneUtilisation rows = lane_utilisation(steps, 1, 2);
    EXPECT_EQ(rows.active, 21.0);
    EXPECT_EQ(rows.total, 32.0);
    const LaneUtilisation tiles = lane_utilisation(steps, 1, 2, 2);
    EXPECT_EQ(tiles.total, 44.0);
    EXPECT_DOUBLE_EQ(tiles.ratio(), 21.0 / 44.0);
    EXPECT_EQ(lane_utilisation(steps, 1, 1).ratio(), 1.0);
    expect_error([&] { lane_utilisation(steps, 2, 1); }, ErrorCategory::InvalidArgument, "channel 2");
}

class GridFiles : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir_ = fs::temp_directory_path() / ("penumbra_sdf_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    // A grid file whose header fields are replaced, with n nodes of `value`.
    void write_raw(const std::string& name, const char* magic, int nx, int ny, int nz, float voxel, std::size_t nodes,
                   float value = 1.0f) const
    {
        std::ofstream out(path(name), std::ios::binary);
        out.write(magic, 8);
        for (int n : {nx, ny, nz}) out.write(reinterpret_cast<const char*>(&n), 4);
        const float origin[3] = {0, 0, 0};
        out.write(reinterpret_cast<const char*>(origin), 12);
        out.write(reinterpret_cast<const char*>(&voxel), 4);
        for (std::size_t i = 0; i < nodes; ++i) out.write(reinterpret_cast<const char*>(&value), 4);
    }

    fs::path dir_;
};

TEST_F(GridFiles, RoundTripIsExact)
{
    DistanceGrid grid(5, 3, 4, {-1.25, 0.5, 3.0}, 0.125);
    for (std::size_t i = 0; i < grid.size(); ++i) grid.data()[i] = float(i) * 0.37f - 3.0f;
    write_distance_grid(path("g.pnsdf"), grid);
    EXPECT_EQ(fs::file_size(path("g.pnsdf")), 36u + 4u * 60u);
    const DistanceGrid back = read_distance_grid(path("g.pnsdf"));
    EXPECT_EQ(back.nx(), 5);
    EXPECT_EQ(back.ny(), 3);
    EXPECT_EQ(back.nz(), 4);
    EXPECT_EQ(back.origin(), grid.origin());
    EXPECT_EQ(back.voxel_size(), 0.125);
    for (std::size_t i = 0; i < grid.size(); ++i) ASSERT_EQ(back.data()[i], grid.data()[i]) << i;
}

TEST_F(GridFiles, RejectsBadFiles)
{
    expect_error([&] { read_distance_grid(path("missing.pnsdf")); }, ErrorCategory::Io, "missing.pnsdf");
    std::ofstream(path("text.pnsdf")) << "not a grid at all, just some text";
    expect_error([&] { read_distance_grid(path("text.pnsdf")); }, ErrorCategory::Io, "PNSDFGR1");
    write_raw("short.pnsdf", "PNSDFGR1", 2, 2, 2, 0.1f, 7);
    expect_error([&] { read_distance_grid(path("short.pnsdf")); }, ErrorCategory::Io, "truncated");
    write_raw("flat.pnsdf", "PNSDFGR1", 2, 1, 2, 0.1f, 4);
    expect_error([&] { read_distance_grid(path("flat.pnsdf")); }, ErrorCategory::InvalidData, "ny is 1");
    write_raw("zero.pnsdf", "PNSDFGR1", 2, 2, 2, 0.0f, 8);
    expect_error([&] { read_distance_grid(path("zero.pnsdf")); }, ErrorCategory::InvalidData, "voxel size");
    write_raw("negative.pnsdf", "PNSDFGR1", 2, 2, 2, -0.5f, 8);
    expect_error([&] { read_distance_grid(path("negative.pnsdf")); }, ErrorCategory::InvalidData, "voxel size");
    write_raw("nan.pnsdf", "PNSDFGR1", 2, 2, 2, 0.1f, 8, NAN);
    expect_error([&] { read_distance_grid(path("nan.pnsdf")); }, ErrorCategory::InvalidData,
                 "nan.pnsdf: node (0, 0, 0) is nan");
}

TEST_F(GridFiles, FailedWriteLeavesTheTargetAlone)
{
    std::ofstream(path("keep.pnsdf")) << "previous";
    expect_error([&] { write_distance_grid(path("keep.pnsdf"), DistanceGrid()); }, ErrorCategory::InvalidArgument,
                 "empty");
    expect_error([&] { write_distance_grid(path("no/such/dir/g.pnsdf"), DistanceGrid(2, 2, 2, {}, 1.0)); },
                 ErrorCategory::Io, "g.pnsdf");
    std::ifstream in(path("keep.pnsdf"));
    std::string text;
    in >> text;
    EXPECT_EQ(text, "previous");
}

}  // namespace
}  // namespace penumbra
