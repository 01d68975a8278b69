// EVSM (kernels/evsm.h, exponential_warp.h, encoded_table.h) on every
// backend: against the warps and Chebyshev bounds computed in double from the
// table's own window sums, the stored warps against exp() in double, the
// exponents at the storage limits, and the failure windows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "penumbra/chebyshev.h"
#include "penumbra/moments.h"
#include "support/backends.h"
#include "support/maps.h"
#include "support/visibility.h"

namespace penumbra {
namespace {

using testing::expect_visibility;
using testing::backend_names;
using testing::backend_test_name;

// Random depths with `extremes` texels (some twice) at 0 or 1, where the
// warps reach their largest and smallest values.
Image depth_with_extremes(int w, int h, int extremes, std::mt19937& rng)
{
    Image depth = testing::random_depth(w, h, rng());
    for (int i = 0; i < extremes; ++i) depth.at(0, int(rng() % w), int(rng() % h)) = float(rng() % 2);
    return depth;
}

// Receivers on every texel at depths in [-0.1, 1.1]: outside [0, 1] too,
// which the kernel clamps.
Image receivers_beyond_the_range(int w, int h, std::mt19937& rng)
{
    return testing::receivers_on_texels(w, h, w, h, -0.1f, 1.1f, rng());
}

EvsmTable evsm_table_for(Context& ctx, const Image& depth, int channels, Quantization q, float cp, float cn)
{
    EvsmWarp warp;
    warp.channels = channels;
    warp.quantization = q;
    warp.positive = cp;
    warp.negative = cn;
    return build_evsm_table(ctx, depth, warp, q == Quantization::Bits16 ? Precision::Exact : Precision::Float);
}

// ---- the reference ---------------------------------------------------------------

// Mean of stored channel k (1-based) over a texel window, from the table's sums.
double channel_mean(const EvsmTable& t, int k, int x0, int x1, int y0, int y1)
{
    const double area = double(x1 - x0) * (y1 - y0);
    if (t.sums.precision() == Precision::Exact) return double(t.sums.exact_box_sum(k, x0, x1, y0, y1)) / 65535.0 / area;
    return t.sums.box_sum(k, x0, x1, y0, y1) / area;
}

double chebyshev(double mean, double mean_sq, double w, double floor, double bleed)
{
    const double var = std::max(mean_sq - mean * mean, floor);
    const double d = w - mean;
    const double p = d <= 0.0 ? 1.0 : var / (var + d * d);
    return std::clamp((p - bleed) / (1.0 - bleed), 0.0, 1.0);
}

// kernels/evsm.h in double, with the warped receiver and each window mean
// moved by -e, 0, +e: the interval float rounding can reach. For the warp,
// e is a few roundings plus exp()'s: it rounds its argument c (z - 1) to
// 2^-24 of c. For a mean, a few roundings, plus on a float table the
// rounding of its entries: a window sum is the difference of entries as
// large as the sum from the origin to the window's far corner, each rounded
// to 2^-24 of itself, which dwarfs a small warped value far from the light.
struct Interval {
    double lo = 2.0, hi = -1.0;
};

Interval evsm_reference(const EvsmTable& t, const EvsmOptions& o, int x0, int x1, int y0, int y1, double receiver_z)
{
    const double z = std::clamp(receiver_z - o.depth_bias, 0.0, 1.0);
    const double area = double(x1 - x0) * (y1 - y0);
    const bool floats = t.sums.precision() == Precision::Float;
    double m[4], e[4];
    for (int k = 0; k < t.channels; ++k) {
        m[k] = channel_mean(t, k + 1, x0, x1, y0, y1);
        const double corner = floats ? t.sums.box_sum(k + 1, 0, x1, 0, y1) : 0.0;
        e[k] = 4e-7 * std::abs(m[k]) + 4.0 * 0x1p-24 * corner / area;
    }
    // One warp's interval; the two warps' errors are independent, and the
    // minimum of two intervals is [min of lows, min of highs].
    auto warp_interval = [&](double c, double sign, double mean, double mean_e, double sq, double sq_e, double w0) {
        const double ew = 4e-7 + 2.0 * c * 0x1p-24;
        Interval iv;
        for (int a : {-1, 0, 1})
            for (int b : {-1, 0, 1})
                for (int d : {-1, 0, 1}) {
                    const double w = w0 * (1 + a * ew);
                    const double v = chebyshev(sign * (mean + b * mean_e), sq + d * sq_e, sign * w,
                                               o.min_variance * std::pow(c * w, 2), o.bleed);
                    iv.lo = std::min(iv.lo, v);
                    iv.hi = std::max(iv.hi, v);
                }
        return iv;
    };
    Interval iv = warp_interval(t.positive, 1.0, m[0], e[0], m[1], e[1], std::exp(t.positive * (z - 1.0)));
    if (t.channels == 4) {
        const Interval n = warp_interval(t.negative, -1.0, m[2], e[2], m[3], e[3], std::exp(-t.negative * z));
        iv = {std::min(iv.lo, n.lo), std::min(iv.hi, n.hi)};
    }
    return iv;
}

// Runs EVSM of `rx` at every radius of `radii`, bleed 0 and 0.3, checks each
// output is a visibility, then calls check(options, x, y, value) per pixel;
// stops at the first fatal failure, as an ASSERT in the loop body would.
template <class Check>
void check_each_pixel(Context& ctx, const EvsmTable& table, const Image& rx, std::initializer_list<int> radii,
                      const std::string& backend, Check&& check)
{
    for (int radius : radii)
        for (float bleed : {0.0f, 0.3f}) {
            const EvsmOptions o{radius, kDefaultMinVariance, bleed, 0.0f};
            const Image out = evsm(ctx, table, rx, o);
            expect_visibility(out, backend);
            for (int y = 0; y < rx.height(); ++y)
                for (int x = 0; x < rx.width(); ++x) {
                    check(o, x, y, double(out.at(0, x, y)));
                    if (::testing::Test::HasFatalFailure()) return;
                }
        }
}

class EvsmTest : public ::testing::TestWithParam<std::string> {};

// Random maps and receivers, both channel counts and storages, default and
// limit exponents, radii 0 to 3, bleed 0 and 0.3: the kernel lands in the
// reference interval (plus 2e-6 for the final divisions and the linstep).
PN_BACKEND_TEST(EvsmTest, MatchesTheReferenceOnTheTablesOwnSums)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    double worst = 0.0;
    for (Quantization q : {Quantization::Bits16, Quantization::Bits32})
        for (int channels : {2, 4}) {
            const float limit = q == Quantization::Bits16 ? kEvsmMaxExponent16 : kEvsmMaxExponent32;
            for (float cp : {default_evsm_exponent(q, true), limit}) {
                const int w = 13, h = 9;
                const Image depth = depth_with_extremes(w, h, 20, rng);
                const EvsmTable table = evsm_table_for(ctx, depth, channels, q, cp, default_evsm_exponent(q, false));
                Image rx = receivers_beyond_the_range(w, h, rng);
                for (int i = 0; i < w * h / 2; ++i) {
                    const int x = int(rng() % w), y = int(rng() % h);
                    rx.at(2, x, y) = depth.at(0, x, y) + 0.02f * (unit(rng) - 0.5f);
                }
                const auto in_interval = [&](const EvsmOptions& o, int x, int y, double got) {
                    const int r = o.radius;
                    const Interval iv = evsm_reference(table, o, std::max(x - r, 0), std::min(x + r + 1, w),
                                                       std::max(y - r, 0), std::min(y + r + 1, h), rx.at(2, x, y));
                    worst = std::max(worst, std::max(iv.lo - got, got - iv.hi));
                    ASSERT_TRUE(got >= iv.lo - 2e-6 && got <= iv.hi + 2e-6)
                        << backend << " " << to_string(q) << "-bit EVSM" << channels << " c+ " << cp << " r=" << r
                        << " at " << x << "," << y << ": " << got << " not in [" << iv.lo << ", " << iv.hi << "]";
                };
                check_each_pixel(ctx, table, rx, {0, 1, 3}, backend, in_interval);
                if (::testing::Test::HasFatalFailure()) return;
            }
        }
    std::printf("[ evsm ] %s: worst distance outside the reference interval %.2g\n", backend.c_str(), worst);
}

// The default storage (exact 48-bit limb tables) against EVSM in double on
// the float32 depths themselves (warps of each depth, window means, bound):
// the limbs round each warp to 2^-49, so only the output's float rounding and
// exp()'s last bits remain. Default and largest exponents, both warps, odd
// sizes, receivers on, in front of and behind the surface, bleed on and off.
PN_BACKEND_TEST(EvsmTest, DefaultStorageIsTheMethodInDouble)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    double worst = 0.0;
    for (int channels : {2, 4})
        for (float cp : {kEvsmPositiveExponentExact, kEvsmMaxExponentExact}) {
            const float cn = channels == 4 ? kEvsmMaxExponentExact : 0.0f;
            const int w = 1 + int(rng() % 23), h = 1 + int(rng() % 11);
            const Image depth = depth_with_extremes(w, h, w * h / 4, rng);
            const EvsmTable table = build_evsm_table(ctx, depth, EvsmWarp{channels, cp, cn, Quantization::None});
            Image rx = receivers_beyond_the_range(w, h, rng);
            for (int i = 0; i < w * h; ++i) {
                const int x = i % w, y = i / w;
                if (i % 3 == 0) rx.at(2, x, y) = depth.at(0, x, y);
                if (i % 3 == 1) rx.at(2, x, y) = depth.at(0, x, y) + 0.02f * (unit(rng) - 0.5f);
            }
            const auto near_double = [&](const EvsmOptions& o, int x, int y, double got) {
                const int x0 = std::max(x - o.radius, 0), x1 = std::min(x + o.radius + 1, w);
                const int y0 = std::max(y - o.radius, 0), y1 = std::min(y + o.radius + 1, h);
                double m[4] = {0, 0, 0, 0};
                for (int j = y0; j < y1; ++j)
                    for (int i = x0; i < x1; ++i) {
                        const double z = depth.at(0, i, j);
                        const double p = std::exp(double(cp) * (z - 1.0)), n = std::exp(-double(cn) * z);
                        m[0] += p, m[1] += p * p, m[2] += n, m[3] += n * n;
                    }
                const double area = double(x1 - x0) * (y1 - y0);
                const double zr = std::clamp(double(rx.at(2, x, y)), 0.0, 1.0);
                const double wp = std::exp(double(cp) * (zr - 1.0)), wn = std::exp(-double(cn) * zr);
                const double floor_p = kDefaultMinVariance * std::pow(double(cp) * wp, 2);
                double want = chebyshev(m[0] / area, m[1] / area, wp, floor_p, o.bleed);
                if (channels == 4)
                    want = std::min(want, chebyshev(-m[2] / area, m[3] / area, -wn,
                                                    kDefaultMinVariance * std::pow(double(cn) * wn, 2), o.bleed));
                worst = std::max(worst, std::abs(got - want));
                ASSERT_NEAR(got, want, 1e-5) << backend << " EVSM" << channels << " c+ " << cp << " r=" << o.radius
                                             << " " << w << "x" << h << " at " << x << "," << y;
            };
            check_each_pixel(ctx, table, rx, {0, 1, 3, 40}, backend, near_double);
            if (::testing::Test::HasFatalFailure()) return;
        }
    std::printf("[ evsm ] %s: default storage, worst |kernel - double| %.2g\n", backend.c_str(), worst);
}

