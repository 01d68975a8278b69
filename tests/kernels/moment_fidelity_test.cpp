// Fidelity of the moment family (issue 9): vsm, vssm, msm, msm-soft, evsm2
// and evsm4, in the mode `penumbra shade` uses with no precision or
// quantization option, on every backend, against the float64 reference of
// tests/support/fidelity_reference.h (direct loops over the window of the
// float32 input depths; never the library's tables).
//
// Per receiver the ill-conditioned rule of docs/fidelity.md: within 2e-4
// (vsm, vssm, evsm2, evsm4) or 1e-3 (msm, msm-soft) of the reference, or, for
// a receiver whose reference answer moves by more than that when the
// window's raw moments move by a relative 2^-20, within the tolerance plus
// twice that movement; always finite and in [0, 1].
//
// Cases (tests/support/fidelity_cases.h): maps 1x1, 7x3, widths around the
// lane counts (3, 4, 5, 15, 16, 17) and 33x17, smooth and two-layer; windows
// of one depth (0, 0.3, 1), of two depths (0.25 and 0.75) and of only 0 and
// 1; 257^2 and 1024^2 smooth and two-layer maps; receivers on the surface, in
// front and behind; box radii 0, 1, 2, 8 and the largest accepted (127),
// light sizes from a texel to the largest search window the map allows.
// 16384^2: VSM on 300 receivers, labelled slow.
//
// The reference answers are computed once per case and shared by all
// backends. MomentAgreement measures every backend against scalar on the
// same cases: the figures docs/fidelity.md states, asserted at its limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "penumbra/chebyshev.h"
#include "penumbra/moment_table.h"
#include "penumbra/moments.h"
#include "support/backends.h"
#include "support/fidelity_cases.h"
#include "support/moment_reference.h"

