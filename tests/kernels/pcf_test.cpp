// The percentage-closer family (kernels/pcf.h, pcf_gauss.h, pcf_disc.h, with
// every bias mode of kernels/depth_bias.h) against the float64 reference of
// tests/support/pcf_reference.h on every backend, at odd sizes and widths
// around every lane count; the weights' sum and a half-plane edge in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "support/backends.h"
#include "support/maps.h"
#include "support/pcf_shade.h"
#include "support/pcf_reference.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;
using testing::PcfKernel;
using testing::RefBias;
using testing::RefBiasMode;
using testing::RefResult;

// A receiver whose decision float32 may take either way (a tap's depth within
// this of z - beta, a position within it of a texel edge) is left out; the
// draws below make them rare, and the count is checked.
constexpr double kDecisionMargin = 1e-5;
// The kernels sum at most 256 weights in float (Gaussian: products of
// float32 exponentials): 1e-5 covers the rounding.
constexpr double kPcfTolerance = 1e-5;

// Receivers with u, v in [-0.1, 1.1] (some clamped), z in [0, 1], and the
// derivative planes: slopes up to 4 depth units per unit of texture and a
// plane flag that fails for one receiver in five.
Image random_receivers(int width, int height, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uv(-0.1f, 1.1f), z(0.0f, 1.0f), slope(-4.0f, 4.0f), flag(0.0f, 1.0f);
    Image rx(width, height, 6);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            rx.at(0, x, y) = uv(rng);
            rx.at(1, x, y) = uv(rng);
            rx.at(2, x, y) = z(rng);
            rx.at(3, x, y) = slope(rng);
            rx.at(4, x, y) = slope(rng);
            rx.at(5, x, y) = flag(rng) < 0.8f ? 1.0f : 0.0f;
        }
    return rx;
}

PcfBias kernel_bias(const RefBias& b)
{
    return PcfBias{int(b.mode), float(b.constant), float(b.slope_scale), float(b.low), float(b.high)};
}

const RefBias kBiases[] = {
    {RefBiasMode::Constant, 0.01, 1.0, 0.0, 1.0},
    {RefBiasMode::Slope, 0.002, 1.5, 0.001, 0.05},
    {RefBiasMode::ReceiverPlane, 0.002, 1.0, 0.0, 0.05},
    {RefBiasMode::ReceiverPlane, 0.0, 1.0, -1.0, 1.0},  // no clamp: the plane both ways
};

struct Case {
    PcfKernel kernel;
    int radius = 2, grid = 4, taps = 16, rotate = 1;
    float sigma = 1.0f, disc_radius = 2.5f;
};

RefResult reference(const Case& c, const Image& map, const testing::RefReceiver& r, const RefBias& b)
{
    switch (c.kernel) {
    case PcfKernel::Box: return testing::pcf_box_reference(map, r, b, c.radius);
    case PcfKernel::Gauss: return testing::pcf_gauss_reference(map, r, b, c.grid, c.sigma);
    case PcfKernel::Disc: return testing::pcf_disc_reference(map, r, b, c.taps, c.disc_radius, c.rotate != 0);
    }
    return {};
}

PcfParams params_for(const Case& c, const RefBias& b)
{
    PcfParams p{};
    p.bias = kernel_bias(b);
    p.radius = c.radius;
    p.grid = c.grid;
    p.taps = c.taps;
    p.rotate = c.rotate;
    p.sigma = c.sigma;
    p.disc_radius = c.disc_radius;
    return p;
}

// Every receiver of `rx` against the reference; returns how many were left out.
int expect_matches_reference(const std::string& backend, const Case& c, const Image& map, const Image& rx)
{
    int undecided = 0;
    for (const RefBias& b : kBiases) {
        const Image out = testing::pcf_shade(backend, c.kernel, map, rx, params_for(c, b));
        for (int y = 0; y < rx.height(); ++y)
            for (int x = 0; x < rx.width(); ++x) {
                const RefResult want = reference(c, map, testing::ref_receiver(rx, x, y), b);
                if (want.margin < kDecisionMargin) {
                    ++undecided;
                    continue;
                }
                if (std::abs(out.at(0, x, y) - want.visibility) <= kPcfTolerance) continue;
                ADD_FAILURE() << backend << " kernel " << int(c.kernel) << " bias mode " << int(b.mode) << " map "
                              << map.width() << "x" << map.height() << " receiver (" << x << ", " << y
                              << "): " << out.at(0, x, y) << ", reference " << want.visibility;
                return undecided;
            }
    }
    return undecided;
}

class PcfReference : public ::testing::TestWithParam<std::string> {};

void run_sizes(const std::string& backend, const std::vector<Case>& cases)
{
    int undecided = 0, receivers = 0;
    const std::pair<int, int> maps[] = {{1, 1}, {7, 3}, {37, 29}};
    for (const auto& [mw, mh] : maps) {
        const Image map = testing::random_depth(mw, mh, 11u + mw);
        for (const int width : testing::lane_edge_widths()) {
            const Image rx = random_receivers(width, 3, 7u * width + mh);
            for (const Case& c : cases) {
                undecided += expect_matches_reference(backend, c, map, rx);
                receivers += width * 3 * int(std::size(kBiases));
            }
        }
    }
    EXPECT_LT(undecided, receivers / 50) << "too many receivers left undecided";
}