// The stored channels are the warps, to the storage's precision: 16-bit
// steps of e^{c+(z-1)}, its square, e^{-c- z} and its square against exp() in
// double (within one step: the kernel's exp and rounding are float); float
// tables to exp()'s and the table's float rounding (4 roundings of the
// argument times c, and 2^-22 of the table entry, which sums (x+1)(y+1) texels).
PN_BACKEND_TEST(EvsmTest, StoredWarpsMatchExp)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image depth(256, 16, 1);
    for (int i = 0; i < 256 * 16; ++i) depth.at(0, i % 256, i / 256) = float(i) / float(256 * 16 - 1);
    for (Quantization q : {Quantization::Bits16, Quantization::Bits32}) {
        const float c = q == Quantization::Bits16 ? kEvsmMaxExponent16 : 10.0f;
        const EvsmTable t = evsm_table_for(ctx, depth, 4, q, c, c);
        for (int i = 0; i < 256 * 16; ++i) {
            const int x = i % 256, y = i / 256;
            const double z = depth.at(0, x, y);
            const double want[4] = {std::exp(c * (z - 1)), std::exp(2 * c * (z - 1)), std::exp(-c * z),
                                    std::exp(-2 * c * z)};
            for (int k = 0; k < 4; ++k) {
                if (q == Quantization::Bits16) {
                    const double steps = double(t.sums.exact_box_sum(k + 1, x, x + 1, y, y + 1));
                    ASSERT_LE(std::abs(steps - want[k] * 65535.0), 1.0) << backend << " z " << z << " channel " << k;
                } else {
                    const double bound = (4e-7 + 8.0 * c * 0x1p-24) * want[k] + 0x1p-22 * (x + 1) * (y + 1);
                    ASSERT_NEAR(t.sums.box_sum(k + 1, x, x + 1, y, y + 1), want[k], bound)
                        << backend << " z " << z << " channel " << k;
                }
            }
        }
    }
}

