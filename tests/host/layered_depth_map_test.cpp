// LayeredDepthMap (Pismo's maps, penumbra/layered_depth_map.h): its invariants
// as typed errors naming the pixel, and the bled and maximum-depth maps
// against brute force: every empty pixel takes the layers of a non-empty pixel
// at the least Euclidean distance, found by scanning every pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/layered_depth_map.h"
#include "support/errors.h"

namespace penumbra {
namespace {

using testing::expect_error;

// A map whose pixel p holds p % 3 layers (none for a third of them) where
// `filled` says so, with depths that name the pixel: 10 p + 1, 10 p + 2.
LayeredDepthMap sparse_map(int w, int h, const std::vector<bool>& filled)
{
    LayeredDepthMapBuilder builder(w, h, MapCamera{});
    for (int p = 0; p < w * h; ++p) {
        std::vector<float> layers;
        if (filled[std::size_t(p)])
            for (int k = 0; k <= p % 2; ++k) layers.push_back(float(10 * p + k + 1));
        builder.add_pixel(layers);
    }
    return builder.build();
}

double nearest_distance_squared(const LayeredDepthMap& map, int x, int y)
{
    double best = std::numeric_limits<double>::infinity();
    for (int j = 0; j < map.height(); ++j)
        for (int i = 0; i < map.width(); ++i)
            if (!map.layers(i, j).empty()) best = std::min(best, double(i - x) * (i - x) + double(j - y) * (j - y));
    return best;
}

// The pixel whose layers `layers` are (sparse_map names each pixel in its depths).
int source_pixel(std::span<const float> layers) { return int(layers[0] - 1) / 10; }

TEST(LayeredDepthMap, BleedingCopiesANearestNonEmptyPixel)
{
    std::mt19937 random(7);
    for (auto [w, h, density] : {std::tuple{1, 1, 1.0}, {7, 3, 0.3}, {17, 5, 0.1}, {16, 16, 0.02}, {33, 9, 0.05},
                                 {40, 40, 0.005}, {5, 31, 0.2}}) {
        std::bernoulli_distribution fill(density);
        std::vector<bool> filled(std::size_t(w * h));
        for (std::size_t p = 0; p < filled.size(); ++p) filled[p] = fill(random);
        filled[std::size_t(w * h / 2)] = true;  // at least one non-empty pixel
        const LayeredDepthMap map = sparse_map(w, h, filled);
        const LayeredDepthMap bled = bleed_empty_pixels(map);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const auto got = bled.layers(x, y);
                ASSERT_FALSE(got.empty()) << w << "x" << h << " (" << x << ", " << y << ")";
                const int source = source_pixel(got);
                const auto expected = map.layers(source % w, source / w);
                ASSERT_TRUE(std::equal(got.begin(), got.end(), expected.begin(), expected.end()));
                if (!map.layers(x, y).empty()) {
                    EXPECT_EQ(source, x + y * w) << "a non-empty pixel keeps its own layers";
                    continue;
                }
                const int sx = source % w, sy = source / w;
                EXPECT_EQ(double(sx - x) * (sx - x) + double(sy - y) * (sy - y), nearest_distance_squared(map, x, y))
                    << w << "x" << h << " (" << x << ", " << y << ") took pixel (" << sx << ", " << sy << ")";
            }
    }
}

TEST(LayeredDepthMap, BleedingAnEmptyMapLeavesItEmpty)
{
    const LayeredDepthMap map = sparse_map(7, 3, std::vector<bool>(21, false));
    EXPECT_EQ(bleed_empty_pixels(map).depths().size(), 0u);
}

TEST(LayeredDepthMap, MaximumDepthMapKeepsTheFarthestLayer)
{
    LayeredDepthMapBuilder builder(3, 1, MapCamera{});
    builder.add_pixel(std::vector<float>{1, 2, 5});
    builder.add_pixel({});
    builder.add_pixel(std::vector<float>{4});
    const LayeredDepthMap farthest = maximum_depth_map(builder.build());
    ASSERT_EQ(farthest.layers(0, 0).size(), 1u);
    EXPECT_EQ(farthest.layers(0, 0)[0], 5.0f);
    EXPECT_TRUE(farthest.layers(1, 0).empty());
    EXPECT_EQ(farthest.layers(2, 0)[0], 4.0f);
    EXPECT_EQ(farthest.max_layers(), 1);
}

TEST(LayeredDepthMap, BadDepthsNameThePixelAndLayer)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const auto& [depths, needle] : std::vector<std::pair<std::vector<float>, std::string>>{
             {{1, nan}, "finite"}, {{-1}, "> 0"}, {{0}, "> 0"}, {{2, 1}, "increase"}, {{2, 2}, "increase"}}) {
        expect_error(
            [&] {
                LayeredDepthMap(2, 1, MapCamera{}, {0, 0, std::uint32_t(depths.size())}, depths);
            },
            ErrorCategory::InvalidData, "layered_depth_map", {"pixel (1, 0)", needle});
    }
}

TEST(LayeredDepthMap, InconsistentStorageAndCamerasAreRefused)
{
    expect_error([] { LayeredDepthMap(2, 2, MapCamera{}, {0, 0, 0}, {}); }, ErrorCategory::InvalidArgument,
                 "layered_depth_map", "offsets");
    expect_error([] { LayeredDepthMap(1, 1, MapCamera{}, {0, 2}, {1}); }, ErrorCategory::InvalidArgument,
                 "layered_depth_map", "offsets");
    expect_error([] { LayeredDepthMap(2, 1, MapCamera{}, {0, 5, 2}, {1, 2}); }, ErrorCategory::InvalidArgument,
                 "layered_depth_map", "decrease");
    MapCamera skewed;
    skewed.down = {0.6, 0.8, 0};
    expect_error([&] { LayeredDepthMap(1, 1, skewed, {0, 0}, {}); }, ErrorCategory::InvalidArgument,
                 "layered_depth_map", "orthonormal");
    MapCamera left_handed;
    left_handed.forward = {0, 0, -1};
    expect_error([&] { LayeredDepthMap(1, 1, left_handed, {0, 0}, {}); }, ErrorCategory::InvalidArgument,
                 "layered_depth_map", "right-handed");
    MapCamera flat;
    flat.tan_half_fov = 0;
    expect_error([&] { LayeredDepthMap(1, 1, flat, {0, 0}, {}); }, ErrorCategory::InvalidArgument,
                 "layered_depth_map", "field of view");
    expect_error([] { LayeredDepthMapBuilder(0, 1, MapCamera{}); }, ErrorCategory::InvalidArgument,
                 "layered_depth_map", "pixel");
    LayeredDepthMapBuilder short_one(2, 1, MapCamera{});
    short_one.add_pixel({});
    expect_error([&] { short_one.build(); }, ErrorCategory::InvalidArgument, "layered_depth_map", "1 of 2");
}

}  // namespace
}  // namespace penumbra
