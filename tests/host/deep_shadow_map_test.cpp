// DeepShadowMap: its invariants (each violation a typed error naming the pixel
// and the vertex), its storage, and deep_visibility against closed forms and
// against the brute-force scan of tests/support/deep_functions.h.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "penumbra/deep_shadow_map.h"
#include "penumbra/error.h"
#include "support/deep_functions.h"

namespace penumbra {
namespace {

// A semi-transparent plane of opacity 0.4 at z = 2, fog from 3 to 5 absorbing
// half, an opaque plane at 6.
const std::vector<float> kZ{2.0f, 2.0f, 3.0f, 5.0f, 6.0f, 6.0f};
const std::vector<float> kT{1.0f, 0.6f, 0.6f, 0.3f, 0.3f, 0.0f};

TEST(DeepShadowMap, VisibilityOfLayersAndFogIsTheClosedForm)
{
    const auto v = [](float z) { return deep_visibility(kZ, kT, z); };
    EXPECT_EQ(v(-1.0f), 1.0f);
    EXPECT_EQ(v(2.0f), 1.0f);  // a surface does not shadow itself
    EXPECT_FLOAT_EQ(v(2.5f), 0.6f);
    EXPECT_FLOAT_EQ(v(3.0f), 0.6f);
    EXPECT_FLOAT_EQ(v(4.0f), 0.45f);  // halfway through the fog
    EXPECT_FLOAT_EQ(v(4.5f), 0.375f);
    EXPECT_FLOAT_EQ(v(6.0f), 0.3f);
    EXPECT_EQ(v(6.5f), 0.0f);
    EXPECT_EQ(v(1e30f), 0.0f);
    EXPECT_EQ(deep_visibility({}, {}, 3.0f), 1.0f);
}

TEST(DeepShadowMap, VisibilityAgreesWithABruteForceScan)
{
    std::mt19937 rng(3);
    for (std::uint32_t seed = 1; seed <= 50; ++seed) {
        const testing::Function f = testing::random_function(seed, 30);
        std::uniform_real_distribution<float> depth(0.0f, 14.0f);
        std::vector<float> probes(f.z);
        for (int k = 0; k < 200; ++k) probes.push_back(depth(rng));
        for (const float d : probes)
            EXPECT_NEAR(deep_visibility(f.z, f.t, d), double(testing::brute_visibility(f, d, -1)), 1e-6)
                << "seed " << seed << " depth " << d;
    }
}

TEST(DeepShadowMap, StoresOffsetsAndPlanarVertices)
{
    DeepShadowMapBuilder builder(3, 2);
    for (int p = 0; p < 6; ++p) {
        if (p == 4) builder.add_pixel(kZ, kT);
        else if (p == 1) builder.add_pixel(std::vector<float>{1.0f, 4.0f}, std::vector<float>{1.0f, 0.5f});
        else builder.add_pixel({}, {});
    }
    const DeepShadowMap map = builder.build();
    EXPECT_EQ(map.offsets(), (std::vector<std::uint32_t>{0, 0, 2, 2, 2, 8, 8}));
    EXPECT_EQ(map.vertex_count(), 8u);
    EXPECT_EQ(map.bytes(), 7u * 4u + 8u * 8u);
    EXPECT_EQ(map.depths(1, 1).size(), 6u);
    EXPECT_FLOAT_EQ(map.visibility(1, 1, 4.0f), 0.45f);
    EXPECT_FLOAT_EQ(map.visibility(1, 0, 2.5f), 0.75f);
    EXPECT_EQ(map.visibility(0, 0, 100.0f), 1.0f);
}

// Each broken invariant: Error(InvalidData) naming the pixel and the vertex.
TEST(DeepShadowMap, RefusesInvalidFunctionsNamingPixelAndVertex)
{
    struct Case {
        std::vector<float> z, t;
        const char* needle;
    };
    const Case cases[] = {
        {{1.0f}, {1.0f}, "no vertices or at least two"},
        {{1.0f, 0.5f}, {1.0f, 0.5f}, "depths decrease"},
        {{1.0f, NAN}, {1.0f, 0.5f}, "not finite"},
        {{1.0f, INFINITY}, {1.0f, 0.5f}, "not finite"},
        {{1.0f, 2.0f}, {0.9f, 0.5f}, "must be 1"},
        {{1.0f, 2.0f}, {1.0f, NAN}, "not in [0, 1]"},
        {{1.0f, 2.0f}, {1.0f, -0.1f}, "not in [0, 1]"},
        {{1.0f, 2.0f, 3.0f}, {1.0f, 0.5f, 0.7f}, "increases"},
    };
    for (const Case& c : cases) {
        DeepShadowMapBuilder builder(2, 2);
        for (int p = 0; p < 3; ++p) builder.add_pixel({}, {});
        builder.add_pixel(c.z, c.t);  // pixel (1, 1)
        try {
            builder.build();
            ADD_FAILURE() << c.needle;
        } catch (const Error& e) {
            EXPECT_EQ(e.category(), ErrorCategory::InvalidData);
            EXPECT_NE(e.message().find(c.needle), std::string::npos) << e.message();
            EXPECT_NE(e.message().find("pixel (1, 1), vertex"), std::string::npos) << e.message();
            ASSERT_TRUE(e.pixel().has_value());
            EXPECT_EQ(e.pixel()->x, 1);
            EXPECT_EQ(e.pixel()->y, 1);
        }
    }
}

TEST(DeepShadowMap, RefusesInconsistentArrays)
{
    EXPECT_THROW(DeepShadowMap(0, 1, {0}, {}, {}), Error);
    EXPECT_THROW(DeepShadowMap(1, 1, {0}, {}, {}), Error);                     // offsets too short
    EXPECT_THROW(DeepShadowMap(1, 1, {0, 2}, {1.0f, 2.0f}, {1.0f}), Error);    // one t short
    EXPECT_THROW(DeepShadowMap(2, 1, {0, 3, 2}, {1, 2}, {1, 1}), Error);       // decreasing offsets
    EXPECT_THROW(DeepShadowMap(1, 1, {1, 2}, {1, 2}, {1, 1}), Error);          // not starting at 0
    DeepShadowMapBuilder builder(1, 2);
    builder.add_pixel({}, {});
    EXPECT_THROW(builder.build(), Error);  // a pixel missing
    builder.add_pixel({}, {});
    EXPECT_THROW(builder.add_pixel({}, {}), Error);  // one too many
    EXPECT_NO_THROW(builder.build());
}

}  // namespace
}  // namespace penumbra
