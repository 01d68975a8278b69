// Ground truth: closed-form cases, convergence, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/metrics.h"

namespace penumbra::reference {
namespace {

// Receivers on the ground (y = 0, normal +y) at the given x positions, z = 0.
Receivers ground_receivers(const std::vector<double>& xs)
{
    Receivers r = Receivers::allocate(int(xs.size()), 1);
    for (int i = 0; i < int(xs.size()); ++i) {
        r.world_position.at(0, i, 0) = float(xs[i]);
        r.normal.at(1, i, 0) = 1;
        r.hit.at(0, i, 0) = 1;
        r.mask.at(0, i, 0) = 1;
    }
    return r;
}

// Pixel (x, 0) of a 3-channel image set to v.
void store3(Image& image, int x, Vec3 v)
{
    image.at(0, x, 0) = float(v.x);
    image.at(1, x, 0) = float(v.y);
    image.at(2, x, 0) = float(v.z);
}

// A light of side `light_width` at height `light_height` looking straight
// down (s = +x), over `occluders` and the ground.
Scene overhead(double light_height, double light_width, std::vector<Primitive> occluders)
{
    Scene scene;
    scene.primitives = std::move(occluders);
    scene.primitives.push_back(Plane{{0, 0, 0}, {0, 1, 0}});
    scene.light.center = {0, light_height, 0};
    scene.light.normal = {0, -1, 0};
    scene.light.width = scene.light.height = light_width;
    return scene;
}

TEST(ReferenceGroundTruth, HalfPlaneEdgeUnderARectangleIsALinearRamp)
{
    // Light: 1 m square at height H = 4. Occluder: the half-plane x < 0 at
    // height h = 1 (a 1 um thick slab reaching 100 m out). A ground point at x
    // sees the light point x_L past the edge when x + (x_L - x) h / H >= 0, so
    // the visible fraction is the ramp
    //   V(x) = clamp(1/2 + x (H - h) / (h W), 0, 1),
    // 2/6 m wide: W h / (H - h), the PCSS penumbra width.
    const double H = 4, h = 1, W = 1;
    const Scene scene = overhead(H, W, {Box{{-50, h, 0}, {100, 1e-6, 100}, {}}});
    std::vector<double> xs;
    for (int i = 0; i <= 60; ++i) xs.push_back(-0.25 + 0.5 * i / 60);
    const int n = 32;
    const Image truth = ground_truth(scene, ground_receivers(xs), {n});
    double sum_abs = 0;
    for (int i = 0; i < int(xs.size()); ++i) {
        const double ramp = std::clamp(0.5 + xs[i] * (H - h) / (h * W), 0.0, 1.0);
        const double error = std::fabs(truth.at(0, i, 0) - ramp);
        // Visibility depends on x_L only: only the column of strata the edge
        // crosses can be wrong, n strata of weight 1/n^2 each, so |error| <= 1/n.
        EXPECT_LE(error, 1.0 / n) << "x = " << xs[i];
        sum_abs += error;
    }
    // On average the jitter does far better: expected |error| ~ 0.4 / n^1.5 in the ramp.
    EXPECT_LT(sum_abs / xs.size(), 2e-3);
}

TEST(ReferenceGroundTruth, SphereOnTheAxisOfADiskLight)
{
    // A receiver on the axis of a disk light (radius R, height H) under a
    // sphere (radius r, centre at height c) sees the sphere as a cone of
    // half-angle asin(r / c); it cuts the light's plane in a disk of radius
    // H tan(asin(r / c)) = H r / sqrt(c^2 - r^2), so V = 1 - (that / R)^2.
    const double H = 5, R = 1, r = 0.3, c = 2;
    Scene scene = overhead(H, 2 * R, {Sphere{{0, c, 0}, r}});
    scene.light.shape = LightShape::Disk;
    const double hidden = H * r / std::sqrt(c * c - r * r);
    const double expected = 1 - (hidden / R) * (hidden / R);
    const int n = 128;
    const Image truth = ground_truth(scene, ground_receivers({0}), {n});
    // The concentric map sends the circle of radius rho = hidden / R to the
    // square ring max(|x|, |y|) = rho, which crosses 4 rho n strata: a standard
    // error of about sqrt(4 rho n / 4) / n^2 = 5e-4 here; the bound is 4 of those.
    EXPECT_NEAR(truth.at(0, 0, 0), expected, 2e-3);
}

TEST(ReferenceGroundTruth, TheReceiversOwnSurfaceIsExactAtASpheresTerminator)
{
    // Points on a small sphere (radius r = 0.01, centre at height 1) whose
    // tangent plane cuts the 1 m square light at height H = 4: nothing else
    // blocks, so the light reaching P is the part of the light above P's
    // tangent plane, the light's x beyond x0 = P.x - (H - P.y) tan(a) for the
    // normal n = (cos a, sin a, 0): V = clamp(1/2 - x0, 0, 1), a ramp across
    // the light's x as the half-plane ramp above. With the receiver's surface
    // named (ground_truth.h) the truth meets it to the strata's 1/n; lifted
    // by kNormalOffset instead, rays up to sqrt(2 h / r) = 0.02 rad below the
    // tangent plane pass beside the sphere and light about 6% more of it.
    const double H = 4, r = 0.01;
    const Vec3 centre{0, 1, 0};
    const Scene scene = overhead(H, 1, {Sphere{centre, r}});
    std::vector<double> angles;
    for (int i = 0; i <= 24; ++i) angles.push_back((-6.0 + 0.5 * i) * std::acos(-1.0) / 180);
    Receivers named = Receivers::allocate(int(angles.size()), 1);
    for (int i = 0; i < int(angles.size()); ++i) {
        const Vec3 n{std::cos(angles[std::size_t(i)]), std::sin(angles[std::size_t(i)]), 0};
        store3(named.world_position, i, centre + n * r);
        store3(named.normal, i, n);
        named.hit.at(0, i, 0) = named.mask.at(0, i, 0) = 1;
        named.surface.at(0, i, 0) = 0;  // scene_surfaces: the sphere, then the ground
    }
    Receivers lifted = named, foreign = named;
    lifted.surface.fill(0, -1.0f);
    foreign.surface.fill(0, 7.0f);  // no such surface: the lift, as without an id
    const int n = 64;
    const Image exact = ground_truth(scene, named, {n}), lift = ground_truth(scene, lifted, {n});
    const Image unknown = ground_truth(scene, foreign, {n});
    double exact_sum = 0, lift_sum = 0;
    for (int i = 0; i < int(angles.size()); ++i) {
        const double a = angles[std::size_t(i)];
        const double x0 = r * std::cos(a) - (H - (centre.y + r * std::sin(a))) * std::tan(a);
        const double expected = std::clamp(0.5 - x0, 0.0, 1.0);
        EXPECT_LE(std::fabs(exact.at(0, i, 0) - expected), 1.0 / n) << "angle " << a;
        EXPECT_EQ(unknown.at(0, i, 0), lift.at(0, i, 0)) << "angle " << a;
        exact_sum += exact.at(0, i, 0) - expected;
        lift_sum += lift.at(0, i, 0) - expected;
    }
    EXPECT_LT(std::fabs(exact_sum) / double(angles.size()), 2e-3);
    EXPECT_GT(lift_sum / double(angles.size()), 0.03);  // what the lift gets wrong, and this test would catch
}

// n x n strata against round(n sqrt 2)^2 (2.0x the samples, another seed) on
// 24 x 18 receivers: the RMSE between the two stays under 1e-3.
void expect_converged(const Scene& scene, int n)
{
    const Receivers receivers = render_receivers(scene, 24, 18);
    const int doubled = int(std::lround(n * std::sqrt(2.0)));
    const Image coarse = ground_truth(scene, receivers, {n});
    const Image fine = ground_truth(scene, receivers, {doubled, 12345});
    const double change = reference::rmse(coarse, fine, &receivers.mask);
    EXPECT_LT(change, 1e-3) << scene.name << ": " << n << " against " << doubled;
    EXPECT_GT(change, 0) << scene.name;  // two different estimates, not one computed twice
}

TEST(ReferenceGroundTruth, ConvergesWhenTheSamplesDouble)
{
    // n x n strata against round(n sqrt 2)^2 (2.0x the samples, another seed)
    // on 24 x 18 receivers: the RMSE between the two stays under 1e-3 with
    // these per-scene n (the error falls as n^-1.5, so the fence, whose whole
    // striped shadow is penumbra, needs the most). Measured: 0.0005-0.0007.
    const std::pair<const char*, int> strata[] = {
        {"contact", 32}, {"overlap", 40}, {"fence", 80}, {"grazing", 32}, {"large", 24}};
    for (const auto& [name, n] : strata) expect_converged(builtin_scene(name), n);
}

TEST(ReferenceGroundTruth, TransmittanceUnderAnAreaLightConvergesToo)
{
    // The deep scenes with their point light replaced by a 0.6 m square one:
    // the truth is then the mean transmittance over the light, sampled as
    // above, and must converge the same way. Measured: 0.00016 (fog), 0.00065
    // (layers). (Hair under an area light is penumbra wherever its shadow
    // falls, like the fence and more so: 0.006 at n = 32. Its built-in light
    // is a point, whose truth is exact.)
    const std::pair<const char*, int> strata[] = {{"fog", 24}, {"layers", 24}};
    for (const auto& [name, n] : strata) {
        Scene scene = builtin_scene(name);
        scene.light.shape = LightShape::Rectangle;
        scene.light.width = scene.light.height = 0.6;
        expect_converged(scene, n);
    }
}

TEST(ReferenceGroundTruth, DeterministicAndInRange)
{
    const Scene scene = builtin_scene("fence");
    const Receivers receivers = render_receivers(scene, 40, 30);
    const Image a = ground_truth(scene, receivers, {6, 7});
    const Image b = ground_truth(scene, receivers, {6, 7});
    const Image other_seed = ground_truth(scene, receivers, {6, 8});
    bool differs = false;
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
            ASSERT_EQ(a.at(0, x, y), b.at(0, x, y));
            ASSERT_TRUE(a.at(0, x, y) >= 0 && a.at(0, x, y) <= 1);
            differs = differs || a.at(0, x, y) != other_seed.at(0, x, y);
        }
    EXPECT_TRUE(differs);
}

TEST(ReferenceGroundTruth, EdgeCases)
{
    const Scene scene = overhead(4, 1, {});
    Receivers r = ground_receivers({0, 1, 2});
    r.hit.at(0, 1, 0) = 0;                   // sees nothing: lit by convention
    r.world_position.at(1, 2, 0) = 10;       // above the light: behind its plane
    const Image truth = ground_truth(scene, r, {4});
    EXPECT_EQ(truth.at(0, 0, 0), 1.0f);
    EXPECT_EQ(truth.at(0, 1, 0), 1.0f);
    EXPECT_EQ(truth.at(0, 2, 0), 0.0f);
    EXPECT_THROW(ground_truth(scene, r, {0}), Error);
    EXPECT_THROW(ground_truth(scene, Receivers{}, {4}), Error);
}

}  // namespace
}  // namespace penumbra::reference
