// Moment soft shadows (kernels/msm_soft.h) on every backend: a straight
// blocker edge, where the blocker search, the penumbra estimate and the
// filtered reconstruction can each be worked out by hand; lit receivers;
// windows up to the whole map; never NaN.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "penumbra/moments.h"
#include "support/fidelity_cases.h"
#include "support/backends.h"
#include "support/maps.h"
#include "support/visibility.h"

namespace penumbra {
namespace {

using testing::expect_visibility;
using testing::backend_names;
using testing::backend_test_name;

MsmTable table_for(Context& ctx, const Image& depth, Quantization q)
{
    return build_msm_table(ctx, depth, q, q == Quantization::Bits16 ? Precision::Exact : Precision::Float);
}

class MsmSoftTest : public ::testing::TestWithParam<std::string> {};

// A 64 x 64 map: a blocker at depth 0.25 over columns 0-31, the ground at 0.75
// beyond; receivers on the ground (z = 0.75) at every texel centre. With
// L = 0.1: the search window is L W / 2 = 3.2 texels either side; it finds
// blockers at 0.25 where it reaches column 32 (centre cx < 35.2). The
// penumbra is L (0.75 - 0.25) / 0.25 = 0.2 texture units, a filter of 6.4
// texels either side, over which the visibility is the ground's share: a
// ramp 1 - clamp((32 - (cx - 6.4)) / 12.8, 0, 1). Where the search finds no
// blocker the receiver is lit: 1 (PCSS's step at cx = 35.2, the search being
// narrower than the penumbra).
PN_BACKEND_TEST(MsmSoftTest, StraightEdgeByHand)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image depth(64, 64, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) depth.at(0, x, y) = x < 32 ? 0.25f : 0.75f;
    const Image rx = testing::receivers_at_depth(64, 64, 0.75f);
    for (Quantization q : {Quantization::Bits16, Quantization::Bits32}) {
        const Image out = msm_soft(ctx, table_for(ctx, depth, q), rx, MsmSoftOptions{0.1f, {}, {}});
        expect_visibility(out, backend);
        double worst = 0.0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const double cx = x + 0.5;
                if (std::abs(cx - 35.2) < 0.6) continue;  // the step itself
                const double shadowed = std::clamp((32.0 - (cx - 6.4)) / 12.8, 0.0, 1.0);
                const double want = cx < 35.2 ? 1.0 - shadowed : 1.0;
                worst = std::max(worst, std::abs(out.at(0, x, y) - want));
                ASSERT_NEAR(out.at(0, x, y), want, 0.01) << backend << " " << to_string(q) << "-bit at " << x << ","
                                                         << y;
            }
        std::printf("[ msm-soft ] %s %s-bit: straight edge, max |got - hand| %.4f\n", backend.c_str(),
                    to_string(q).c_str(), worst);
    }
}

// The halo of issue 13: blockers of two depths in the search window, each far
// enough from the receiver to leave it lit by PCSS's own geometry (a blocker
// at z_b shadows a receiver at z only within w / 2 = L (z - z_b) / (2 z_b) of
// it), but their mean depth is nearer the light than the nearer one's, so
// the penumbra window that mean gives holds it. 64 x 16 map, ground 0.75,
// receiver at column 32 (centre 32.5), L W = 40 texels: B1 at depth 0.6 over
// columns 39-41 (6.5 texels away; its w / 2 is 5), B2 at 0.4 over 50-51 (17.5
// away; its w / 2 is 17.5, the edge of its reach). One search (the code
// before issue 13): mean blocker depth about 0.5, a window of about 9 texels
// that holds B1: 0.861. Searching again over each window found
// (kernels/msm_soft.h) narrows it to B1's depth, 5 texels, then finds no
// blocker: exactly 1.
PN_BACKEND_TEST(MsmSoftTest, NoHaloFromBlockersOfTwoDepths)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image depth(64, 16, 1);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 64; ++x) depth.at(0, x, y) = x >= 39 && x <= 41 ? 0.6f : x >= 50 && x <= 51 ? 0.4f : 0.75f;
    const Image rx = testing::receivers_at_depth(64, 16, 0.75f);
    for (Quantization q : {Quantization::Bits16, Quantization::Bits32}) {
        const Image out = msm_soft(ctx, table_for(ctx, depth, q), rx, MsmSoftOptions{40.0f / 64.0f, {}, {}});
        for (int y = 0; y < 16; ++y) EXPECT_EQ(out.at(0, 32, y), 1.0f) << backend << " " << to_string(q) << " row " << y;
    }
}

