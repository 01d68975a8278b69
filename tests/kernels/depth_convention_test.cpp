// Depth conventions (kernels/depth_convention.h, penumbra/depth_convention.h)
// on every backend: the tables hold the float64 reference conversion of the
// stored values; every method that reads a shadow map, on a map and
// receivers written in each convention, gives the visibility of the
// normalised map the convention's float32 storage holds (the kernels'
// conversion is the only difference) and, within the storage's measured
// error, of the original normalised map; bad conventions and maps are typed
// errors. Odd sizes: 1x1, 7x3, widths 15, 16, 17 around the lane counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "penumbra/device_image.h"
#include "penumbra/error.h"
#include "penumbra/methods.h"
#include "support/backends.h"
#include "support/depth_conventions.h"
#include "support/maps.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;
using testing::convention_of;
using testing::kAllConventions;

class DepthConventions : public ::testing::TestWithParam<std::string> {};

// The kernels convert in float: a few roundings of relative 2^-24 each (the
// rational forms add positive terms only), 4 ulps of l <= 1 at most:
// 2.4e-7; the exact table adds its own rounding (2^-33).
constexpr double kConversionTolerance = 4.0 * 0x1p-24 + 0x1p-33;

std::vector<std::pair<std::string, std::string>> convention_options(const DepthConvention& c)
{
    if (c.kind == DepthConventionKind::Normalized) return {};
    return {{"depth-convention", to_string(c.kind)}, {"near", "0.5"}, {"far", "50"}};
}

PN_BACKEND_TEST(DepthConventions, TableHoldsTheConvertedDepth)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image normalized = testing::random_depth(37, 5, 7);
    for (DepthConventionKind kind : kAllConventions) {
        const DepthConvention c = convention_of(kind);
        const Image stored = testing::in_convention(normalized, 0, c);
        for (int moments : {2, 4}) {
            const MomentTable table = build_moment_table(ctx, stored, moments, Precision::Exact, c);
            for (int y = 0; y < stored.height(); ++y)
                for (int x = 0; x < stored.width(); ++x) {
                    const double l = testing::normalized_from_stored(stored.at(0, x, y), c);
                    ASSERT_NEAR(table.box_sum(1, x, x + 1, y, y + 1), l, kConversionTolerance)
                        << to_string(kind) << " moments " << moments << " at " << x << ", " << y;
                    ASSERT_NEAR(table.box_sum(2, x, x + 1, y, y + 1), l * l, 2.0 * kConversionTolerance)
                        << to_string(kind) << " moments " << moments << " at " << x << ", " << y;
                }
        }
    }
}

// Each method of a shadow map, once with a table and once with the direct
// window sums where it has both (radius 0 or 1: kVsmDirectMaxRadius, ...).
struct MethodRun {
    const char* method;
    std::vector<std::pair<std::string, std::string>> options;
};
const std::vector<MethodRun> kRuns = {
    {"vsm", {}},          {"vsm", {{"radius", "0"}}},
    {"vssm", {}},         {"msm", {}},
    {"msm", {{"radius", "1"}}}, {"msm", {{"quantize", "16"}}},
    {"msm-soft", {}},     {"msm-soft", {{"plane-bias", "1"}}},
    {"evsm2", {}},        {"evsm4", {}},
    {"evsm4", {{"radius", "0"}}}, {"pcf", {}},
    {"pcf", {{"bias-mode", "receiver-plane"}}}, {"pcf-gauss", {}},
    {"pcf-disc", {{"bias-mode", "slope"}}}, {"pcss", {}},
    {"burley", {}},
};

Image run_method(Context& ctx, const MethodRun& run, const DepthConvention& c, const Image& map, const Image& rx)
{
    auto options = run.options;
    const auto extra = convention_options(c);
    options.insert(options.end(), extra.begin(), extra.end());
    const Method& m = find_method(run.method);
    return m.run(ctx, map, rx, parse_method_settings(m, options));
}

