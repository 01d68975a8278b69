// The cross-bilateral filter (kernels/bilateral.h) on every backend: against
// a brute-force reference in double, a closed-form Gaussian blur on a flat
// guide, a constant mask, the halo test across a depth step, fully rejected
// neighbourhoods, odd sizes, and every backend against the scalar one.
// tests/kernels/bilateral_opencv_test.cpp compares with OpenCV; bad input and the
// `penumbra blur` command are in tests/host/bilateral_errors_test.cpp.
//
// Tolerances (masks in [0, 1]). The kernel differs from the reference in
// double by: its exponential, 2.9e-6 relative (bilateral_exp2_neg); the
// float difference d and exponent d^2 + e, relative 2^-23 each, which moves
// a weight 2^-s by s 2^-22 ln2 relative, under 3e-6 for the s <= 18 of
// weights above 2^-18 (smaller ones cannot move the result by 1e-5: their sum
// is below 25 2^-18 of the centre's); the float sums. A relative weight error
// e moves a normalised average by at most 2e times the spread of the values
// (1): kBilateralTolerance = 2e-5 covers 2 (3e-6 + 3e-6) plus the sums' rounding.
#include "penumbra/bilateral.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "support/bilateral_reference.h"
#include "support/backends.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;

constexpr double kBilateralTolerance = 2e-5;
// A weighted average of copies of one value m is m within the rounding of two
// float sums of up to 25 terms (24 2^-24 relative each) and a division.
constexpr double kAverageOfCopies = 3e-6;

class BilateralTest : public ::testing::TestWithParam<std::string> {};

// The option sets every test runs through: both range weights, absolute and
// relative differences, both windows, both schedules.
std::vector<BilateralOptions> option_sets(int radius)
{
    std::vector<BilateralOptions> sets;
    for (bool separable : {false, true})
        for (BilateralWindow window : {BilateralWindow::Square, BilateralWindow::Disk})
            for (BilateralRange range : {BilateralRange::Gaussian, BilateralRange::Threshold})
                for (bool relative : {false, true}) {
                    if (separable && window == BilateralWindow::Disk) continue;
                    BilateralOptions o;
                    o.radius = radius;
                    o.separable = separable;
                    o.window = window;
                    o.range = range;
                    o.relative = relative;
                    o.depth_sigma = relative ? 0.04f : 0.02f;
                    o.depth_threshold = relative ? 0.08f : 0.04f;
                    sets.push_back(o);
                }
    return sets;
}

std::string describe(const BilateralOptions& o)
{
    return std::string(o.separable ? "separable" : "full") +
           (o.window == BilateralWindow::Disk ? " disk" : " square") +
           (o.range == BilateralRange::Threshold ? " threshold" : " gaussian") +
           (o.relative ? " relative" : " absolute") + " r" + std::to_string(o.radius);
}

// ---- against the brute-force reference -----------------------------------

PN_BACKEND_TEST(BilateralTest, MatchesBruteForceReference)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    struct Case {
        int w, h, channels, radius;
    };
    const Case cases[] = {{37, 23, 1, 2}, {29, 17, 4, 1}, {33, 19, 3, 3}, {40, 12, 2, 0}};
    for (const Case& k : cases) {
        const Image guide = testing::structured_guide(k.w, k.h, 11);
        const Image mask = testing::random_mask(k.w, k.h, k.channels, 5);
        for (const BilateralOptions& o : option_sets(k.radius)) {
            const Image out = cross_bilateral(ctx, mask, guide, o);
            EXPECT_LE(testing::max_difference(out, testing::reference_bilateral(mask, guide, o)), kBilateralTolerance)
                << describe(o) << " on " << k.w << "x" << k.h << "x" << k.channels;
        }
    }
}

PN_BACKEND_TEST(BilateralTest, MatchesBruteForceReferenceWithNormals)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 31, h = 21;
    const Image guide = testing::structured_guide(w, h, 3);
    const Image normals = testing::structured_normals(w, h);
    const Image mask = testing::random_mask(w, h, 2, 9);
    for (BilateralOptions o : option_sets(2)) {
        o.normal_sigma = 0.3f;
        const Image out = cross_bilateral(ctx, mask, guide, o, &normals);
        const auto ref = testing::reference_bilateral(mask, guide, o, &normals);
        EXPECT_LE(testing::max_difference(out, ref), kBilateralTolerance)
            << describe(o) << " with normals";
    }
}

