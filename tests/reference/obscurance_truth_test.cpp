// The AO and volumetric-obscurance truths (reference/obscurance_truth.h):
// closed forms on a plane and in a right-angle corner, convergence when the
// samples double, bad options.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/error.h"
#include "penumbra/reference/metrics.h"
#include "penumbra/reference/obscurance_truth.h"
#include "support/errors.h"

namespace penumbra::reference {
namespace {

// Receivers at the given points, normal +y.
Receivers receivers_at(const std::vector<Vec3>& points)
{
    Receivers r = Receivers::allocate(int(points.size()), 1);
    for (int i = 0; i < int(points.size()); ++i) {
        r.world_position.at(0, i, 0) = float(points[std::size_t(i)].x);
        r.world_position.at(1, i, 0) = float(points[std::size_t(i)].y);
        r.world_position.at(2, i, 0) = float(points[std::size_t(i)].z);
        r.normal.at(1, i, 0) = 1;
        r.hit.at(0, i, 0) = 1;
        r.mask.at(0, i, 0) = 1;
    }
    return r;
}

// The ground y <= 0 and, with `wall`, the solid x >= 0 too.
Scene ground(bool wall)
{
    Scene s = builtin_scene("contact");
    s.primitives = {Plane{{0, 0, 0}, {0, 1, 0}}};
    if (wall) s.primitives.push_back(Plane{{0, 0, 0}, {-1, 0, 0}});
    return s;
}

TEST(ObscuranceTruth, APlaneIsOpenAndHalfObscured)
{
    const Receivers rx = receivers_at({{0, 0, 0}, {3, 0, -2}, {-7, 0, 1}});
    const Image ao = ambient_occlusion_truth(ground(false), rx, {0.5, 16});
    const Image vo = volumetric_obscurance_truth(ground(false), rx, {0.5, 24});
    for (int x = 0; x < 3; ++x) {
        EXPECT_EQ(ao.at(0, x, 0), 1.0f);
        EXPECT_NEAR(vo.at(0, x, 0), 0.5, 2e-3);
    }
}

// At the corner's edge the wall takes half the hemisphere of the ground's
// normal, which cosine weighting splits evenly: AO 1/2; the free space is a
// quarter of the ball: VO 3/4.
TEST(ObscuranceTruth, ACornerHalvesTheHemisphereAndLeavesAQuarterOfTheBall)
{
    const Receivers rx = receivers_at({{-1e-5, 0, 0}, {-1e-5, 0, 4}});
    const Image ao = ambient_occlusion_truth(ground(true), rx, {0.5, 64});
    const Image vo = volumetric_obscurance_truth(ground(true), rx, {0.5, 32});
    for (int x = 0; x < 2; ++x) {
        EXPECT_NEAR(ao.at(0, x, 0), 0.5, 2e-3);
        EXPECT_NEAR(vo.at(0, x, 0), 0.75, 2e-3);
    }
    // Far from the wall (beyond R) the corner is a plane again.
    const Image far = ambient_occlusion_truth(ground(true), receivers_at({{-0.6, 0, 0}}), {0.5, 8});
    EXPECT_EQ(far.at(0, 0, 0), 1.0f);
}

// n against about twice the samples (another seed) on each scene's view at
// 24 x 18: AO 24^2 against 34^2 rays, VO 12^3 against 15^3 points. The RMSE
// between the two stays under the stated bounds; measured (2026-12-03): AO
// 0.0004-0.0030 (the fence's slats the most), VO 0.0024-0.0030.
TEST(ObscuranceTruth, ConvergesWhenTheSamplesDouble)
{
    for (const std::string& name : builtin_scene_names()) {
        const Scene scene = builtin_scene(name);
        const Receivers rx = render_receivers(scene, 24, 18);
        const Image ao = ambient_occlusion_truth(scene, rx, {0.5, 24});
        const Image ao2 = ambient_occlusion_truth(scene, rx, {0.5, 34, 99});
        const Image vo = volumetric_obscurance_truth(scene, rx, {0.5, 12});
        const Image vo2 = volumetric_obscurance_truth(scene, rx, {0.5, 15, 99});
        const double ao_change = rmse(ao, ao2, &rx.hit), vo_change = rmse(vo, vo2, &rx.hit);
        EXPECT_LT(ao_change, 5e-3) << name;
        EXPECT_LT(vo_change, 4e-3) << name;
        EXPECT_GT(ao_change + vo_change, 0) << name;
        std::cout << name << ": AO change " << ao_change << ", VO change " << vo_change << "\n";
    }
}

TEST(ObscuranceTruth, BadOptionsAreTypedErrors)
{
    const Receivers rx = receivers_at({{0, 0, 0}});
    using testing::expect_error;
    expect_error([&] { ambient_occlusion_truth(ground(false), rx, {0.0, 4}); }, ErrorCategory::InvalidArgument,
                 "ambient_occlusion_truth", {"radius"});
    expect_error([&] { volumetric_obscurance_truth(ground(false), rx, {0.5, 129}); },
                 ErrorCategory::InvalidArgument, "volumetric_obscurance_truth", {"strata", "128"});
}

}  // namespace
}  // namespace penumbra::reference