// One depth per window (every level of a ramp, radius 0) at the exponents'
// storage limits, receivers from 2 in front to 2 behind (clamped into [0, 1]):
// never NaN, always in [0, 1]. On exact tables, in front is lit exactly and
// behind (by 0.05 or more) dark: EVSM4 everywhere, EVSM2 but near the light,
// where the positive warp's square is within a few 16-bit steps (measured:
// 0.38 at depths below 0.25, docs/moments.md). Float tables are printed only:
// a float summed-area table cannot hold e^{-42} next to sums of 1 (the
// largest exponents are for small maps; docs/moments.md).
PN_BACKEND_TEST(EvsmTest, OneDepthWindowsAtTheStorageLimits)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image ramp(64, 64, 1);
    for (int i = 0; i < 4096; ++i) ramp.at(0, i % 64, i / 64) = float(i) / 4095.0f;
    for (Quantization q : {Quantization::Bits16, Quantization::Bits32}) {
        const float limit = q == Quantization::Bits16 ? kEvsmMaxExponent16 : kEvsmMaxExponent32;
        for (int channels : {2, 4}) {
            const EvsmTable t = evsm_table_for(ctx, ramp, channels, q, limit, limit);
            for (float shift : {-2.0f, -0.1f, 0.1f, 2.0f}) {
                Image rx = testing::receivers_at_depth(64, 64, 0.0f);
                for (int i = 0; i < 4096; ++i) rx.at(2, i % 64, i / 64) = ramp.at(0, i % 64, i / 64) + shift;
                const Image out = evsm(ctx, t, rx, EvsmOptions{0});
                expect_visibility(out, backend);
                float worst[4] = {0, 0, 0, 0};  // by the texel's depth quarter: least lit in front, most lit behind
                for (int i = 0; i < 4096; ++i) {
                    const float z = rx.at(2, i % 64, i / 64), level = ramp.at(0, i % 64, i / 64);
                    const float v = out.at(0, i % 64, i / 64);
                    const int quarter = std::min(int(level * 4), 3);
                    if (shift < 0) worst[quarter] = std::max(worst[quarter], 1.0f - v);
                    if (shift > 0 && std::min(z, 1.0f) - level >= 0.05f) worst[quarter] = std::max(worst[quarter], v);
                }
                std::printf("[ evsm ] %s %s-bit EVSM%d c=%.3g, receivers %+.1f from one depth, worst %s by depth "
                            "quarter: %.3f %.3f %.3f %.3f\n",
                            backend.c_str(), to_string(q).c_str(), channels, limit, shift,
                            shift < 0 ? "shadow" : "light", worst[0], worst[1], worst[2], worst[3]);
                if (q == Quantization::Bits32) continue;
                for (int k = 0; k < 4; ++k) {
                    if (shift < 0) {
                        EXPECT_EQ(worst[k], 0.0f) << backend << " in front, quarter " << k;
                    }
                    if (shift > 0 && (channels == 4 || k > 0)) {
                        EXPECT_LT(worst[k], 0.05f) << backend << " EVSM" << channels << " behind, quarter " << k;
                    }
                }
            }
        }
    }
}

// EVSM4 takes the smaller of two upper bounds: never above EVSM2 with the
// same positive warp.
PN_BACKEND_TEST(EvsmTest, FourChannelsNeverAboveTwo)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image depth = testing::random_depth(41, 29, 17);
    const Image rx = testing::receivers_on_texels(41, 29, 41, 29, 0.0f, 1.0f, 19);
    for (Quantization q : {Quantization::Bits16, Quantization::Bits32}) {
        const float cp = default_evsm_exponent(q, true), cn = default_evsm_exponent(q, false);
        const Image two = evsm(ctx, evsm_table_for(ctx, depth, 2, q, cp, cn), rx, EvsmOptions{2});
        const Image four = evsm(ctx, evsm_table_for(ctx, depth, 4, q, cp, cn), rx, EvsmOptions{2});
        for (int y = 0; y < 29; ++y)
            for (int x = 0; x < 41; ++x)
                ASSERT_LE(four.at(0, x, y), two.at(0, x, y)) << backend << " " << x << "," << y;
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, EvsmTest, ::testing::ValuesIn(backend_names()), backend_test_name);

}  // namespace
}  // namespace penumbra