// A namespace of its own: the using-directive below must not reach the test
// sources that share this one's unity batch (tests/CMakeLists.txt), and the
// using-declarations win over penumbra::Method and penumbra::Mode there.
namespace penumbra::moment_fidelity_test {
namespace {

using namespace testing::fidelity;
using testing::fidelity::Method;
using testing::fidelity::Mode;
using testing::backend_test_name;

struct FidelityCase {
    std::string name;
    Image map, receivers;
    std::vector<Setting> box, soft;  // the settings run on this case
};

// Receivers at every texel centre (on, 1e-2 in front, 1e-3 and 3e-2 behind)
// and `random` more anywhere.
Image texel_receivers(const Image& map, int random, std::uint32_t seed)
{
    const float offsets[] = {0.0f, -1e-2f, 1e-3f, 3e-2f};
    const int texels = map.width() * map.height();
    const Image extra = receivers_for(map, std::max(random, 1), seed);
    Image rx(texels * 4 + extra.width(), 1, 3);
    int i = 0;
    for (float dz : offsets) {
        const Image at = receivers_at_texels(map, dz);
        for (int y = 0; y < map.height(); ++y)
            for (int x = 0; x < map.width(); ++x, ++i)
                for (int c = 0; c < 3; ++c) rx.at(c, i, 0) = at.at(c, x, y);
    }
    for (int j = 0; j < extra.width(); ++j, ++i)
        for (int c = 0; c < 3; ++c) rx.at(c, i, 0) = extra.at(c, j, 0);
    return rx;
}

std::vector<Setting> radii(std::initializer_list<int> list)
{
    std::vector<Setting> s;
    for (int r : list) s.push_back({r, 0.02f});
    return s;
}

std::vector<Setting> lights(std::initializer_list<float> list)
{
    std::vector<Setting> s;
    for (float l : list) s.push_back({0, l});
    return s;
}

const std::vector<FidelityCase>& cases()
{
    static const std::vector<FidelityCase> all = [] {
        std::vector<FidelityCase> c;
        const auto all_radii = radii({0, 1, 2, 8, kExactMaxRadius});
        const auto small_lights = lights({0.05f, 0.3f, 0.9f});
        std::uint32_t seed = 90;
        for (auto [w, h] : {std::pair{1, 1}, {7, 3}, {3, 5}, {4, 4}, {5, 2}, {15, 9}, {16, 16}, {17, 6}, {33, 17}}) {
            for (int layered = 0; layered < 2; ++layered) {
                Image map = layered ? two_layer_map(w, h) : smooth_map(w, h);
                Image rx = texel_receivers(map, 32, seed++);
                c.push_back({(layered ? "two-layer " : "smooth ") + std::to_string(w) + "x" + std::to_string(h),
                             std::move(map), std::move(rx), all_radii, small_lights});
            }
        }
        for (float z : {0.0f, 0.3f, 1.0f}) {
            Image map = constant_map(9, 7, z);
            Image rx = texel_receivers(map, 16, seed++);
            c.push_back({"one depth " + std::to_string(z), std::move(map), std::move(rx), radii({0, 1, 3}),
                         lights({0.2f})});
        }
        for (auto [a, b] : {std::pair{0.25f, 0.75f}, {0.0f, 1.0f}}) {
            Image map = checker_map(9, 7, a, b);
            Image rx = texel_receivers(map, 64, seed++);
            c.push_back({"depths " + std::to_string(a) + " and " + std::to_string(b), std::move(map), std::move(rx),
                         radii({0, 1, 3}), lights({0.2f})});
        }
        for (int layered = 0; layered < 2; ++layered) {
            Image map = layered ? two_layer_map(257, 257) : smooth_map(257, 257);
            Image rx = receivers_for(map, 1200, seed++);
            c.push_back({layered ? "two-layer 257^2" : "smooth 257^2", std::move(map), std::move(rx),
                         radii({0, 1, 2, 8}), lights({0.02f})});
        }
        // The widest windows cost the reference up to 65025 texels a receiver: fewer receivers.
        for (int layered = 0; layered < 2; ++layered) {
            Image map = layered ? two_layer_map(257, 257) : smooth_map(257, 257);
            Image rx = receivers_for(map, 96, seed++);
            c.push_back({layered ? "two-layer 257^2, wide" : "smooth 257^2, wide", std::move(map), std::move(rx),
                         radii({kExactMaxRadius}), lights({0.2f, 0.9f})});
        }
        for (int layered = 0; layered < 2; ++layered) {
            Image map = layered ? two_layer_map(1024, 1024) : smooth_map(1024, 1024);
            Image rx = receivers_for(map, 500, seed++);
            c.push_back({layered ? "two-layer 1024^2" : "smooth 1024^2", std::move(map), std::move(rx),
                         radii({1, 8}), lights({0.02f})});
        }
        return c;
    }();
    return all;
}

const Method kMethods[] = {Method::Vsm, Method::Vssm, Method::Msm, Method::MsmSoft, Method::Evsm2, Method::Evsm4};

std::string setting_name(Method m, Setting s)
{
    char text[64];
    if (is_soft(m)) std::snprintf(text, sizeof text, "light size %g", double(s.light_size));
    else std::snprintf(text, sizeof text, "radius %d", s.radius);
    return text;
}

// The reference answers of a case, computed once per test process.
const std::vector<double>& references(const FidelityCase& c, Method m, Setting s, const Params& p)
{
    static std::map<std::string, std::vector<double>> cache;
    const std::string key = c.name + "/" + method_name(m) + "/" + setting_name(m, s);
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, reference_all(m, c.map, c.receivers, p)).first;
    return it->second;
}

// A light a map's exact table accepts: its search window within 253 texels.
bool light_accepted(const FidelityCase& c, float light)
{
    return light * 0.5f * float(std::max(c.map.width(), c.map.height())) <= float(kExactMaxRadius - 1);
}

// The direct window sums are run at every case's radii up to 8: 0, 1, 2 and
// 3 (the cuts of penumbra/chebyshev.h and moments.h and beyond them: the
// same method at any radius) and 8; the widest, 127, would be 65025 taps per
// receiver and says nothing more.
constexpr int kDirectMaxTestedRadius = 8;
static_assert(kVsmDirectMaxRadius < kDirectMaxTestedRadius && kMsmDirectMaxRadius < kDirectMaxTestedRadius &&
              kEvsmDirectMaxRadius < kDirectMaxTestedRadius);

// Visits every method of a case with the library's runs of its settings in `mode`.
template <class Visit>
void for_each_run(Context& ctx, Mode mode, const FidelityCase& c, Visit visit)
{
    for (Method m : kMethods) {
        const std::vector<Mode> modes = modes_of(m);
        if (std::find(modes.begin(), modes.end(), mode) == modes.end()) continue;
        std::vector<Setting> settings;
        for (Setting s : is_soft(m) ? c.soft : c.box)
            if ((!is_soft(m) || light_accepted(c, s.light_size)) &&
                (mode != Mode::Direct || s.radius <= kDirectMaxTestedRadius))
                settings.push_back(s);
        StoredMoments stored;
        const std::vector<LibraryRun> runs = run_library(ctx, m, mode, c.map, c.receivers, settings, &stored);
        for (std::size_t i = 0; i < runs.size(); ++i) visit(m, settings[i], runs[i]);
    }
}

// ---- the reference against closed forms and the older double reference ----

Moments atoms_moments(const std::vector<std::pair<double, double>>& atoms)
{
    std::array<real, 5> raw{1, 0, 0, 0, 0};
    for (auto [x, w] : atoms)
        for (int k = 1; k <= 4; ++k) raw[k] += real(w) * std::pow(real(x), real(k));
    return from_raw(raw);
}

TEST(FidelityReference, VsmOnACheckerWindowIsTheClosedForm)
{
    // 3 x 3 around texel (4, 3) of a checker: five texels at 0.75 ((x + y) odd), four at 0.25.
    const Image map = checker_map(9, 7, 0.25f, 0.75f);
    Params p;
    p.radius = 1;
    const double mean = (5 * 0.75 + 4 * 0.25) / 9, var = (5 * 0.5625 + 4 * 0.0625) / 9 - mean * mean;
    const double z = 0.8, expected = var / (var + (z - mean) * (z - mean));
    const Answer a = evaluate(Method::Vsm, map, {4.5f / 9, 3.5f / 7, float(z)}, p, true);
    EXPECT_NEAR(double(a.visibility), expected, 1e-6 * expected);  // z is a float32
    EXPECT_LT(double(a.movement), 1e-5);
}

TEST(FidelityReference, FractionalWindowsWeighTexelsByOverlap)
{
    Image map(2, 1, 1);
    map.at(0, 0, 0) = 0.0f;
    map.at(0, 1, 0) = 1.0f;
    const Moments m = span_moments(map, {0.5L, 1.75L, 0, 1}, identity, Params{});
    EXPECT_NEAR(double(m.centre), 0.75 / 1.25, 1e-15);
}

TEST(FidelityReference, MsmIsExactOnOneAndTwoDepthsWithoutBias)
{
    const Moments two = atoms_moments({{0.25, 5.0 / 9}, {0.75, 4.0 / 9}});
    EXPECT_NEAR(double(msm_intensity(two, 0.25, 0)), 0.0, 1e-12);
    EXPECT_NEAR(double(msm_intensity(two, 0.5, 0)), 5.0 / 9, 1e-12);
    EXPECT_NEAR(double(msm_intensity(two, 0.76, 0)), 1.0, 1e-12);
    const Moments one = atoms_moments({{0.3, 1.0}});
    EXPECT_EQ(double(msm_intensity(one, 0.3, 0)), 0.0);
    EXPECT_EQ(double(msm_intensity(one, 0.30001, 0)), 1.0);
    // Only 0 and 1, with the bias (whose atoms are there too): exact.
    const Moments zero_one = atoms_moments({{0.0, 0.375}, {1.0, 0.625}});
    const double alpha = 6e-5;
    EXPECT_NEAR(double(msm_intensity(zero_one, 0.5, alpha)), (1 - alpha) * 0.375 + alpha / 2, 1e-12);
}

TEST(FidelityReference, MsmAgreesWithTheOlderDoubleReference)
{
    // tests/support/moment_reference.h computes the bound by other means
    // (Gaussian elimination, Vandermonde weights; checked against a linear
    // program there): the two must agree on random few-depth windows.
    std::mt19937 rng(2015);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0;
    for (int i = 0; i < 400; ++i) {
        const int n = 1 + i % 5;
        std::vector<std::pair<double, double>> atoms;
        std::vector<testing::Atom> old_atoms;
        double total = 0;
        for (int k = 0; k < n; ++k) total += (atoms.emplace_back(unit(rng), 0.1 + unit(rng)).second);
        for (auto& [x, w] : atoms) old_atoms.push_back({x, w /= total});
        const double alpha = 6e-5, z = unit(rng);
        const double old = testing::msm_bound(testing::biased(testing::moments_of(old_atoms), alpha), z).intensity;
        worst = std::max(worst, std::fabs(double(msm_intensity(atoms_moments(atoms), z, alpha)) - old));
    }
    std::printf("msm: fidelity reference vs moment_reference on 400 windows: max |diff| %.3g\n", worst);
    EXPECT_LT(worst, 1e-7);
}

class MomentFidelity : public ::testing::TestWithParam<std::string> {};

PN_BACKEND_TEST(MomentFidelity, DefaultModeWithinToleranceOfTheFloat64Method)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const FidelityCase& c : cases())
        for_each_run(ctx, Mode::Default, c, [&](Method m, Setting s, const LibraryRun& run) {
            const Tally t = judge_all(m, c.map, c.receivers, run.out, run.params, 5, &references(c, m, s, run.params));
            EXPECT_EQ(t.failed, 0) << method_name(m) << " on " << c.name << ", " << setting_name(m, s) << ": "
                                   << t.failed << " of " << t.receivers << " receivers fail the rule (worst "
                                   << t.worst << ", " << t.ill << " ill-conditioned)\n"
                                   << t.first_failures;
        });
}

