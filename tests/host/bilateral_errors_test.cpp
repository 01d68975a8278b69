// Bad input to cross_bilateral() (penumbra::Error with a category and a
// message naming the parameter, on every backend) and the `penumbra blur`
// command's contract (exit status 2, one line naming the file, channel or
// option, an existing output left untouched).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "support/bilateral_reference.h"
#include "penumbra/bilateral.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "support/backends.h"

#include "support/cli.h"
#include "support/errors.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;

class BilateralErrorTest : public ::testing::TestWithParam<std::string> {};

// Runs `call`, expecting penumbra::Error of `category` from cross_bilateral
// whose message holds `needle`.
template <class Call>
void expect_error(Call&& call, ErrorCategory category, const std::string& needle)
{
    testing::expect_error(call, category, "cross_bilateral", needle);
}

PN_BACKEND_TEST(BilateralErrorTest, RejectsBadImages)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image guide = testing::structured_guide(16, 9, 1);
    const Image mask = testing::random_mask(16, 9, 1, 2);
    const auto run = [&](const Image& m, const Image& g) { return [&] { cross_bilateral(ctx, m, g); }; };
    expect_error(run(testing::random_mask(15, 9, 1, 2), guide), ErrorCategory::InvalidArgument, "same size");
    expect_error(run(testing::random_mask(16, 10, 1, 2), guide), ErrorCategory::InvalidArgument, "16x9");
    expect_error(run(testing::random_mask(16, 9, 5, 2), guide), ErrorCategory::InvalidArgument, "5 channels");
    expect_error(run(mask, testing::random_mask(16, 9, 2, 3)), ErrorCategory::InvalidArgument,
                 "guide depth must have 1");
    expect_error(run(Image(0, 0, 1), Image(0, 0, 1)), ErrorCategory::InvalidArgument, "empty");

    const Image wrong_normals = testing::random_mask(16, 9, 2, 4);
    expect_error([&] { cross_bilateral(ctx, mask, guide, {}, &wrong_normals); }, ErrorCategory::InvalidArgument,
                 "normals must have 3");
    const Image small_normals = testing::structured_normals(8, 9);
    expect_error([&] { cross_bilateral(ctx, mask, guide, {}, &small_normals); }, ErrorCategory::InvalidArgument,
                 "normals are 8x9");
}

PN_BACKEND_TEST(BilateralErrorTest, RejectsNonFiniteValuesNamingThePixel)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (bool separable : {false, true}) {
        BilateralOptions o;
        o.separable = separable;
        Image guide = testing::structured_guide(19, 7, 1);
        Image mask = testing::random_mask(19, 7, 2, 2);
        Image normals = testing::structured_normals(19, 7);
        guide.at(0, 18, 6) = nan;  // the last pixel: a tail lane of every ISA
        expect_error([&] { cross_bilateral(ctx, mask, guide, o); }, ErrorCategory::InvalidData,
                     "guide depth has a non-finite value (nan) in channel 0 at pixel (18, 6)");
        guide.at(0, 18, 6) = 0.5f;
        mask.at(1, 3, 0) = -inf;
        expect_error([&] { cross_bilateral(ctx, mask, guide, o); }, ErrorCategory::InvalidData,
                     "mask has a non-finite value (-inf) in channel 1 at pixel (3, 0)");
        mask.at(1, 3, 0) = 0.5f;
        normals.at(2, 0, 4) = nan;
        expect_error([&] { cross_bilateral(ctx, mask, guide, o, &normals); }, ErrorCategory::InvalidData,
                     "normals has a non-finite value (nan) in channel 2 at pixel (0, 4)");
    }
}

PN_BACKEND_TEST(BilateralErrorTest, RejectsBadOptions)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image guide = testing::structured_guide(8, 8, 1);
    const Image mask = testing::random_mask(8, 8, 1, 2);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const auto with = [&](auto change) {
        BilateralOptions o;
        change(o);
        return [&, o] { cross_bilateral(ctx, mask, guide, o); };
    };
    expect_error(with([](BilateralOptions& o) { o.radius = -1; }), ErrorCategory::InvalidArgument, "radius");
    expect_error(with([](BilateralOptions& o) { o.radius = 33; }), ErrorCategory::InvalidArgument, "radius");
    expect_error(with([](BilateralOptions& o) { o.radius = 1 << 30; }), ErrorCategory::InvalidArgument, "[0, 32]");
    expect_error(with([](BilateralOptions& o) { o.spatial_sigma = 0.0f; }), ErrorCategory::InvalidArgument,
                 "spatial_sigma");
    expect_error(with([](BilateralOptions& o) { o.spatial_sigma = -1.0f; }), ErrorCategory::InvalidArgument,
                 "spatial_sigma");
    expect_error(with([&](BilateralOptions& o) { o.depth_sigma = nan; }), ErrorCategory::InvalidArgument,
                 "depth_sigma");
    expect_error(with([](BilateralOptions& o) { o.depth_sigma = 0.0f; }), ErrorCategory::InvalidArgument,
                 "depth_sigma");
    expect_error(with([](BilateralOptions& o) { o.normal_sigma = -0.5f; }), ErrorCategory::InvalidArgument,
                 "normal_sigma");
    expect_error(with([](BilateralOptions& o) { o.depth_threshold = -0.1f; }), ErrorCategory::InvalidArgument,
                 "depth_threshold");
    expect_error(with([](BilateralOptions& o) {
                     o.separable = true;
                     o.window = BilateralWindow::Disk;
                 }),
                 ErrorCategory::InvalidArgument, "separable");
}