std::string label(const MethodRun& run, DepthConventionKind kind, const Image& rx)
{
    std::string text = std::string(run.method);
    for (const auto& [name, value] : run.options) text += " --" + name + " " + value;
    return text + ", " + to_string(kind) + ", " + std::to_string(rx.width()) + "x" + std::to_string(rx.height());
}

// Maps and receivers of odd sizes: (map, receivers) pairs.
std::vector<std::pair<Image, Image>> odd_inputs()
{
    std::vector<std::pair<Image, Image>> inputs;
    inputs.emplace_back(testing::random_depth(1, 1, 3), testing::receivers_on_texels(1, 1, 1, 1, 0.0f, 1.0f, 4));
    inputs.emplace_back(testing::random_depth(7, 3, 5), testing::receivers_on_texels(7, 3, 7, 3, 0.0f, 1.0f, 6));
    for (int width : {15, 16, 17})
        inputs.emplace_back(testing::random_depth(33, 21, 8),
                            testing::scattered_receivers(width, 3, -0.05f, 1.05f, 0.0f, 1.0f, 9 + width));
    return inputs;
}

// The kernels' conversion against the float64 reference's: the same
// stored inputs, shaded in their convention and, converted back to
// normalised depth in double (stored float32), in the default one. The
// inputs then differ by the conversions' roundings (kConversionTolerance);
// a Chebyshev bound's slope is at most 0.65 / sqrt(min_variance) = 145 per
// unit of depth, so moment methods move by < 4e-5; MSM's four-moment bound
// and the blocker searches are steeper, and a percentage-closer tap flips
// where a depth lies within the roundings of its reference (none here).
// One more difference: a bias reading the receiver's plane by finite
// differences takes them of the stored z, scaled by dl/dz at the receiver
// (kernels/depth_convention.h): the secant of a hyperbola against the
// normalised run's secant of l, equal to first order. On scattered
// receivers (neighbours far apart) a tap may flip there: at most one tap
// (1/25) on one receiver in 20.
int flipped(const Image& a, const Image& b)
{
    int count = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) count += std::abs(a.at(0, x, y) - b.at(0, x, y)) > 1e-4f;
    return count;
}

bool reads_differences(const MethodRun& run)
{
    for (const auto& [name, value] : run.options)
        if (name == "bias-mode" || name == "plane-bias") return true;
    return false;
}

PN_BACKEND_TEST(DepthConventions, EachMethodShadesItsStoredMapAsTheNormalisedOne)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const auto& [map, rx] : odd_inputs())
        for (DepthConventionKind kind : kAllConventions) {
            const DepthConvention c = convention_of(kind);
            const Image stored_map = testing::in_convention(map, 0, c);
            const Image stored_rx = testing::in_convention(rx, 2, c);
            const Image held_map = testing::back_to_normalized(stored_map, 0, c);
            const Image held_rx = testing::back_to_normalized(stored_rx, 2, c);
            for (const MethodRun& run : kRuns) {
                const Image got = run_method(ctx, run, c, stored_map, stored_rx);
                const Image want = run_method(ctx, run, {}, held_map, held_rx);
                const testing::Difference d = testing::difference(got, want);
                if (reads_differences(run) && kind != DepthConventionKind::Linear) {
                    EXPECT_LE(d.max, 1.0 / 25.0 + 1e-6) << label(run, kind, rx);
                    EXPECT_LE(flipped(got, want) * 20, std::max(rx.width() * rx.height(), 20)) << label(run, kind, rx);
                    continue;
                }
                EXPECT_LE(d.max, 1e-4) << label(run, kind, rx) << ": " << d.differing << " differ";
            }
        }
}