// The box methods' windows summed directly from the map (no table; what
// `penumbra shade` runs at small radii): the same rule on the same cases,
// the map borders (receivers at every texel), odd sizes and the one-depth,
// two-depth and 0-and-1 windows included.
PN_BACKEND_TEST(MomentFidelity, DirectSumsWithinToleranceOfTheFloat64Method)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    int runs = 0;
    for (const FidelityCase& c : cases())
        for_each_run(ctx, Mode::Direct, c, [&](Method m, Setting s, const LibraryRun& run) {
            ++runs;
            const Tally t = judge_all(m, c.map, c.receivers, run.out, run.params, 5, &references(c, m, s, run.params));
            EXPECT_EQ(t.failed, 0) << method_name(m) << " (direct sums) on " << c.name << ", " << setting_name(m, s)
                                   << ": " << t.failed << " of " << t.receivers << " receivers fail the rule (worst "
                                   << t.worst << ", " << t.ill << " ill-conditioned)\n"
                                   << t.first_failures;
        });
    EXPECT_GT(runs, 0);
}

// The opt-in I3D 2015 16-bit quantization: the arithmetic after it against
// the float64 method on its dequantized moments (its quantization error
// against the input depths is measured by bench/moment_fidelity, not held to
// the tolerance).
PN_BACKEND_TEST(MomentFidelity, SixteenBitMsmWithinToleranceOfItsDequantizedMoments)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const FidelityCase& c : cases())
        for_each_run(ctx, Mode::Msm16, c, [&](Method m, Setting s, const LibraryRun& run) {
            const Tally t = judge_all(m, c.map, c.receivers, run.out, run.params, 5);
            EXPECT_EQ(t.failed, 0) << method_name(m) << " (16-bit) on " << c.name << ", " << setting_name(m, s)
                                   << ": " << t.failed << " of " << t.receivers << " receivers fail the rule (worst "
                                   << t.worst << ", " << t.ill << " ill-conditioned)\n"
                                   << t.first_failures;
        });
}

