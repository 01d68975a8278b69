// Metrics on hand-made images whose answers are worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "penumbra/error.h"
#include "penumbra/reference/metrics.h"

namespace penumbra::reference {
namespace {

Image row_image(const std::vector<float>& values)
{
    Image image(int(values.size()), 1, 1);
    for (int i = 0; i < int(values.size()); ++i) image.at(0, i, 0) = values[i];
    return image;
}

TEST(Metrics, RmseOfKnownDifferences)
{
    const Image truth = row_image({0, 0.5f, 1, 1});
    const Image estimate = row_image({0.5f, 0.5f, 0.5f, 1});
    // Squared errors 0.25, 0, 0.25, 0: mean 0.125.
    EXPECT_NEAR(rmse(estimate, truth), std::sqrt(0.125), 1e-12);
    EXPECT_EQ(rmse(truth, truth), 0.0);
    const Image mask = row_image({1, 1, 0, 0});
    EXPECT_NEAR(rmse(estimate, truth, &mask), std::sqrt(0.125), 1e-12);  // 0.25 and 0 over 2
}

TEST(Metrics, Percentile99IsTheNearestRank)
{
    // 200 pixels with errors 0.001 * k, k = 1..200: rank ceil(0.99 * 200) = 198.
    std::vector<float> zeros(200, 0), errors(200);
    for (int k = 0; k < 200; ++k) errors[k] = 0.001f * float(200 - k);
    EXPECT_FLOAT_EQ(float(p99_abs_error(row_image(errors), row_image(zeros))), 0.198f);
    // Below 100 pixels the 99th percentile is the largest error.
    EXPECT_FLOAT_EQ(float(p99_abs_error(row_image({0.1f, -0.3f, 0.2f}), row_image({0, 0, 0}))), 0.3f);
}

TEST(Metrics, LightLeakingCountsOverestimatesInTheDark)
{
    const Image truth = row_image({0, 0.02f, 0.04f, 0.5f, 1});
    const Image estimate = row_image({0.3f, 0, 0.14f, 0.9f, 1});
    // Dark pixels (truth < 0.05): overestimates 0.3, 0 (an underestimate is clamped), 0.1.
    EXPECT_NEAR(light_leaking(estimate, truth), (0.3 + 0 + 0.1) / 3, 1e-7);
}

TEST(Metrics, OverDarkeningCountsUnderestimatesInTheLight)
{
    const Image truth = row_image({1, 0.97f, 0.96f, 0.5f, 0});
    const Image estimate = row_image({0.6f, 1, 0.76f, 0, 0});
    // Lit pixels (truth > 0.95): underestimates 0.4, 0 (clamped), 0.2.
    EXPECT_NEAR(over_darkening(estimate, truth), (0.4 + 0 + 0.2) / 3, 1e-7);
}

TEST(Metrics, NoQualifyingPixelGivesZero)
{
    const Image grey = row_image({0.5f, 0.5f});
    const Image zero_mask = row_image({0, 0});
    EXPECT_EQ(light_leaking(grey, grey), 0.0);
    EXPECT_EQ(over_darkening(grey, grey), 0.0);
    EXPECT_EQ(rmse(grey, row_image({0, 1}), &zero_mask), 0.0);
    EXPECT_EQ(p99_abs_error(grey, row_image({0, 1}), &zero_mask), 0.0);
}

TEST(Metrics, FlickerIsTheSpreadOfTheErrorOverFrames)
{
    // Pixel 0: errors +0.1, -0.1 (std 0.1). Pixel 1: the truth moves and the
    // estimate follows it exactly (std 0). Mean 0.05.
    const std::vector<Image> truths = {row_image({0.5f, 0.2f}), row_image({0.5f, 0.8f})};
    const std::vector<Image> estimates = {row_image({0.6f, 0.2f}), row_image({0.4f, 0.8f})};
    EXPECT_NEAR(flicker(estimates, truths), 0.05, 1e-7);
    const Image only_second = row_image({0, 1});
    EXPECT_NEAR(flicker(estimates, truths, &only_second), 0, 1e-7);
    // A constant bias does not flicker.
    const std::vector<Image> biased = {row_image({0.7f, 0.5f}), row_image({0.7f, 1.1f})};
    EXPECT_NEAR(flicker(biased, truths), 0, 1e-7);
}

TEST(Metrics, BadInputsAreErrors)
{
    const Image a = row_image({0, 1});
    const Image longer = row_image({0, 1, 0});
    EXPECT_THROW(rmse(a, longer), Error);
    EXPECT_THROW(rmse(Image(), Image()), Error);
    EXPECT_THROW(light_leaking(Image(2, 1, 2), a), Error);
    EXPECT_THROW(over_darkening(a, a, &longer), Error);
    const Image nan = row_image({std::numeric_limits<float>::quiet_NaN(), 0});
    try {
        p99_abs_error(nan, a);
        ADD_FAILURE() << "NaN accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.category(), ErrorCategory::InvalidData);
    }
    EXPECT_THROW(flicker({a}, {a}), Error);
    EXPECT_THROW(flicker({a, a}, {a}), Error);
    EXPECT_THROW(flicker({a, longer}, {a, longer}), Error);
    try {
        rmse(a, longer);
    } catch (const Error& e) {
        EXPECT_EQ(e.category(), ErrorCategory::InvalidArgument);
        EXPECT_NE(std::string(e.what()).find("2x1x1 but the truth is 3x1x1"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace penumbra::reference