// What the float32 storage of each convention loses, measured: the largest
// |l - l0| of a depth l0 written in the convention (in double, stored
// float32) and read back in double. Bounds (ulp of the stored value times
// dl/dz, kernels/depth_convention.h): linear 2^-24 far / (far - near);
// perspective (1 + k) 2^-24 at the far plane (k = 99 here: 6e-6);
// reversed 2^-24 (reversed Z keeps its precision where perspective loses it).
TEST(DepthConventionStorage, ErrorOfEachConventionIsItsOwnStorage)
{
    const Image normalized = testing::random_depth(256, 64, 11);
    const double k = 99.0;
    const double bound[] = {0.0, 0x1p-24 * 50.0 / 49.5, (1.0 + k) * 0x1p-24, 0x1p-24};
    for (DepthConventionKind kind : kAllConventions) {
        const DepthConvention c = convention_of(kind);
        const Image held = testing::back_to_normalized(testing::in_convention(normalized, 0, c), 0, c);
        const testing::Difference d = testing::difference(held, normalized);
        std::printf("%-12s storage error: max |l - l0| = %.3g over %d texels\n", to_string(kind).c_str(), d.max,
                    normalized.width() * normalized.height());
        EXPECT_LE(d.max, bound[int(kind)]) << to_string(kind);
    }
}