PN_BACKEND_TEST(PcfReference, BoxMatchesTheBruteForceLoop)
{
    run_sizes(backend, {{PcfKernel::Box, 0}, {PcfKernel::Box, 1}, {PcfKernel::Box, 2}, {PcfKernel::Box, 5}});
}

PN_BACKEND_TEST(PcfReference, GaussMatchesItsBilinearTaps)
{
    Case c{PcfKernel::Gauss};
    std::vector<Case> cases;
    for (const int grid : {1, 2, 4, 5})
        for (const float sigma : {0.5f, 1.0f, 3.0f}) {
            c.grid = grid;
            c.sigma = sigma;
            cases.push_back(c);
        }
    run_sizes(backend, cases);
}

PN_BACKEND_TEST(PcfReference, DiscMatchesItsSpiral)
{
    Case c{PcfKernel::Disc};
    std::vector<Case> cases;
    for (const int taps : {1, 7, 16, 64})
        for (const int rotate : {0, 1}) {
            c.taps = taps;
            c.rotate = rotate;
            c.disc_radius = taps == 7 ? 0.5f : 4.5f;
            cases.push_back(c);
        }
    run_sizes(backend, cases);
}

// A map that is lit everywhere: every method returns the sum of its weights.
PN_BACKEND_TEST(PcfReference, WeightsSumToOne)
{
    Image map(19, 13, 1);
    map.fill(0, 1.0f);
    const Image rx = random_receivers(23, 5, 3u);
    for (const Case& c : {Case{PcfKernel::Gauss, 2, 4}, Case{PcfKernel::Gauss, 2, 7, 16, 1, 2.0f},
                          Case{PcfKernel::Disc, 2, 4, 64}, Case{PcfKernel::Disc, 2, 4, 5, 0, 1.0f, 9.0f}}) {
        const Image out = testing::pcf_shade(backend, c.kernel, map, rx, params_for(c, kBiases[0]));
        for (int y = 0; y < rx.height(); ++y)
            for (int x = 0; x < rx.width(); ++x) ASSERT_NEAR(out.at(0, x, y), 1.0, 1e-6) << backend;
    }
}

// The half-plane x < edge (in texels) at depth 0 in front of receivers at 0.5.
Image half_plane(int width, int height, int edge)
{
    Image map(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) map.at(0, x, y) = x < edge ? 0.0f : 1.0f;
    return map;
}

Image receivers_across(int count, int map_width, double from, double to)
{
    Image rx(count, 1, 3);
    for (int i = 0; i < count; ++i) {
        rx.at(0, i, 0) = float((from + (to - from) * (i + 0.5) / count) / map_width);
        rx.at(1, i, 0) = 0.5f;
        rx.at(2, i, 0) = 0.5f;
    }
    return rx;
}

// Gaussian grid across the edge: tap i at p_i = x - 1/2 + (i - (n-1)/2) in
// texel-centre units sees the bilinear step clamp(p_i - (edge - 1), 0, 1).
PN_BACKEND_TEST(PcfReference, GaussReproducesTheHalfPlaneClosedForm)
{
    const int edge = 20, n = 4;
    const double sigma = 1.0, centre = 1.5;
    const Image map = half_plane(40, 9, edge);
    const Image rx = receivers_across(61, 40, edge - 4.0, edge + 4.0);
    const Case c{PcfKernel::Gauss, 0, n, 16, 1, float(sigma)};
    const Image out = testing::pcf_shade(backend, c.kernel, map, rx, params_for(c, kBiases[0]));
    double norm = 0.0;
    for (int i = 0; i < n; ++i) norm += std::exp(-(i - centre) * (i - centre) / (2 * sigma * sigma));
    for (int k = 0; k < rx.width(); ++k) {
        const double x = double(rx.at(0, k, 0)) * 40.0;
        double want = 0.0;
        for (int i = 0; i < n; ++i)
            want += std::exp(-(i - centre) * (i - centre) / (2 * sigma * sigma)) / norm *
                    std::clamp(x - 0.5 + (i - centre) - (edge - 1), 0.0, 1.0);
        ASSERT_NEAR(out.at(0, k, 0), want, 1e-5) << backend << " at x = " << x;
    }
}

// A uniform disc of radius R centred at signed distance d R from the edge
// (d > 0: centre on the lit side) has the lit share (acos(-d) + d sqrt(1 - d^2)) / pi;
// 256 spiral taps reach it within 0.02.
PN_BACKEND_TEST(PcfReference, DiscReproducesTheHalfPlaneAreaShare)
{
    const int edge = 30;
    const double radius = 8.0;
    const Image map = half_plane(60, 41, edge);
    const Image rx = receivers_across(41, 60, edge - radius, edge + radius);
    const Case c{PcfKernel::Disc, 0, 4, 256, 0, 1.0f, float(radius)};
    const Image out = testing::pcf_shade(backend, c.kernel, map, rx, params_for(c, kBiases[0]));
    for (int k = 0; k < rx.width(); ++k) {
        const double d = std::clamp((double(rx.at(0, k, 0)) * 60.0 - edge) / radius, -1.0, 1.0);
        const double want = (std::acos(-d) + d * std::sqrt(1.0 - d * d)) / std::numbers::pi;
        ASSERT_NEAR(out.at(0, k, 0), want, 0.02) << backend << " at d = " << d;
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, PcfReference, ::testing::ValuesIn(backend_names()), backend_test_name);

}  // namespace
}  // namespace penumbra
