// Every backend against the scalar one (the dialect's oracle) for MSM, moment
// soft shadows and EVSM, on one and the same table per storage, and end to
// end (each backend building its own table).
//
// Stated tolerances, on the same table:
//  - msm, msm-soft: the lookups run the same operations in the same order
//    everywhere with contraction off and correctly rounded division and
//    square root, so SIMD must match scalar to the bit and OpenCL (PoCL) to
//    1e-5, as VSM's (tests/kernels/chebyshev_test.cpp);
//  - evsm: the warp's exp() differs by an ulp or two between xsimd, libm and
//    OpenCL, which the bound can amplify where the receiver's warped depth
//    nears the window mean: 2e-5 (measured: 6.7e-6).
// End to end, exact tables are built bit-identically on every backend (the
// same integers), so the same limits hold; float tables are summed in other
// orders and differ by their rounding: printed, not asserted (that error is
// the float table's, docs/moment_table.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "penumbra/moments.h"
#include "support/backends.h"
#include "support/maps.h"

namespace penumbra {
namespace {

using testing::backend_test_name;

using testing::Difference;
using testing::difference;

Image cross_receivers(const Image& depth, std::uint32_t seed)
{
    Image rx(67, 41, 3);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uv(-0.1f, 1.1f), z(-0.05f, 1.05f), near(-0.02f, 0.02f);
    for (int y = 0; y < 41; ++y)
        for (int x = 0; x < 67; ++x) {
            const float u = uv(rng), v = uv(rng);
            rx.at(0, x, y) = u;
            rx.at(1, x, y) = v;
            const int tx = std::clamp(int(u * depth.width()), 0, depth.width() - 1);
            const int ty = std::clamp(int(v * depth.height()), 0, depth.height() - 1);
            rx.at(2, x, y) = rng() % 2 ? z(rng) : depth.at(0, tx, ty) + near(rng);
        }
    return rx;
}

// Blocks at a few depths over a noisy ground: every path of the kernels runs.
Image cross_depth()
{
    Image depth(131, 29, 1);
    std::mt19937 rng(41);
    std::uniform_real_distribution<float> noise(0.0f, 0.01f);
    for (int y = 0; y < 29; ++y)
        for (int x = 0; x < 131; ++x) {
            const int block = (x / 9 + y / 7) % 4;
            depth.at(0, x, y) = block == 0 ? 0.8f + noise(rng) : block == 1 ? 0.3f : block == 2 ? 0.55f : float(x % 2);
        }
    return depth;
}

class MomentsCrossBackendTest : public ::testing::TestWithParam<std::string> {};

PN_BACKEND_TEST(MomentsCrossBackendTest, AgreesWithScalar)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Context& scalar = testing::scalar_oracle(backend);
    const Image depth = cross_depth();
    const Image rx = cross_receivers(depth, 43);
    const bool simd = backend != "opencl";
    using Run = std::function<Image(Context&, Context&)>;  // (lookup context, table context)
    struct Case {
        std::string name;
        Run run;
        double tolerance;
        bool bit_identical;
    };
    std::vector<Case> cases;
    for (Quantization q : {Quantization::Bits16, Quantization::Bits32}) {
        const Precision p = q == Quantization::Bits16 ? Precision::Exact : Precision::Float;
        const std::string tag = std::string(" ").append(to_string(q)).append("-bit");  // GCC 12 -Wrestrict, bug 105329
        for (int radius : {1, 6})
            cases.push_back({"msm r=" + std::to_string(radius) + tag,
                             [=](Context& c, Context& t) {
                                 return msm(c, build_msm_table(t, depth, q, p), rx, MsmOptions{radius, {}, {}});
                             },
                             1e-5, true});
        for (float light : {0.03f, 0.15f})
            cases.push_back({"msm-soft L=" + std::to_string(light) + tag,
                             [=](Context& c, Context& t) {
                                 return msm_soft(c, build_msm_table(t, depth, q, p), rx, MsmSoftOptions{light});
                             },
                             1e-5, true});
        for (int channels : {2, 4})
            cases.push_back({"evsm" + std::to_string(channels) + tag,
                             [=](Context& c, Context& t) {
                                 return evsm(c, build_evsm_table(t, depth, EvsmWarp{channels, {}, {}, q}, p), rx,
                                             EvsmOptions{2, EvsmOptions{}.min_variance, 0.1f});
                             },
                             2e-5, false});
    }
    for (const Case& c : cases) {
        const Image oracle = c.run(scalar, scalar);
        const Difference lookup = difference(c.run(ctx, scalar), oracle);
        const Difference end_to_end = difference(c.run(ctx, ctx), oracle);
        std::printf("[ cross ] %s %s: same table max |diff| %.3g (%d of %d differ); own table %.3g (%d)\n",
                    backend.c_str(), c.name.c_str(), lookup.max, lookup.differing, 67 * 41, end_to_end.max,
                    end_to_end.differing);
        EXPECT_LE(lookup.max, c.tolerance) << c.name;
        if (simd && c.bit_identical) {
            EXPECT_EQ(lookup.differing, 0) << c.name << ": not bit-identical to scalar";
        }
        if (c.name.find("16-bit") != std::string::npos) {
            EXPECT_LE(end_to_end.max, c.tolerance) << c.name << ": exact tables build identically";
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, MomentsCrossBackendTest, ::testing::ValuesIn(testing::non_scalar_backends()),
                         backend_test_name);

}  // namespace
}  // namespace penumbra
