// Images allocated without a zero fill (Image::Uninitialized, issue 10 item 10):
// their row padding is zero, and every method that returns such an image
// writes every pixel. The second claim is tested through each method's
// overload that writes into a caller's image: filled with NaN first, the
// output must come back finite everywhere and equal to the returned image.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "penumbra/chebyshev.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"
#include "penumbra/moments.h"
#include "support/backends.h"
#include "support/maps.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;

TEST(UninitializedImage, HasTheShapeOfAZeroFilledOneAndZeroPadding)
{
    for (const int width : {1, 7, 15, 16, 17, 33})
        for (const int height : {1, 3})
            for (const int channels : {1, 3}) {
                const Image zeroed(width, height, channels);
                const Image image(width, height, channels, Image::Uninitialized{});
                ASSERT_EQ(image.width(), width);
                ASSERT_EQ(image.height(), height);
                ASSERT_EQ(image.channels(), channels);
                ASSERT_EQ(image.pitch(), zeroed.pitch());
                ASSERT_EQ(image.plane_pitch(), zeroed.plane_pitch());
                for (int c = 0; c < channels; ++c)
                    for (int y = 0; y < height; ++y)
                        for (int x = width; x < image.pitch(); ++x)
                            ASSERT_EQ(image.row(c, y)[x], 0.0f) << width << "x" << height << " c" << c << " x" << x;
            }
}

Image random_depths(int width, int height, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> depth(0.2f, 0.8f);
    Image map(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) map.at(0, x, y) = depth(rng);
    return map;
}

// u, v across the map (a little beyond its edges), z around the depths.
Image receivers_around_the_map(int width, int height, unsigned seed)
{
    return testing::scattered_receivers(width, height, -0.05f, 1.05f, 0.1f, 0.9f, seed);
}

// Writes a method's output into `out`; the allocating overload is the reference.
using IntoOutput = std::function<void(Context&, const Image& map, const Image& receivers, Image& out)>;
using Returning = std::function<Image(Context&, const Image& map, const Image& receivers)>;

struct MethodPair {
    const char* name;
    IntoOutput into;
    Returning returning;
};

std::vector<MethodPair> method_pairs()
{
    const auto vsm_table = [](Context& c, const Image& m) { return build_moment_table(c, m, 2); };
    return {
        {"vsm", [=](Context& c, const Image& m, const Image& r, Image& o) { vsm(c, vsm_table(c, m), r, VsmOptions{3}, o); },
         [=](Context& c, const Image& m, const Image& r) { return vsm(c, vsm_table(c, m), r, VsmOptions{3}); }},
        {"vssm", [=](Context& c, const Image& m, const Image& r, Image& o) { vssm(c, vsm_table(c, m), r, VssmOptions{}, o); },
         [=](Context& c, const Image& m, const Image& r) { return vssm(c, vsm_table(c, m), r, VssmOptions{}); }},
        {"msm", [](Context& c, const Image& m, const Image& r, Image& o) { msm(c, build_msm_table(c, m), r, MsmOptions{}, o); },
         [](Context& c, const Image& m, const Image& r) { return msm(c, build_msm_table(c, m), r, MsmOptions{}); }},
        {"msm_soft",
         [](Context& c, const Image& m, const Image& r, Image& o) { msm_soft(c, build_msm_table(c, m), r, MsmSoftOptions{}, o); },
         [](Context& c, const Image& m, const Image& r) { return msm_soft(c, build_msm_table(c, m), r, MsmSoftOptions{}); }},
        {"evsm", [](Context& c, const Image& m, const Image& r, Image& o) { evsm(c, build_evsm_table(c, m), r, EvsmOptions{}, o); },
         [](Context& c, const Image& m, const Image& r) { return evsm(c, build_evsm_table(c, m), r, EvsmOptions{}); }},
    };
}

class UninitializedOutput : public ::testing::TestWithParam<std::string> {};

PN_BACKEND_TEST(UninitializedOutput, EveryMethodWritesEveryPixel)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image map = random_depths(23, 19, 7);
    for (const int width : testing::lane_edge_widths()) {
        const Image receivers = receivers_around_the_map(width, 3, unsigned(width));
        for (const MethodPair& method : method_pairs()) {
            Image out(width, 3, 1);
            out.fill(0, std::nanf(""));
            method.into(ctx, map, receivers, out);
            const Image returned = method.returning(ctx, map, receivers);
            for (int y = 0; y < 3; ++y)
                for (int x = 0; x < width; ++x) {
                    ASSERT_TRUE(std::isfinite(out.at(0, x, y))) << method.name << " width " << width << " at " << x << "," << y;
                    ASSERT_EQ(returned.at(0, x, y), out.at(0, x, y)) << method.name << " width " << width << " at " << x << "," << y;
                }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, UninitializedOutput, ::testing::ValuesIn(backend_names()), backend_test_name);

}  // namespace
}  // namespace penumbra