// Without the moment bias a window of one or two depths has a singular
// Hankel matrix: the library must answer exactly for that distribution (the
// reference's one- and two-point answers), and windows of more depths go
// through the full reconstruction, near-singular or not (the rule holds them).
PN_BACKEND_TEST(MomentFidelity, UnbiasedMsmIsExactOnOneAndTwoDepthWindows)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (const FidelityCase& c : cases()) {
        if (c.map.width() * c.map.height() > 64 * 64) continue;  // the special windows and the small maps
        const MsmTable t = build_msm_table(ctx, c.map);
        Params p;
        p.moment_bias = 0.0f;
        p.msm_depth_bias = default_depth_bias(t.quantization);
        p.max_radius = kExactMaxRadius - 1;
        const auto check = [&](Method m, Setting s, const Image& out) {
            Params q = p;
            q.radius = s.radius;
            q.light_size = s.light_size;
            const Tally tally = judge_all(m, c.map, c.receivers, out, q, 5);
            EXPECT_EQ(tally.failed, 0) << method_name(m) << " without bias on " << c.name << ", "
                                       << setting_name(m, s) << ": " << tally.failed << " of " << tally.receivers
                                       << " receivers fail the rule (worst " << tally.worst << ")\n"
                                       << tally.first_failures;
        };
        for (Setting s : c.box) check(Method::Msm, s, msm(ctx, t, c.receivers, MsmOptions{s.radius, 0.0f, {}}));
        for (Setting s : c.soft)
            if (light_accepted(c, s.light_size))
                check(Method::MsmSoft, s, msm_soft(ctx, t, c.receivers, MsmSoftOptions{s.light_size, 0.0f, {}}));
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, MomentFidelity, ::testing::ValuesIn(testing::backend_names()), backend_test_name);

