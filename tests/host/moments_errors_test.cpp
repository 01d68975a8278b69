// Bad input to the moment family (host/src/moments.cpp): penumbra::Error with
// its category, the operation and a message naming the parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "penumbra/error.h"
#include "penumbra/moments.h"
#include "support/errors.h"
#include "support/maps.h"

namespace penumbra {
namespace {

using testing::expect_error;

constexpr ErrorCategory kArg = ErrorCategory::InvalidArgument;
constexpr ErrorCategory kData = ErrorCategory::InvalidData;

class MomentsErrors : public ::testing::Test {
protected:
    Context ctx{ContextOptions{Backend::Scalar, {}}};
    Image depth = testing::random_depth(9, 8, 1);
    Image rx = testing::receivers_at_depth(9, 8, 0.5f);
};

TEST_F(MomentsErrors, TablesRejectBadMapsAndStorage)
{
    expect_error([&] { build_msm_table(ctx, Image(9, 8, 2)); }, kArg, "build_msm_table", "one channel");
    expect_error([&] { build_evsm_table(ctx, Image(9, 8, 3)); }, kArg, "build_evsm_table", "one channel");
    expect_error([&] { build_msm_table(ctx, Image(0, 8, 1)); }, kArg, "build_msm_table", "empty");
    Image nan = depth, far = depth, negative = depth;
    nan.at(0, 2, 3) = NAN;
    far.at(0, 4, 5) = 1.5f;
    negative.at(0, 1, 1) = -0.25f;
    for (Quantization q : {Quantization::Bits16, Quantization::Bits32}) {
        const Precision p = q == Quantization::Bits16 ? Precision::Exact : Precision::Float;
        expect_error([&] { build_msm_table(ctx, nan, q, p); }, kData, "build_msm_table", "non-finite");
        expect_error([&] { build_msm_table(ctx, far, q, p); }, kData, "build_msm_table", "at (4, 5) is outside [0, 1]");
        expect_error([&] { build_evsm_table(ctx, negative, EvsmWarp{4, {}, {}, q}, p); }, kData, "build_evsm_table",
                     "at (1, 1) is outside [0, 1]");
    }
    // 32-bit floats cannot be summed exactly in 16-bit steps.
    expect_error([&] { build_msm_table(ctx, depth, Quantization::Bits32, Precision::Exact); }, kArg,
                 "build_msm_table", "quantization 32");
    expect_error([&] { build_evsm_table(ctx, depth, EvsmWarp{4, {}, {}, Quantization::Bits32}, Precision::Exact); },
                 kArg, "build_evsm_table", "quantization 32");
    expect_error([&] { build_evsm_table(ctx, depth, EvsmWarp{3}); }, kArg, "build_evsm_table", "channels must be 2");
}

TEST_F(MomentsErrors, ExponentsBeyondTheStorageLimit)
{
    auto warp = [](int channels, float p, float n, Quantization q) {
        EvsmWarp w;
        w.channels = channels;
        w.positive = p;
        w.negative = n;
        w.quantization = q;
        return w;
    };
    const Quantization b16 = Quantization::Bits16, b32 = Quantization::Bits32;
    expect_error([&] { build_evsm_table(ctx, depth, warp(4, 5.6f, 5.0f, b16)); }, kArg, "build_evsm_table",
                 "positive exponent 5.6");
    expect_error([&] { build_evsm_table(ctx, depth, warp(4, 5.0f, 6.0f, b16)); }, kArg, "build_evsm_table",
                 "negative exponent 6");
    expect_error([&] { build_evsm_table(ctx, depth, warp(2, 42.5f, 5.0f, b32), Precision::Float); }, kArg,
                 "build_evsm_table", "exceeds 42");
    for (float bad : {0.0f, -1.0f, NAN, INFINITY})
        expect_error([&] { build_evsm_table(ctx, depth, warp(4, bad, 5.0f, b32), Precision::Float); }, kArg,
                     "build_evsm_table", "positive exponent");
    // The limits themselves pass; EVSM2 ignores the negative exponent.
    EXPECT_NO_THROW(build_evsm_table(ctx, depth, warp(4, kEvsmMaxExponent16, kEvsmMaxExponent16, b16)));
    EXPECT_NO_THROW(build_evsm_table(ctx, depth, warp(4, 42.0f, 42.0f, b32), Precision::Float));
    EXPECT_NO_THROW(build_evsm_table(ctx, depth, warp(2, 5.0f, 1e9f, b16)));
}

TEST_F(MomentsErrors, LookupsRejectBadReceiversTablesAndBiases)
{
    const MsmTable table = build_msm_table(ctx, depth);
    const EvsmTable warped = build_evsm_table(ctx, depth);
    // Receivers: channel count, emptiness, non-finite values.
    for (int channels : {1, 2, 4}) {
        const Image bad(9, 8, channels);
        expect_error([&] { msm(ctx, table, bad); }, kArg, "msm", "3 channels");
        expect_error([&] { msm_soft(ctx, table, bad); }, kArg, "msm_soft", "3 channels");
        expect_error([&] { evsm(ctx, warped, bad); }, kArg, "evsm", "3 channels");
    }
    expect_error([&] { msm(ctx, table, Image(0, 4, 3)); }, kArg, "msm", "receivers image is empty");
    Image nan_rx = rx;
    nan_rx.at(2, 3, 4) = NAN;
    expect_error([&] { msm(ctx, table, nan_rx); }, kData, "msm", "receivers image has a non-finite value");
    expect_error([&] { msm_soft(ctx, table, nan_rx); }, kData, "msm_soft", "non-finite");
    expect_error([&] { evsm(ctx, warped, nan_rx); }, kData, "evsm", "non-finite");
    // Tables: empty, wrong channel count.
    expect_error([&] { msm(ctx, MsmTable{}, rx); }, kArg, "msm", "table is empty");
    MsmTable two;
    two.sums = build_moment_table(ctx, depth, 2, Precision::Float);
    expect_error([&] { msm(ctx, two, rx); }, kArg, "msm", "has 2 channels, this method reads 4");
    EvsmTable mismatched = warped;
    mismatched.channels = 2;
    expect_error([&] { evsm(ctx, mismatched, rx); }, kArg, "evsm", "has 4 channels, this method reads 2");
    // Biases: negative, >= 1, NaN.
    for (float bad : {-1e-6f, -0.5f, 1.0f, 1.5f, NAN}) {
        expect_error([&] { msm(ctx, table, rx, MsmOptions{2, bad, {}}); }, kArg, "msm",
                     "moment-bias must be in [0, 1)");
        expect_error([&] { msm(ctx, table, rx, MsmOptions{2, {}, bad}); }, kArg, "msm", "depth-bias must be in [0, 1)");
        expect_error([&] { msm_soft(ctx, table, rx, MsmSoftOptions{0.02f, bad, {}}); }, kArg, "msm_soft",
                     "moment-bias");
        expect_error([&] { evsm(ctx, warped, rx, EvsmOptions{2, 2e-5f, 0.0f, bad}); }, kArg, "evsm", "depth-bias");
    }
    EXPECT_NO_THROW(msm(ctx, table, rx, MsmOptions{2, 0.0f, 0.0f}));
    EXPECT_NO_THROW(msm(ctx, table, rx, MsmOptions{2, 0.999f, 0.999f}));
    // Windows an exact table cannot sum exactly; shapes of the other options.
    expect_error([&] { msm(ctx, table, rx, MsmOptions{128}); }, kArg, "msm", "radius 128 exceeds 127");
    expect_error([&] { msm(ctx, table, rx, MsmOptions{-1}); }, kArg, "msm", "radius must be >= 0");
    expect_error([&] { evsm(ctx, warped, rx, EvsmOptions{128}); }, kArg, "evsm", "radius 128 exceeds 127");
    expect_error([&] { msm_soft(ctx, table, rx, MsmSoftOptions{0.0f}); }, kArg, "msm_soft", "light-size must be > 0");
    for (float bad : {-0.1f, 16.5f, NAN}) {
        expect_error([&] { msm_soft(ctx, table, rx, MsmSoftOptions{0.02f, {}, {}, bad}); }, kArg, "msm_soft",
                     "plane-bias must be in [0, 16]");
        expect_error([&] { msm_soft(ctx, table, rx, MsmSoftOptions{0.02f, {}, {}, 1.0f, bad}); }, kArg, "msm_soft",
                     "plane-bias-max must be in [0, 1]");
    }
    // The plane from channels the receivers do not have (u, v, z only).
    expect_error([&] { msm_soft(ctx, table, rx, MsmSoftOptions{0.02f, {}, {}, 1.0f, 0.02f, DerivativeSource::Channels}); },
                 kArg, "msm_soft", "receivers must have 5 channels (u, v, z, dzdu, dzdv), got 3");
    Image big_depth(600, 4, 1);
    const MsmTable big = build_msm_table(ctx, big_depth);
    expect_error([&] { msm_soft(ctx, big, testing::receivers_at_depth(600, 4, 0.5f), MsmSoftOptions{0.5f}); }, kArg,
                 "msm_soft", "blocker search of 300 texels");
    expect_error([&] { evsm(ctx, warped, rx, EvsmOptions{2, -1.0f}); }, kArg, "evsm", "min-variance");
    expect_error([&] { evsm(ctx, warped, rx, EvsmOptions{2, 2e-5f, 1.0f}); }, kArg, "evsm", "bleed");
    Image wrong_out(9, 8, 2);
    expect_error([&] { msm(ctx, table, rx, MsmOptions{}, wrong_out); }, kArg, "msm", "1-channel image");
}

TEST(MomentsQuantization, ParsesSixteenAndThirtyTwo)
{
    EXPECT_EQ(parse_quantization("16"), Quantization::Bits16);
    EXPECT_EQ(parse_quantization("32"), Quantization::Bits32);
    expect_error([] { parse_quantization("8"); }, kArg, "quantize", "'8' is not none, 16 or 32");
}

}  // namespace
}  // namespace penumbra