// The plane bias (kernels/msm_soft.h) against the float64 reference of
// tests/support/fidelity_reference.cpp on every backend: a ground tilted in
// both axes (dz/du = 0.1, dz/dv = 0.05) under a square blocker, receivers
// on the ground at every texel centre, so that the receivers' plane is
// known in closed form and the library's finite differences must find it.
// Bias shares 0.5 and 1, and 1 capped at 2e-3 (the cap binding); odd sizes.
// Ground sloping dz/du = 0.1, dz/dv = 0.05 under a square blocker at 0.15;
// receivers on the ground (u, v, z), and with `slope_channels` also its
// exact dzdu, dzdv as channels 3 and 4.
struct SlopedGround {
    static constexpr int w = 61, h = 47;
    Image depth{w, h, 1}, rx;
};

SlopedGround sloped_ground(bool slope_channels)
{
    SlopedGround g;
    g.rx = Image(g.w, g.h, slope_channels ? 5 : 3);
    const auto ground = [&](double u, double v) { return float(0.4 + 0.1 * u + 0.05 * v); };
    for (int y = 0; y < g.h; ++y)
        for (int x = 0; x < g.w; ++x) {
            const double u = (x + 0.5) / g.w, v = (y + 0.5) / g.h;
            const bool blocker = x >= 20 && x < 30 && y >= 15 && y < 25;
            g.depth.at(0, x, y) = blocker ? 0.15f : ground(u, v);
            g.rx.at(0, x, y) = float(u);
            g.rx.at(1, x, y) = float(v);
            g.rx.at(2, x, y) = ground(u, v);
        }
    if (slope_channels) {
        g.rx.fill(3, 0.1f);
        g.rx.fill(4, 0.05f);
    }
    return g;
}

// msm_soft with the plane bias on the sloped ground against its float64
// evaluation with the exact plane; `moved`: the largest rise over no bias.
void expect_plane_bias_fidelity(Context& ctx, const std::string& backend, const SlopedGround& g, MsmSoftOptions o)
{
    namespace fid = testing::fidelity;
    const MsmTable table = build_msm_table(ctx, g.depth);
    const Image out = msm_soft(ctx, table, g.rx, o);
    fid::Params p;
    p.light_size = o.light_size;
    p.max_radius = kExactMaxRadius - 1;
    p.moment_bias = default_moment_bias(table.quantization);
    p.msm_depth_bias = default_depth_bias(table.quantization);
    p.plane_bias = o.plane_bias;
    p.plane_bias_max = o.plane_bias_max;
    p.plane_dzdu = 0.1L;
    p.plane_dzdv = 0.05L;
    if (o.light_size == 0.3f && o.plane_bias_max == 0.02f) {  // a case where the bias matters
        const Image unbiased = msm_soft(ctx, table, sloped_ground(false).rx, MsmSoftOptions{0.3f, {}, {}});
        float moved = 0.0f;
        for (int i = 0; i < g.w * g.h; ++i)
            moved = std::max(moved, out.at(0, i % g.w, i / g.w) - unbiased.at(0, i % g.w, i / g.w));
        EXPECT_GT(moved, 0.05f) << backend << " plane bias " << o.plane_bias;
    }
    const fid::Tally t = fid::judge_all(fid::Method::MsmSoft, g.depth, g.rx, out, p);
    EXPECT_EQ(t.failed, 0) << backend << " L " << o.light_size << " plane bias " << o.plane_bias << " cap "
                           << o.plane_bias_max << ": " << t.failed << " of " << t.receivers << " fail (worst "
                           << t.worst << ")\n" << t.first_failures;
}

PN_BACKEND_TEST(MsmSoftTest, PlaneBiasMatchesTheFloat64Reference)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const SlopedGround g = sloped_ground(false);
    struct Bias {
        float share, cap;
    };
    for (float light : {0.1f, 0.3f})
        for (Bias b : {Bias{0.5f, 0.02f}, Bias{1.0f, 0.02f}, Bias{1.0f, 2e-3f}})
            expect_plane_bias_fidelity(ctx, backend, g, MsmSoftOptions{light, {}, {}, b.share, b.cap});
}