// Every strip and tail shape of every lane count, and windows wider than the
// image (every tap clamped): the clamp-to-edge accessor (pn_load_clamped) and
// the interior fast path (pn_strips_inside, pn_load_inside) at their edges.
PN_BACKEND_TEST(BilateralTest, OddSizesAndLaneEdgeWidths)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    std::vector<std::pair<int, int>> sizes{{1, 1}, {7, 3}, {2, 9}, {3, 2}};
    for (int w : testing::lane_edge_widths()) sizes.push_back({w, 6});
    for (auto [w, h] : sizes)
        for (int radius : {1, 2, 5}) {
            const Image guide = testing::structured_guide(w, h, 17);
            const Image mask = testing::random_mask(w, h, 2, 23);
            for (const BilateralOptions& o : option_sets(radius)) {
                if (o.relative) continue;  // the shapes matter here, not the range weight
                const Image out = cross_bilateral(ctx, mask, guide, o);
                const auto ref = testing::reference_bilateral(mask, guide, o);
                EXPECT_LE(testing::max_difference(out, ref), kBilateralTolerance)
                    << describe(o) << " on " << w << "x" << h;
            }
        }
}

// Every tap of a 1x1 image reads its one pixel: the result is that value,
// within the rounding of a weighted average of copies of it.
PN_BACKEND_TEST(BilateralTest, OnePixelImageIsItsOwnAverage)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image guide(1, 1, 1), mask(1, 1, 4);
    guide.at(0, 0, 0) = 3.5f;
    for (int c = 0; c < 4; ++c) mask.at(c, 0, 0) = 0.1f * float(c + 1);
    for (const BilateralOptions& o : option_sets(2)) {
        const Image out = cross_bilateral(ctx, mask, guide, o);
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(out.at(c, 0, 0), mask.at(c, 0, 0), kAverageOfCopies * mask.at(c, 0, 0)) << describe(o);
    }
}

// ---- properties with closed forms ------------------------------------------

// Sum w c / sum w = c whatever the weights: exact up to the rounding of the
// sums (25 taps: relative 2^-24 per addition and the division).
PN_BACKEND_TEST(BilateralTest, ConstantMaskStaysConstant)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 45, h = 27;
    const Image guide = testing::structured_guide(w, h, 2, 0.2f);
    const Image normals = testing::structured_normals(w, h);
    Image mask(w, h, 4);
    const float values[4] = {0.0f, 0.37f, 1.0f, 0.8125f};
    for (int c = 0; c < 4; ++c) mask.fill(c, values[c]);
    for (const BilateralOptions& o : option_sets(2))
        for (const Image* n : {static_cast<const Image*>(nullptr), &normals}) {
            const Image out = cross_bilateral(ctx, mask, guide, o, n);
            for (int c = 0; c < 4; ++c)
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x)
                        ASSERT_NEAR(out.at(c, x, y), values[c], 4e-6 * values[c]) << describe(o) << " at " << x << ","
                                                                                  << y;
        }
}

// A flat guide makes every range weight 1: the filter is the normalised
// Gaussian blur of the mask, computed here in closed form.
PN_BACKEND_TEST(BilateralTest, FlatGuideIsAGaussianBlur)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 39, h = 26;
    Image guide(w, h, 1);
    guide.fill(0, 0.625f);
    const Image mask = testing::random_mask(w, h, 3, 41);
    for (int radius : {1, 2, 3})
        for (BilateralOptions o : option_sets(radius))
            for (float sigma : {0.8f, 1.5f, 4.0f}) {
                o.spatial_sigma = sigma;
                const Image out = cross_bilateral(ctx, mask, guide, o);
                for (int c = 0; c < 3; ++c) {
                    const std::vector<double> blur =
                        testing::gaussian_blur(mask, c, radius, sigma, o.window == BilateralWindow::Disk);
                    for (int y = 0; y < h; ++y)
                        for (int x = 0; x < w; ++x)
                            ASSERT_NEAR(out.at(c, x, y), blur[std::size_t(y) * w + x], kBilateralTolerance)
                                << describe(o) << " sigma " << sigma << " at " << x << "," << y;
                }
            }
}