// ---- every backend against scalar on the same cases (docs/fidelity.md) ----

// docs/fidelity.md states that every backend gives scalar's bits on these
// cases (the per-window arithmetic is double in every binding, the result
// rounded once to float): max |backend - scalar| = 0 for every method.
constexpr double kAgreementLimit = 0.0;

class MomentAgreement : public ::testing::TestWithParam<std::string> {};

PN_BACKEND_TEST(MomentAgreement, EveryBackendAgreesWithScalarOnTheFidelityCases)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Context& scalar = testing::scalar_oracle(backend);
    std::map<Method, double> worst;
    std::map<Method, long> differing, total;
    for (const FidelityCase& c : cases())
        for (Mode mode : {Mode::Default, Mode::Direct}) {
            std::vector<Image> baseline;
            for_each_run(scalar, mode, c,
                         [&](Method, Setting, const LibraryRun& run) { baseline.push_back(run.out); });
            std::size_t next = 0;
            for_each_run(ctx, mode, c, [&](Method m, Setting, const LibraryRun& run) {
                const Image& b = baseline[next++];
                for (int i = 0; i < run.out.width(); ++i) {
                    const double d = std::fabs(double(run.out.at(0, i, 0)) - double(b.at(0, i, 0)));
                    worst[m] = std::max(worst[m], d);
                    differing[m] += d != 0.0;
                    ++total[m];
                }
            });
        }
    for (Method m : kMethods) {
        std::printf("%s vs scalar, %s: max |diff| %.3g, %ld of %ld receivers differ\n", backend.c_str(),
                    method_name(m).c_str(), worst[m], differing[m], total[m]);
        EXPECT_LE(worst[m], kAgreementLimit) << method_name(m) << " on " << backend;
    }
}

// Not for scalar: it is the baseline, and comparing it with itself would count as a pass.
INSTANTIATE_TEST_SUITE_P(Backends, MomentAgreement, ::testing::ValuesIn(testing::non_scalar_backends()),
                         backend_test_name);

// ---- 16384^2 (slow: a 1 GiB map and its table) ----------------------------

TEST(MomentFidelitySlowTest, VsmAt16384)
{
    Context ctx;
    const Image map = smooth_map(16384, 16384);
    const Image rx = receivers_for(map, 300, 16384);
    const std::vector<Setting> settings = radii({0, 2, 8, kExactMaxRadius});
    const std::vector<LibraryRun> runs = run_library(ctx, Method::Vsm, Mode::Default, map, rx, settings);
    for (std::size_t i = 0; i < runs.size(); ++i) {
        const Tally t = judge_all(Method::Vsm, map, rx, runs[i].out, runs[i].params);
        std::printf("vsm at 16384^2, radius %d: worst %.3g over %d receivers\n", settings[i].radius, t.worst,
                    t.receivers);
        EXPECT_EQ(t.failed, 0) << "radius " << settings[i].radius << ": worst " << t.worst << "\n"
                               << t.first_failures;
    }
}

}  // namespace
}  // namespace penumbra::moment_fidelity_test
