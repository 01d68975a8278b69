// Ambient volumes (kernels/ambient_volumes.h, host/src/ambient_volumes.cpp) on
// every backend: inside 1, outside 0, the falloff against the float64 formula
// (tests/support/ambient_cases.h) for rotated and scaled spheres and boxes with
// scale bias and delayed falloff, the max rule for overlaps, the volumes'
// blend inside the SH kernel, odd sizes, and bad volumes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "penumbra/ambient.h"
#include "penumbra/error.h"
#include "support/ambient_cases.h"
#include "support/backends.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;
using Shape = AmbientVolume::Shape;

class AmbientVolumesTest : public ::testing::TestWithParam<std::string> {};

// A w x h grid of positions over [-2, 2] x [-1.5, 1.5] at height z.
Image positions(int w, int h, double z)
{
    Image p(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            p.at(0, x, y) = float(-2.0 + 4.0 * (x + 0.5) / w);
            p.at(1, x, y) = float(-1.5 + 3.0 * (y + 0.5) / h);
            p.at(2, x, y) = float(z);
        }
    return p;
}

AmbientVolume rotated(Shape shape, double angle)
{
    AmbientVolume v;
    v.shape = shape;
    v.center = {0.2, -0.1, 0.05};
    v.half_size = {1.3, 0.7, 0.9};
    v.axis_x = {std::cos(angle), std::sin(angle), 0};
    v.axis_y = {-std::sin(angle), std::cos(angle), 0};
    v.scale_bias = 1.05;
    v.falloff_delay = 0.5;
    return v;
}

void expect_factor(Context& ctx, const std::vector<AmbientVolume>& volumes, const Image& p, double tolerance)
{
    const Image f = ambient_volume_factor(ctx, p, AmbientVolumes(volumes));
    int inside = 0, outside = 0, between = 0;
    for (int y = 0; y < p.height(); ++y)
        for (int x = 0; x < p.width(); ++x) {
            const double e = testing::expected_factor(volumes, testing::normal_at(p, x, y));
            ASSERT_NEAR(f.at(0, x, y), e, tolerance) << "pixel " << x << "," << y;
            inside += e == 1.0;
            outside += e == 0.0;
            between += e > 0.0 && e < 1.0;
        }
    const bool plateau = std::any_of(volumes.begin(), volumes.end(), [](const AmbientVolume& v) { return v.falloff_delay > 0; });
    if (plateau) {
        EXPECT_GT(inside, 0) << "a delayed falloff keeps f = 1 out to the delay";
    }
    EXPECT_GT(outside, 0);
    EXPECT_GT(between, 0) << "the falloff must be crossed";
}

PN_BACKEND_TEST(AmbientVolumesTest, FalloffAgainstTheFormula)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (Shape shape : {Shape::Sphere, Shape::Box})
        for (double delay : {0.0, 0.5, 0.85}) {
            AmbientVolume v = rotated(shape, 0.6);
            v.falloff_delay = delay;
            for (double z : {0.0, 0.5}) expect_factor(ctx, {v}, positions(61, 47, z), 2e-6);
        }
}

// Inside 1 (the centre, and out to the delay), outside 0, and the box's
// faces at 0 with no bias (the cube-to-sphere map takes them onto the sphere).
PN_BACKEND_TEST(AmbientVolumesTest, InsideOneOutsideZero)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    AmbientVolume box = rotated(Shape::Box, 0.0);
    box.center = {0, 0, 0};
    box.scale_bias = 1.0;
    box.falloff_delay = 0.0;
    Image p(5, 1, 3);
    const float points[5][3] = {{0, 0, 0}, {1.3f, 0, 0}, {1.3f, 0.7f, 0.9f}, {1.31f, 0, 0}, {5, 5, 5}};
    for (int i = 0; i < 5; ++i)
        for (int c = 0; c < 3; ++c) p.at(c, i, 0) = points[i][c];
    const Image f = ambient_volume_factor(ctx, p, AmbientVolumes({box}));
    EXPECT_EQ(f.at(0, 0, 0), 1.0f);
    EXPECT_NEAR(f.at(0, 1, 0), 0.0f, 1e-6) << "a face centre";
    EXPECT_NEAR(f.at(0, 2, 0), 0.0f, 1e-6) << "a corner";
    EXPECT_EQ(f.at(0, 3, 0), 0.0f);
    EXPECT_EQ(f.at(0, 4, 0), 0.0f);
    const Image none = ambient_volume_factor(ctx, p, AmbientVolumes());
    for (int i = 0; i < 5; ++i) EXPECT_EQ(none.at(0, i, 0), 0.0f) << "no volume: the light rig";
}