// The halo test: a depth step (near on the left, far on the right, along a
// staircase so that the step is not one straight column), and a mask that is
// 1 on one side and 0 on the other, both ways round. The leak is the largest
// value the filter puts on the side of 0s: a plain Gaussian blur leaks across
// the step (its closed-form leak is printed beside the filter's); the
// cross-bilateral filter must not: below 1e-12 with Gaussian weights (a
// rejected tap weighs at most 2^-60), exactly 0 with the threshold.
PN_BACKEND_TEST(BilateralTest, DepthStepDoesNotLeak)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 40, h = 24, step = 19;
    Image guide(w, h, 1), far_ones(w, h, 1), near_ones(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool far = x >= step + (y / 8);
            guide.at(0, x, y) = far ? 0.8f : 0.2f;
            far_ones.at(0, x, y) = far ? 1.0f : 0.0f;
            near_ones.at(0, x, y) = far ? 0.0f : 1.0f;
        }
    // The largest value of `filtered` where `mask` is 0.
    auto leak_of = [&](const Image& mask, auto value_at) {
        double leak = 0.0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if (mask.at(0, x, y) == 0.0f) leak = std::max(leak, double(value_at(x, y)));
        return leak;
    };
    double blur_leak = 0.0;
    for (const Image* mask : {&far_ones, &near_ones}) {
        const std::vector<double> blur = testing::gaussian_blur(*mask, 0, 2, 1.5, false);
        blur_leak = std::max(blur_leak, leak_of(*mask, [&](int x, int y) { return blur[std::size_t(y) * w + x]; }));
    }
    EXPECT_GT(blur_leak, 0.3);
    for (BilateralOptions o : option_sets(2)) {
        o.spatial_sigma = 1.5f;
        double leak = 0.0;
        for (const Image* mask : {&far_ones, &near_ones}) {
            const Image out = cross_bilateral(ctx, *mask, guide, o);
            leak = std::max(leak, leak_of(*mask, [&](int x, int y) { return out.at(0, x, y); }));
        }
        if (o.range == BilateralRange::Threshold)
            EXPECT_EQ(leak, 0.0) << describe(o);
        else
            EXPECT_LT(leak, 1e-12) << describe(o);
        if (backend == "scalar" && !o.separable && o.window == BilateralWindow::Square && !o.relative)
            std::cout << "[ halo     ] largest leak across the step, radius 2, sigma 1.5: plain Gaussian blur "
                      << blur_leak << ", cross-bilateral (" << describe(o) << ") " << leak << "\n";
    }
}

// Depths all far apart: every neighbour is rejected, the pixel keeps its own
// value, finite, without a division by zero. z = 2^(x mod 5 + 5 (y mod 5)):
// within radius 2 every other pixel differs by a factor of 2 at least
// (absolute difference >= 1, relative >= 0.5). In the interior the result is
// the value itself (threshold: exactly; Gaussian: but for the 2^-60 floor of
// 24 taps); taps clamped at the border read the pixel itself, and a weighted
// average of copies of one value is that value within the rounding of its
// two float sums of 25 terms (24 2^-24 relative each) and the division:
// kAverageOfCopies = 3e-6 relative.
PN_BACKEND_TEST(BilateralTest, FullyRejectedNeighbourhoodKeepsItsValue)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 23, h = 11;
    Image guide(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) guide.at(0, x, y) = std::ldexp(1.0f, x % 5 + 5 * (y % 5));
    const Image mask = testing::random_mask(w, h, 2, 77);
    for (const BilateralOptions& o : option_sets(2)) {
        const Image out = cross_bilateral(ctx, mask, guide, o);
        for (int c = 0; c < 2; ++c)
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const float v = out.at(c, x, y);
                    ASSERT_TRUE(std::isfinite(v));
                    const bool interior = x >= 2 && y >= 2 && x < w - 2 && y < h - 2;
                    const float m = mask.at(c, x, y);
                    if (interior && o.range == BilateralRange::Threshold)
                        ASSERT_EQ(v, m) << describe(o) << " at " << x << "," << y;
                    else if (interior)
                        ASSERT_NEAR(v, m, 1e-15) << describe(o) << " at " << x << "," << y;
                    else
                        ASSERT_NEAR(v, m, kAverageOfCopies * m + 1e-15) << describe(o) << " at " << x << "," << y;
                }
    }
}