// Against the original normalised map: the storage's error (above) on
// inputs kept away from every decision (depths on multiples of 1/16,
// receivers on odd multiples of 1/32: every comparison has a margin of
// 1/32 - the bias, far above 6e-6), so that the percentage-closer methods
// decide alike and the moment methods move by their slope times 6e-6.
PN_BACKEND_TEST(DepthConventions, EachMethodGivesTheNormalisedMapsVisibility)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image map = testing::random_depth(33, 21, 21, true);
    Image rx = testing::scattered_receivers(17, 5, 0.0f, 1.0f, 0.0f, 1.0f, 22);
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x)
            rx.at(2, x, y) = (2.0f * std::floor(rx.at(2, x, y) * 16.0f) + 1.0f) / 32.0f;
    for (DepthConventionKind kind : kAllConventions) {
        const DepthConvention c = convention_of(kind);
        const Image stored_map = testing::in_convention(map, 0, c), stored_rx = testing::in_convention(rx, 2, c);
        for (const MethodRun& run : kRuns) {
            const Image got = run_method(ctx, run, c, stored_map, stored_rx);
            const Image want = run_method(ctx, run, {}, map, rx);
            const testing::Difference d = testing::difference(got, want);
            EXPECT_LE(d.max, 2e-3) << label(run, kind, rx) << ": " << d.differing << " differ";
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, DepthConventions, ::testing::ValuesIn(backend_names()), backend_test_name);

template <class F>
void expect_error(F&& call, ErrorCategory category, const std::string& parameter, const std::string& needle)
{
    try {
        call();
        ADD_FAILURE() << "accepted; wanted an error naming " << parameter;
    } catch (const Error& e) {
        EXPECT_EQ(e.category(), category) << e.what();
        EXPECT_EQ(e.parameter(), parameter) << e.what();
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
}

TEST(DepthConventionErrors, BadConventionsAreRefusedNamingNearOrFar)
{
    using K = DepthConventionKind;
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const struct {
        DepthConvention c;
        const char* parameter;
        const char* needle;
    } rows[] = {
        {{K::Perspective, 0.0f, 10.0f}, "near", "near > 0"},
        {{K::Reversed, -1.0f, 10.0f}, "near", "near > 0"},
        {{K::Linear, 5.0f, 5.0f}, "far", "far > near"},
        {{K::Perspective, 2.0f, 1.0f}, "far", "far > near"},
        {{K::Linear, nan, 1.0f}, "near", "finite near"},
        {{K::Reversed, 0.1f, inf}, "far", "infinite far plane"},
        {{K::Perspective, 0.1f, nan}, "far", "finite far"},
    };
    for (const auto& row : rows)
        expect_error([&] { check_depth_convention(row.c, "test"); }, ErrorCategory::InvalidArgument, row.parameter,
                     row.needle);
    EXPECT_NO_THROW(check_depth_convention({K::Linear, -3.0f, 2.0f}, "test"));  // linear: any near below far
}

TEST(DepthConventionErrors, MethodOptionsNeedNearAndFarWhereTheConventionReadsThem)
{
    const Method& pcf = find_method("pcf");
    expect_error([&] { parse_method_settings(pcf, {{"depth-convention", "linear"}, {"far", "2"}}); },
                 ErrorCategory::InvalidArgument, "near", "finite near (got none)");
    expect_error([&] { parse_method_settings(pcf, {{"near", "0.5"}, {"far", "2"}}); },
                 ErrorCategory::InvalidArgument, "near", "not to normalized depth");
    expect_error([&] { parse_method_settings(pcf, {{"depth-convention", "orthographic"}}); },
                 ErrorCategory::InvalidArgument, "depth-convention", "normalized, linear, perspective or reversed");
    expect_error([&] { parse_method_settings(find_method("dsm"), {{"depth-convention", "linear"}}); },
                 ErrorCategory::InvalidArgument, "depth-convention", "applies to");
    const MethodSettings s =
        parse_method_settings(pcf, {{"far", "9"}, {"depth-convention", "reversed"}, {"near", "0.25"}});
    EXPECT_EQ(s.depth_convention.kind, DepthConventionKind::Reversed);
    EXPECT_EQ(s.depth_convention.near, 0.25f);
    EXPECT_EQ(s.depth_convention.far, 9.0f);
}

TEST(DepthConventionErrors, DepthsOutsideTheConventionsRangeAreNamed)
{
    Context ctx(ContextOptions{Backend::Scalar, {}});
    const DepthConvention linear{DepthConventionKind::Linear, 2.0f, 10.0f};
    Image map = testing::in_convention(testing::random_depth(5, 4, 1), 0, linear);
    const Image rx = testing::in_convention(testing::receivers_on_texels(5, 4, 5, 4, 0.1f, 0.9f, 2), 2, linear);
    map.at(0, 3, 2) = 1.5f;  // in [0, 1], below near
    for (const MethodRun& run : kRuns) {
        const Method& m = find_method(run.method);
        const MethodSettings s = parse_method_settings(
            m, {{"depth-convention", "linear"}, {"near", "2"}, {"far", "10"}});
        expect_error([&] { m.run(ctx, map, rx, s); }, ErrorCategory::InvalidData, "depth", "outside [2, 10]");
    }
    Image perspective = testing::random_depth(5, 4, 1);
    perspective.at(0, 0, 0) = 1.25f;
    PcfOptions o;
    o.depth_convention = {DepthConventionKind::Perspective, 1.0f, 10.0f};
    expect_error([&] { pcf(ctx, perspective, rx, o); }, ErrorCategory::InvalidData, "depth", "outside [0, 1]");
}

TEST(DepthConventionErrors, ATableLookupTakesReceiversInTheTablesConvention)
{
    Context ctx(ContextOptions{Backend::Scalar, {}});
    const DepthConvention linear{DepthConventionKind::Linear, 2.0f, 10.0f};
    const Image map = testing::in_convention(testing::random_depth(5, 4, 1), 0, linear);
    const Image rx = testing::in_convention(testing::receivers_on_texels(5, 4, 5, 4, 0.1f, 0.9f, 2), 2, linear);
    const MomentTable table = build_moment_table(ctx, map, 2, Precision::Exact, linear);
    expect_error([&] { vsm(ctx, table, rx, VsmOptions{}); }, ErrorCategory::InvalidArgument, "depth-convention",
                 "the table holds a map of linear depth (near 2, far 10)");
    VsmOptions same;
    same.depth_convention = linear;
    EXPECT_NO_THROW(vsm(ctx, table, rx, same));
}

// Equal floats, pixel by pixel.
void expect_same_bits(const Image& got, const Image& want, const std::string& what)
{
    ASSERT_EQ(got.width(), want.width()) << what;
    ASSERT_EQ(got.height(), want.height()) << what;
    for (int y = 0; y < got.height(); ++y)
        for (int x = 0; x < got.width(); ++x)
            ASSERT_EQ(got.at(0, x, y), want.at(0, x, y)) << what << " at " << x << ", " << y;
}

// The device-resident chain in each convention: a table made for the map's
// convention converts in the build's load and its lookups read the
// receivers' z in it, as the Image forms do; the downloads equal those forms
// on the same backend bit for bit (VSM and VSSM, exact and float tables,
// maps of 1x1, 7x3 and 33x9 and receivers two texels wider).
PN_BACKEND_TEST(DepthConventions, TheDeviceChainShadesEachConventionAsTheHostPath)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (DepthConventionKind kind : kAllConventions)
        for (const auto& [w, h] : {std::pair{1, 1}, {7, 3}, {33, 9}})
            for (const Precision precision : {Precision::Exact, Precision::Float}) {
                const std::string what = to_string(kind) + " " + std::to_string(w) + "x" + std::to_string(h) + " " +
                                         to_string(precision);
                const DepthConvention c = convention_of(kind);
                const Image map = testing::in_convention(testing::random_depth(w, h, 21), 0, c);
                const Image rx = testing::in_convention(
                    testing::scattered_receivers(w + 2, h, 0.0f, 1.0f, 0.05f, 0.95f, 22), 2, c);
                DeviceMomentTable table = device_moment_table(ctx, w, h, precision, c);
                EXPECT_TRUE(same_convention(table.depth_convention(), c)) << what;
                build_moment_table(ctx, upload(ctx, map), table);
                const DeviceImage receivers = upload(ctx, rx);
                DeviceImage hard = device_image(ctx, w + 2, h, 1), soft = device_image(ctx, w + 2, h, 1);
                VsmOptions vsm_options;
                vsm_options.radius = 1;
                vsm_options.depth_convention = c;
                VssmOptions vssm_options;
                vssm_options.light_size = 0.2f;
                vssm_options.depth_convention = c;
                vsm(ctx, table, receivers, vsm_options, hard);
                vssm(ctx, table, receivers, vssm_options, soft);
                const MomentTable host = build_moment_table(ctx, map, 2, precision, c);
                expect_same_bits(download(ctx, hard), vsm(ctx, host, rx, vsm_options), what + " vsm");
                expect_same_bits(download(ctx, soft), vssm(ctx, host, rx, vssm_options), what + " vssm");
            }
}

// The chain's checks in a convention: a lookup naming another convention
// than the table's is refused at the call; a map value outside the
// convention's range is the build's InvalidData naming `depth` (at the call
// on the CPU backends, at finish() on OpenCL), its message the range.
PN_BACKEND_TEST(DepthConventions, TheDeviceChainChecksTheConvention)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const DepthConvention linear = convention_of(DepthConventionKind::Linear);
    Image map = testing::in_convention(testing::random_depth(5, 4, 1), 0, linear);
    const Image receivers = testing::receivers_on_texels(5, 4, 5, 4, 0.1f, 0.9f, 2);
    const DeviceImage rx = upload(ctx, testing::in_convention(receivers, 2, linear));
    DeviceMomentTable table = device_moment_table(ctx, 5, 4, Precision::Exact, linear);
    build_moment_table(ctx, upload(ctx, map), table);
    DeviceImage out = device_image(ctx, 5, 4, 1);
    VsmOptions vsm_options;
    vsm_options.depth_convention = convention_of(DepthConventionKind::Perspective);
    expect_error([&] { vsm(ctx, table, rx, vsm_options, out); }, ErrorCategory::InvalidArgument, "depth-convention",
                 "");
    VssmOptions vssm_options;  // normalized, the table linear
    expect_error([&] { vssm(ctx, table, rx, vssm_options, out); }, ErrorCategory::InvalidArgument, "depth-convention",
                 "");
    finish(ctx);
    map.at(0, 2, 3) = 0.25f;  // below near (0.5)
    const DeviceImage bad = upload(ctx, map);
    expect_error(
        [&] {
            build_moment_table(ctx, bad, table);
            finish(ctx);
        },
        ErrorCategory::InvalidData, "depth", "linear");
    DepthConvention no_far = linear;
    no_far.far = std::nanf("");
    expect_error([&] { device_moment_table(ctx, 5, 4, Precision::Exact, no_far); }, ErrorCategory::InvalidArgument,
                 "far", "");
}

}  // namespace
}  // namespace penumbra