// Overlapping volumes take the larger factor (BlendOp MAX), in any order.
PN_BACKEND_TEST(AmbientVolumesTest, OverlapsTakeTheMaximum)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    AmbientVolume a = rotated(Shape::Sphere, 0.0), b = rotated(Shape::Box, 0.4);
    b.center = {1.0, 0.3, 0.0};
    const Image p = positions(37, 29, 0.1);
    expect_factor(ctx, {a, b}, p, 2e-6);
    const Image ab = ambient_volume_factor(ctx, p, AmbientVolumes({a, b}));
    const Image ba = ambient_volume_factor(ctx, p, AmbientVolumes({b, a}));
    const Image fa = ambient_volume_factor(ctx, p, AmbientVolumes({a}));
    const Image fb = ambient_volume_factor(ctx, p, AmbientVolumes({b}));
    int both = 0;
    for (int y = 0; y < p.height(); ++y)
        for (int x = 0; x < p.width(); ++x) {
            EXPECT_EQ(ab.at(0, x, y), ba.at(0, x, y));
            EXPECT_EQ(ab.at(0, x, y), std::max(fa.at(0, x, y), fb.at(0, x, y)));
            both += fa.at(0, x, y) > 0 && fb.at(0, x, y) > 0;
        }
    EXPECT_GT(both, 0) << "the volumes must overlap";
}

// The SH kernel's volume blend is (1 - f) light + f dark with f the factor,
// on odd sizes.
PN_BACKEND_TEST(AmbientVolumesTest, VolumesBlendTheRigsInTheShKernel)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const std::vector<testing::NamedRig> rigs = testing::error_table_rigs();
    AmbientLighting l;
    l.light = project_rig(rigs[1].rig);
    l.dark = project_rig(rigs[2].rig);
    l.volumes = AmbientVolumes({rotated(Shape::Box, 0.3)});
    for (auto [w, h] : {std::pair{1, 1}, {7, 3}, {15, 3}, {16, 3}, {17, 3}, {61, 9}}) {
        const Image n = testing::sphere_of_normals(w * h, w);
        const Image p = positions(w, h, 0.2);
        Image rx(w, h, 6);
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    rx.at(c, x, y) = n.at(c, x, y);
                    rx.at(3 + c, x, y) = p.at(c, x, y);
                }
        const Image e = ambient_irradiance(ctx, rx, l);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double f = testing::expected_factor(l.volumes.count() ? rotated(Shape::Box, 0.3) : AmbientVolume{},
                                                          testing::normal_at(p, x, y));
                const std::array<double, 3> a = evaluate_irradiance(*l.dark, testing::normal_at(n, x, y));
                const std::array<double, 3> b = evaluate_irradiance(l.light, testing::normal_at(n, x, y));
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(e.at(c, x, y), (1 - f) * b[c] + f * a[c], 5e-6) << w << "x" << h << " at " << x << "," << y;
            }
    }
}

TEST(AmbientVolumesInput, BadVolumesNameTheField)
{
    AmbientVolume v;
    v.half_size = {1, 0, 1};
    try {
        AmbientVolumes({AmbientVolume{}, v});
        ADD_FAILURE() << "a zero scale must be refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("volumes[1].half_size"), std::string::npos) << e.what();
    }
    v = {};
    v.falloff_delay = 1.0;
    EXPECT_THROW(AmbientVolumes({v}), Error);
    v = {};
    v.axis_y = {1, 0, 0};
    EXPECT_THROW(AmbientVolumes({v}), Error);
    v = {};
    v.center.x = std::nan("");
    EXPECT_THROW(AmbientVolumes({v}), Error);
}

INSTANTIATE_TEST_SUITE_P(Backends, AmbientVolumesTest, ::testing::ValuesIn(backend_names()), backend_test_name);

}  // namespace
}  // namespace penumbra
