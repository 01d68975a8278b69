// compress_visibility (Lokovic & Veach's error-bounded compression) against a
// brute-force dense evaluation: within the tolerance at every depth (at and
// between the vertices of both functions, on both sides of every step, and at
// random depths), monotone, in [0, 1], exact at the ends, output depths drawn
// from the input's, and vertex counts where the answer is known.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "penumbra/deep_shadow_map.h"
#include "penumbra/dsm_compression.h"
#include "penumbra/error.h"
#include "support/deep_functions.h"

namespace penumbra {
namespace {

using testing::brute_visibility;
using testing::Function;
using testing::random_function;

// Float rounding of the stored t (the band itself is exact in double).
constexpr double kRounding = 1e-6;

Function compressed(const Function& f, float eps)
{
    Function c;
    compress_visibility(f.z, f.t, eps, c.z, c.t);
    return c;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The depths at which the two functions are compared: every vertex of both,
// the midpoints of every input segment, and random depths over the range and
// beyond it.
std::vector<double> probe_depths(const Function& f, const Function& c, std::uint32_t seed)
{
    std::vector<double> d(f.z.begin(), f.z.end());
    d.insert(d.end(), c.z.begin(), c.z.end());
    for (std::size_t i = 0; i + 1 < f.z.size(); ++i) d.push_back(0.5 * (double(f.z[i]) + f.z[i + 1]));
    if (f.z.empty()) return d;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> over(double(f.z.front()) - 1.0, double(f.z.back()) + 1.0);
    for (int k = 0; k < 2000; ++k) d.push_back(over(rng));
    return d;
}

void expect_within_band(const Function& f, const Function& c, float eps, std::uint32_t seed = 1)
{
    double worst = 0.0;
    for (const double d : probe_depths(f, c, seed))
        for (const int side : {-1, +1})
            worst = std::max(worst, double(std::fabs(brute_visibility(c, d, side) - brute_visibility(f, d, side))));
    EXPECT_LE(worst, double(eps) + kRounding) << "eps " << eps;
}

void expect_valid_and_exact_at_ends(const Function& f, const Function& c)
{
    ASSERT_GE(c.z.size(), 2u);
    EXPECT_NO_THROW(require_visibility_function(c.z, c.t));  // sorted, monotone, in [0, 1], t_0 = 1
    EXPECT_TRUE(same_bits(c.z.front(), f.z.front()) && c.t.front() == 1.0f);
    EXPECT_TRUE(same_bits(c.z.back(), f.z.back()) && same_bits(c.t.back(), f.t.back()));
    EXPECT_LE(c.z.size(), f.z.size());
    // Every output depth is an input depth, bit for bit: no surface moves.
    for (const float z : c.z)
        EXPECT_TRUE(std::any_of(f.z.begin(), f.z.end(), [&](float w) { return same_bits(w, z); })) << z;
}

TEST(DsmCompression, DefaultToleranceIsAQuarterOverRootN)
{
    EXPECT_FLOAT_EQ(dsm_default_tolerance(1), 0.25f);
    EXPECT_FLOAT_EQ(dsm_default_tolerance(16), 0.0625f);
    EXPECT_FLOAT_EQ(dsm_default_tolerance(256), 0.015625f);
    EXPECT_THROW(dsm_default_tolerance(0), Error);
}

TEST(DsmCompression, AStraightLineBecomesTwoVertices)
{
    Function line;
    for (int i = 0; i <= 1000; ++i) line.z.push_back(2.0f + 0.01f * float(i)), line.t.push_back(1.0f - 0.0009f * float(i));
    const Function c = compressed(line, 0.01f);
    EXPECT_EQ(c.z.size(), 2u);
    expect_valid_and_exact_at_ends(line, c);
    expect_within_band(line, c, 0.01f);
}

TEST(DsmCompression, ANoisyLineWithinTheBandBecomesTwoVertices)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> noise(-0.004f, 0.004f);
    Function line;
    line.z.push_back(0.0f), line.t.push_back(1.0f);
    for (int i = 1; i < 500; ++i) {
        line.z.push_back(0.02f * float(i));
        line.t.push_back(std::min(line.t.back(), std::clamp(1.0f - 0.0015f * float(i) + noise(rng), 0.0f, 1.0f)));
    }
    line.z.push_back(10.0f), line.t.push_back(std::min(line.t.back(), 0.25f));
    const Function c = compressed(line, 0.01f);
    EXPECT_EQ(c.z.size(), 2u);
    expect_within_band(line, c, 0.01f);
}

// Surfaces at depths 1, 2, ..., steps, each dropping t by `drop`, with empty
// space between them and after the last.
Function staircase(int steps, float drop, bool tail)
{
    Function stairs;
    stairs.z.push_back(1.0f), stairs.t.push_back(1.0f);
    float t = 1.0f;
    for (int s = 1; s <= steps; ++s) {
        stairs.z.push_back(float(s)), stairs.t.push_back(t);
        t -= drop;
        stairs.z.push_back(float(s)), stairs.t.push_back(t);
    }
    if (tail) stairs.z.push_back(float(steps + 1)), stairs.t.push_back(t);
    return stairs;
}

// Steps larger than 2 eps cannot be hidden in the band: each stays a step at
// its exact depth, dropping to the input's own value.
TEST(DsmCompression, AStaircaseOfLargeStepsKeepsEveryStep)
{
    const float eps = 0.05f;
    const Function stairs = staircase(6, 3.0f * eps, true);
    const Function c = compressed(stairs, eps);
    expect_valid_and_exact_at_ends(stairs, c);
    expect_within_band(stairs, c, eps);
    for (int s = 1; s <= 6; ++s) {
        const double before = brute_visibility(c, s, -1), after = brute_visibility(c, s, +1);
        EXPECT_GT(before - after, 0.15 - 2.0 * eps - kRounding) << "step " << s;
        EXPECT_FLOAT_EQ(float(after), float(brute_visibility(stairs, s, +1))) << "step " << s;
    }
}

// Flat stretches stay flat: two sheets (t 1 -> 0.6 at depth 1, -> 0.3 at
// depth 2) sampled densely between them, as a generator's union of sample
// depths gives them. The value just before the second step is the input's
// own 0.6, not eps/2 lower (the middle of the slope range ended there).
TEST(DsmCompression, FlatStretchesStayFlat)
{
    const float eps = 0.0625f;  // 0.25 / sqrt(16)
    Function f{{0.5f, 1.0f, 1.0f}, {1.0f, 1.0f, 0.6f}};
    for (int i = 1; i < 40; ++i) {
        f.z.push_back(1.0f + float(i) / 40.0f);
        f.t.push_back(0.6f);
    }
    f.z.insert(f.z.end(), {2.0f, 2.0f, 3.0f});
    f.t.insert(f.t.end(), {0.6f, 0.3f, 0.3f});
    const Function c = compressed(f, eps);
    expect_valid_and_exact_at_ends(f, c);
    expect_within_band(f, c, eps);
    for (double d : {1.0, 1.25, 1.5, 1.75, 2.0})
        EXPECT_NEAR(double(brute_visibility(c, d, d == 1.0 ? +1 : -1)), 0.6, 1e-6) << "at depth " << d;
}

// Steps of at most 2 eps may be smoothed into a slope: fewer vertices, same band.
TEST(DsmCompression, AStaircaseOfSmallStepsIsSmoothed)
{
    const float eps = 0.05f;
    const Function stairs = staircase(20, 0.8f * eps, false);
    const Function c = compressed(stairs, eps);
    EXPECT_LT(c.z.size(), stairs.z.size() / 4);
    expect_valid_and_exact_at_ends(stairs, c);
    expect_within_band(stairs, c, eps);
}

TEST(DsmCompression, ZeroToleranceKeepsTheFunction)
{
    for (std::uint32_t seed = 1; seed <= 20; ++seed) {
        const Function f = random_function(seed, 40);
        const Function c = compressed(f, 0.0f);
        expect_valid_and_exact_at_ends(f, c);
        expect_within_band(f, c, 0.0f, seed);
    }
}

TEST(DsmCompression, RandomFunctionsStayInTheBand)
{
    for (const float eps : {0.001f, 0.01f, 0.0625f, 0.25f})
        for (std::uint32_t seed = 1; seed <= 60; ++seed) {
            const Function f = random_function(seed * 7919u, 5 + int(seed % 13) * 20, 0.5f, 20.0f, 0.1f);
            const Function c = compressed(f, eps);
            SCOPED_TRACE(::testing::Message() << "seed " << seed << " eps " << eps << " n " << f.z.size());
            expect_valid_and_exact_at_ends(f, c);
            expect_within_band(f, c, eps, seed);
        }
}

TEST(DsmCompression, SmoothFogCompressesWell)
{
    // exp(-z) sampled at 2000 vertices: the band of 0.01 needs few segments.
    Function fog;
    for (int i = 0; i < 2000; ++i) {
        const float z = 0.005f * float(i);
        fog.z.push_back(z), fog.t.push_back(i == 0 ? 1.0f : std::min(fog.t.back(), float(std::exp(-double(z)))));
    }
    const Function c = compressed(fog, 0.01f);
    EXPECT_LT(c.z.size(), 20u);
    expect_valid_and_exact_at_ends(fog, c);
    expect_within_band(fog, c, 0.01f);
}

TEST(DsmCompression, FullyOpaqueAtTheFirstDepth)
{
    const Function f{{3.0f, 3.0f, 8.0f}, {1.0f, 0.0f, 0.0f}};
    const Function c = compressed(f, 0.1f);
    EXPECT_EQ(c.z, (std::vector<float>{3.0f, 3.0f, 8.0f}));
    EXPECT_EQ(c.t, (std::vector<float>{1.0f, 0.0f, 0.0f}));
}

TEST(DsmCompression, AllAtOneDepthAndFullyLitKeepsTwoVertices)
{
    for (const Function& f : {Function{{5.0f, 5.0f}, {1.0f, 1.0f}}, Function{{5.0f, 5.0f, 5.0f}, {1.0f, 1.0f, 1.0f}}}) {
        const Function c = compressed(f, 0.1f);
        EXPECT_EQ(c.z, (std::vector<float>{5.0f, 5.0f}));
        EXPECT_EQ(c.t, (std::vector<float>{1.0f, 1.0f}));
    }
}

TEST(DsmCompression, EmptyFunctionStaysEmpty)
{
    const Function c = compressed({}, 0.1f);
    EXPECT_TRUE(c.z.empty() && c.t.empty());
}

TEST(DsmCompression, RefusesBadToleranceAndBadFunctions)
{
    const Function f{{0.0f, 1.0f}, {1.0f, 0.5f}};
    Function c;
    for (const float eps : {-0.1f, NAN, INFINITY})
        EXPECT_THROW(compress_visibility(f.z, f.t, eps, c.z, c.t), Error);
    const Function rising{{0.0f, 1.0f, 2.0f}, {1.0f, 0.5f, 0.6f}};
    try {
        compress_visibility(rising.z, rising.t, 0.1f, c.z, c.t);
        ADD_FAILURE() << "a rising function was compressed";
    } catch (const Error& e) {
        EXPECT_EQ(e.category(), ErrorCategory::InvalidData);
        EXPECT_NE(e.message().find("vertex 2"), std::string::npos) << e.message();
    }
}

TEST(DsmCompression, AMapCompressesPixelByPixel)
{
    DeepShadowMapBuilder builder(7, 5);
    std::vector<Function> pixels;
    for (std::uint32_t p = 0; p < 35; ++p) {
        pixels.push_back(p % 6 == 0 ? Function{} : random_function(100 + p, 30));
        builder.add_pixel(pixels.back().z, pixels.back().t);
    }
    const DeepShadowMap map = builder.build();
    const DeepShadowMap small = compress_deep_shadow_map(map, 0.05f);
    EXPECT_LT(small.vertex_count(), map.vertex_count());
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x) {
            const Function c = compressed(pixels[std::size_t(y * 7 + x)], 0.05f);
            EXPECT_TRUE(std::equal(c.z.begin(), c.z.end(), small.depths(x, y).begin(), small.depths(x, y).end()));
            EXPECT_TRUE(std::equal(c.t.begin(), c.t.end(), small.transmittances(x, y).begin(),
                                   small.transmittances(x, y).end()));
        }
}

}  // namespace
}  // namespace penumbra