// The plane read from the receivers' channels dzdu, dzdv (no host pass of
// finite differences) meets the same float64 reference.
PN_BACKEND_TEST(MsmSoftTest, PlaneBiasFromChannelsMatchesTheFloat64Reference)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const SlopedGround g = sloped_ground(true);
    for (float light : {0.1f, 0.3f})
        expect_plane_bias_fidelity(ctx, backend, g,
                                   MsmSoftOptions{light, {}, {}, 1.0f, 0.02f, DerivativeSource::Channels});
}

// No blocker in front: exactly 1. On flat ground 0.01 below the receivers
// whatever the light size (up to a search over the whole map); on ground
// sloping 0.004 per texel for lights whose search (half-width L W / 2, plus
// the partly covered texel at its end) stays within the 2 texels on either
// side over which the ground rises less than 0.01.
PN_BACKEND_TEST(MsmSoftTest, LitReceiversAreExactlyLit)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (float slope : {0.0f, 0.004f}) {
        Image depth(48, 40, 1);
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 48; ++x) depth.at(0, x, y) = 0.5f + slope * float(x);
        Image rx = testing::receivers_at_depth(48, 40, 0.0f);
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 48; ++x) rx.at(2, x, y) = depth.at(0, x, y) - 0.01f;
        for (Quantization q : {Quantization::Bits16, Quantization::Bits32}) {
            const MsmTable table = table_for(ctx, depth, q);
            for (float light : {0.01f, 0.1f, q == Quantization::Bits16 ? 1.0f : 4.0f}) {
                if (slope > 0.0f && light * 0.5f * 48.0f > 1.5f) continue;
                const Image out = msm_soft(ctx, table, rx, MsmSoftOptions{light, {}, {}});
                for (int i = 0; i < 48 * 40; ++i)
                    ASSERT_EQ(out.at(0, i % 48, i / 48), 1.0f)
                        << backend << " " << to_string(q) << " slope " << slope << " L " << light;
            }
        }
    }
}

// A blocker plane over the whole map: receivers behind it are dark however
// wide the penumbra (clamped to the table's largest window), in front lit;
// to the bias's alpha / 2 (the light it puts behind every receiver).
PN_BACKEND_TEST(MsmSoftTest, CoveredAndUncovered)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Image depth(33, 17, 1);
    depth.fill(0, 0.2f);
    for (Quantization q : {Quantization::Bits16, Quantization::Bits32}) {
        const MsmTable table = table_for(ctx, depth, q);
        const float alpha = default_moment_bias(q);
        for (float z : {0.1f, 0.3f, 0.9f, 1.0f})
            for (float light : {0.02f, 0.5f}) {
                const Image out = msm_soft(ctx, table, testing::receivers_at_depth(33, 17, z), MsmSoftOptions{light});
                for (int i = 0; i < 33 * 17; ++i)
                    ASSERT_NEAR(out.at(0, i % 33, i / 33), z < 0.2f ? 1.0f : alpha / 2, alpha)
                        << backend << " " << to_string(q) << " z " << z << " L " << light;
            }
    }
}

PN_BACKEND_TEST(MsmSoftTest, NeverNaNOnAnything)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> wide(-0.5f, 1.5f);
    const int lanes = testing::backend_lanes(backend);
    for (int w : {1, 7, lanes + 1, 3 * lanes + 1}) {
        for (int kind = 0; kind < 3; ++kind) {
            Image depth = testing::random_depth(w, 5, rng(), kind == 1);
            if (kind == 2)
                for (int i = 0; i < w * 5; ++i) depth.at(0, i % w, i / w) = float(rng() % 2);
            Image rx = testing::receivers_on_texels(w, 5, w, 5, 0.0f, 1.0f, rng());
            for (int i = 0; i < w * 5; ++i) rx.at(2, i % w, i / w) = rng() % 2 ? depth.at(0, i % w, i / w) : wide(rng);
            for (Quantization q : {Quantization::Bits16, Quantization::Bits32})
                for (float light : {0.001f, 0.2f})
                    for (float alpha : {0.0f, 6e-5f, 0.5f})
                        expect_visibility(
                            msm_soft(ctx, table_for(ctx, depth, q), rx, MsmSoftOptions{light, alpha, 0.0f}),
                            backend + " width " + std::to_string(w));
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, MsmSoftTest, ::testing::ValuesIn(backend_names()), backend_test_name);

}  // namespace
}  // namespace penumbra