PN_BACKEND_TEST(BilateralErrorTest, RejectsBadOutput)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image guide = testing::structured_guide(8, 6, 1);
    Image mask = testing::random_mask(8, 6, 2, 2);
    Image wrong_size(8, 5, 2), wrong_channels(8, 6, 1);
    expect_error([&] { cross_bilateral(ctx, mask, guide, {}, wrong_size); }, ErrorCategory::InvalidArgument,
                 "output must be a 2-channel image");
    expect_error([&] { cross_bilateral(ctx, mask, guide, {}, wrong_channels); }, ErrorCategory::InvalidArgument,
                 "output must be a 2-channel image");
    expect_error([&] { cross_bilateral(ctx, mask, guide, {}, mask); }, ErrorCategory::InvalidArgument,
                 "must not be the mask");
}

INSTANTIATE_TEST_SUITE_P(Backends, BilateralErrorTest, ::testing::ValuesIn(backend_names()), backend_test_name);

// ---- penumbra blur -------------------------------------------------------------

class BlurCliTest : public testing::CliFixture {
protected:
    void SetUp() override
    {
        CliFixture::SetUp();
        guide_ = testing::structured_guide(33, 21, 5);
        mask_ = testing::random_mask(33, 21, 2, 6);
        write_exr(path("depth.exr"), guide_, {"Z"});
        write_exr(path("mask.exr"), mask_, {"shadow", "ao"});
    }

    std::string blur(const std::string& extra) const
    {
        return "blur --in " + path("mask.exr") + " --guide " + path("depth.exr") + " --out " + path("out.exr") + " " +
               extra;
    }

    Image guide_, mask_;
};

TEST_F(BlurCliTest, WritesEveryChannelAsTheLibraryFilters)
{
    const testing::ToolRun r =
        run(blur("--radius 3 --spatial-sigma 2 --depth-threshold 0.03 --difference absolute --backend scalar"));
    ASSERT_EQ(r.status, 0) << r.err;
    const Image out = read_exr(path("out.exr"), {"ao", "shadow"});  // the mask's own channel names
    Context ctx(ContextOptions{Backend::Scalar, {}});
    BilateralOptions o;
    o.radius = 3;
    o.spatial_sigma = 2.0f;
    o.range = BilateralRange::Threshold;
    o.depth_threshold = 0.03f;
    o.relative = false;
    const Image expected = cross_bilateral(ctx, read_exr(path("mask.exr"), {"ao", "shadow"}), guide_, o);
    EXPECT_EQ(testing::max_difference(out, expected), 0.0);

    ASSERT_EQ(run(blur("--separable --window square --depth-sigma 0.1")).status, 0);
    ASSERT_EQ(run(blur("--window disk")).status, 0);
    EXPECT_EQ(run("blur --help").status, 0);
}

TEST_F(BlurCliTest, RejectsBadFiles)
{
    write_exr(path("no_z.exr"), guide_, {"depth"});
    expect_bad_input("blur --in " + path("mask.exr") + " --guide " + path("no_z.exr") + " --out " + path("out.exr"),
                     "Z");
    write_exr(path("small.exr"), testing::structured_guide(32, 21, 5), {"Z"});
    expect_bad_input("blur --in " + path("mask.exr") + " --guide " + path("small.exr") + " --out " + path("out.exr"),
                     "same size");
    write_exr(path("five.exr"), testing::random_mask(33, 21, 5, 1), {"A", "B", "C", "D", "E"});
    expect_bad_input("blur --in " + path("five.exr") + " --guide " + path("depth.exr") + " --out " + path("out.exr"),
                     "5 channels");
    Image nan_guide = guide_;
    nan_guide.at(0, 4, 7) = std::nanf("");
    write_exr(path("nan.exr"), nan_guide, {"Z"});
    expect_bad_input("blur --in " + path("mask.exr") + " --guide " + path("nan.exr") + " --out " + path("out.exr"),
                     "nan.exr: channel Z at pixel (4, 7)");
    expect_bad_input("blur --in " + path("missing.exr") + " --guide " + path("depth.exr") + " --out " +
                         path("out.exr"),
                     "missing.exr");
}

TEST_F(BlurCliTest, RejectsBadOptions)
{
    expect_bad_inputs([&](const std::string& options) { return blur(options); },
                      {
                          {"--radius -1", "--radius"},
                          {"--radius 1000", "--radius"},
                          {"--spatial-sigma 0", "--spatial-sigma"},
                          {"--depth-sigma -2", "--depth-sigma"},
                          {"--depth-threshold -1", "--depth-threshold"},
                          {"--depth-sigma 0.1 --depth-threshold 0.1", "--depth-threshold"},
                          {"--difference sideways", "--difference"},
                          {"--window hexagon", "--window"},
                          {"--separable --window disk", "--separable"},
                          {"--backend cuda", "backend"},
                      });
    expect_bad_input("blur --in " + path("mask.exr") + " --out " + path("out.exr"), "--guide");
}

}  // namespace
}  // namespace penumbra
