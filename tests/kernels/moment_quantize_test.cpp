// The optimized 16-bit moment quantization (kernels/moment_quantize.h) and
// the encoded tables (kernels/encoded_table.h) on every backend: the paper's
// two matrices are inverse, every 16-bit depth encodes to the steps a double
// computation gives, decodes back to its powers, and window sums of the
// exact table are exact up to the largest window it accepts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

#include "penumbra/moments.h"
#include "support/backends.h"
#include "support/maps.h"
#include "support/moment_reference.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;

// The paper prints T^-1 to 10 digits: T^-1 T = I to 4e-9.
TEST(MomentQuantize, ThePapersMatricesAreInverse)
{
    const auto& t = testing::optimized_matrix();
    const auto& inverse = testing::optimized_inverse();
    double worst = 0.0;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            double s = 0.0;
            for (int k = 0; k < 4; ++k) s += inverse[r][k] * t[k][c];
            worst = std::max(worst, std::abs(s - (r == c ? 1.0 : 0.0)));
        }
    std::printf("[ quantize ] max |T^-1 T - I| = %.2g\n", worst);
    EXPECT_LT(worst, 4e-9);
}

// In double: every depth's encoding lies in [0, 1] (to 1e-7: o_3 dips to
// -6.5e-8 and is clamped), and the rounded steps decode to within 1.1e-5 of
// z^k: the quantization's own round trip, independent of any kernel.
TEST(MomentQuantize, RoundTripInDouble)
{
    double worst[4] = {0, 0, 0, 0}, low = 1.0, high = 0.0;
    for (int i = 0; i <= 65535; ++i) {
        const double z = i / 65535.0;
        const auto o = testing::optimized_encode(z);
        for (double v : o) {
            low = std::min(low, v);
            high = std::max(high, v);
        }
        const auto q = testing::optimized_steps(z);
        const testing::Moments4 b = testing::optimized_decode({q[0] / 65535.0, q[1] / 65535.0, q[2] / 65535.0,
                                                                q[3] / 65535.0});
        for (int k = 0; k < 4; ++k) worst[k] = std::max(worst[k], std::abs(b[k + 1] - std::pow(z, k + 1)));
    }
    std::printf("[ quantize ] encodings in [%.3g, %.9g]; decoded z^k off by at most %.3g %.3g %.3g %.3g\n", low, high,
                worst[0], worst[1], worst[2], worst[3]);
    EXPECT_GT(low, -1e-7);
    EXPECT_LT(high, 1.0 + 1e-7);
    for (double w : worst) EXPECT_LT(w, 1.1e-5);
}

class MomentQuantizeTest : public ::testing::TestWithParam<std::string> {};

// The kernel's steps for every 16-bit depth (a 256 x 256 map, one texel per
// depth; the exact table's one-texel sums are the steps themselves) against
// the double encoding: equal, or one step off where the float encoding lands
// within float rounding of a half step. Depths 0 and 1 (the 16-bit limits)
// exactly. The float table of the same 16-bit values holds steps / 65535
// (checked near its origin, where its own rounding is below 1e-6).
PN_BACKEND_TEST(MomentQuantizeTest, EveryDepthEncodesToThePapersSteps)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image depth(256, 256, 1);
    for (int i = 0; i < 65536; ++i) depth.at(0, i % 256, i / 256) = float(i) / 65535.0f;
    const MsmTable exact = build_msm_table(ctx, depth, Quantization::Bits16, Precision::Exact);
    const MsmTable floats = build_msm_table(ctx, depth, Quantization::Bits16, Precision::Float);
    int off_by_one = 0;
    for (int i = 0; i < 65536; ++i) {
        const int x = i % 256, y = i / 256;
        const auto want = testing::optimized_steps(depth.at(0, x, y));
        for (int k = 0; k < 4; ++k) {
            const std::uint32_t got = exact.sums.exact_box_sum(k + 1, x, x + 1, y, y + 1);
            ASSERT_LE(got, 65535u);
            ASSERT_LE(std::abs(double(got) - double(want[k])), 1.0) << backend << " depth " << i << " moment " << k;
            off_by_one += got != want[k];
            if (x < 8 && y < 8) {  // near the origin the float table's entries are small: rounding 1e-6
                ASSERT_NEAR(floats.sums.box_sum(k + 1, x, x + 1, y, y + 1), double(got) / 65535.0, 1e-6);
            }
        }
    }
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(exact.sums.exact_box_sum(k + 1, 0, 1, 0, 1), testing::optimized_steps(0.0)[k]);
        EXPECT_EQ(exact.sums.exact_box_sum(k + 1, 255, 256, 255, 256), testing::optimized_steps(1.0)[k]);
    }
    std::printf("[ quantize ] %s: %d of 262144 steps one off the double encoding\n", backend.c_str(), off_by_one);
    // A value within float rounding of a half step can round either way: the
    // share of such values is twice the rounding in steps (measured 0.24%,
    // i.e. 1.2e-3 steps; evaluated as printed, the paper's polynomials gave 4.4%).
    EXPECT_LT(off_by_one, 262144 / 200);
}

// Window sums of the exact table are the exact integer sums of the steps for
// every window it accepts, the largest (255 x 255) included, anywhere on a map
// whose table entries wrap modulo 2^32 many times over.
PN_BACKEND_TEST(MomentQuantizeTest, ExactWindowSumsUpToTheLargestWindow)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 613, h = 521;  // the entries reach 1e10 steps: they wrap modulo 2^32
    Image depth(w, h, 1);
    std::mt19937 rng(12);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) depth.at(0, x, y) = float(rng() % 65536) / 65535.0f;
    const MsmTable table = build_msm_table(ctx, depth);
    struct Window {
        int x0, x1, y0, y1;
    };
    for (Window win : {Window{0, 255, 0, 255}, Window{w - 255, w, h - 255, h}, Window{100, 355, 200, 455},
                       Window{w - 1, w, h - 1, h}, Window{3, 4, 517, 521}}) {
        // In 64 bits, from the table's own one-texel sums (each texel's steps).
        std::uint64_t want[4] = {0, 0, 0, 0};
        for (int y = win.y0; y < win.y1; ++y)
            for (int x = win.x0; x < win.x1; ++x)
                for (int k = 0; k < 4; ++k) want[k] += table.sums.exact_box_sum(k + 1, x, x + 1, y, y + 1);
        for (int k = 0; k < 4; ++k) {
            ASSERT_LT(want[k], std::uint64_t(1) << 32);
            ASSERT_EQ(table.sums.exact_box_sum(k + 1, win.x0, win.x1, win.y0, win.y1), want[k])
                << backend << " window at " << win.x0 << "," << win.y0 << " moment " << k;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, MomentQuantizeTest, ::testing::ValuesIn(backend_names()), backend_test_name);

}  // namespace
}  // namespace penumbra