// ---- the two schedules, and the backends against each other -----------------

// Separable equals full on a flat guide (the Gaussian is separable); across
// depth edges it is an approximation, whose distance the test prints and
// bounds on a structured guide.
PN_BACKEND_TEST(BilateralTest, SeparableIsCloseToFull)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 64, h = 48;
    const Image mask = testing::random_mask(w, h, 1, 8);
    Image flat(w, h, 1);
    flat.fill(0, 0.5f);
    const Image guide = testing::structured_guide(w, h, 12, 0.002f);
    BilateralOptions full;
    full.relative = false;
    full.depth_sigma = 0.02f;
    BilateralOptions separable = full;
    separable.separable = true;
    const Image flat_full = cross_bilateral(ctx, mask, flat, full);
    EXPECT_LE(testing::max_difference(flat_full, cross_bilateral(ctx, mask, flat, separable)), kBilateralTolerance);
    const double distance =
        testing::max_difference(cross_bilateral(ctx, mask, guide, full), cross_bilateral(ctx, mask, guide, separable));
    if (backend == "scalar")
        std::cout << "[ separable] largest |separable - full| on a structured guide: " << distance << "\n";
    EXPECT_LT(distance, 0.25);
}

// Every backend against the scalar oracle. The descriptions use the same
// operations in the same order everywhere; only pn_fma differs (SSE4.2 has no
// FMA and rounds twice), so ISAs with FMA and OpenCL agree to 2e-7 (a few
// roundings of values in [0, 1]) and SSE4.2 to 2e-6.
// Its own suite, instantiated without scalar: scalar against itself would count as a pass.
class BilateralAgreement : public ::testing::TestWithParam<std::string> {};

PN_BACKEND_TEST(BilateralAgreement, AgreesWithScalarBackend)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Context& oracle = testing::scalar_oracle(backend);
    const double tolerance = backend == "sse4.2" ? 2e-6 : 2e-7;
    const int w = 67, h = 45;
    const Image guide = testing::structured_guide(w, h, 4);
    const Image normals = testing::structured_normals(w, h);
    const Image mask = testing::random_mask(w, h, 4, 6);
    for (const BilateralOptions& o : option_sets(2))
        for (const Image* n : {static_cast<const Image*>(nullptr), &normals}) {
            const Image ours = cross_bilateral(ctx, mask, guide, o, n);
            const double diff = testing::max_difference(ours, cross_bilateral(oracle, mask, guide, o, n));
            EXPECT_LE(diff, tolerance) << describe(o) << (n ? " with normals" : "");
        }
}

INSTANTIATE_TEST_SUITE_P(Backends, BilateralAgreement, ::testing::ValuesIn(testing::non_scalar_backends()),
                         backend_test_name);

// The into-variant writes an existing image and gives the same result.
PN_BACKEND_TEST(BilateralTest, IntoVariantMatches)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image guide = testing::structured_guide(21, 13, 1);
    const Image mask = testing::random_mask(21, 13, 3, 2);
    Image out(21, 13, 3);
    out.fill(0, 42.0f);
    const BilateralOptions o;
    cross_bilateral(ctx, mask, guide, o, out);
    EXPECT_EQ(testing::max_difference(out, cross_bilateral(ctx, mask, guide, o)), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Backends, BilateralTest, ::testing::ValuesIn(backend_names()), backend_test_name);

}  // namespace
}  // namespace penumbra
