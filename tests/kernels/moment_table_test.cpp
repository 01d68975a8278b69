// Summed-area tables of moments against brute-force sums, on every backend.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "penumbra/error.h"
#include "penumbra/moment_table.h"
#include "support/backends.h"
#include "support/maps.h"

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;

class MomentTableTest : public ::testing::TestWithParam<std::string> {};

struct Size {
    int w, h;
};

std::vector<Size> odd_sizes()
{
    std::vector<Size> sizes{{1, 1}, {7, 3}, {1023, 17}, {3, 70}};
    for (int w : testing::lane_edge_widths()) sizes.push_back({w, 5});
    sizes.push_back({130, 67});  // two SIMD column bands and two row blocks on any thread count
    return sizes;
}

// Every rectangle of small maps, a random sample of larger ones.
template <class Check>
void for_rectangles(int w, int h, std::uint32_t seed, Check&& check)
{
    if (w * h <= 64) {
        for (int y0 = 0; y0 < h; ++y0)
            for (int y1 = y0 + 1; y1 <= h; ++y1)
                for (int x0 = 0; x0 < w; ++x0)
                    for (int x1 = x0 + 1; x1 <= w; ++x1) check(x0, x1, y0, y1);
        return;
    }
    std::mt19937 rng(seed);
    for (int i = 0; i < 300; ++i) {
        int xa = std::uniform_int_distribution<int>(0, w)(rng), xb = std::uniform_int_distribution<int>(0, w)(rng);
        int ya = std::uniform_int_distribution<int>(0, h)(rng), yb = std::uniform_int_distribution<int>(0, h)(rng);
        if (xa == xb) xb = xa == w ? xa - 1 : xa + 1;
        if (ya == yb) yb = ya == h ? ya - 1 : ya + 1;
        check(std::min(xa, xb), std::max(xa, xb), std::min(ya, yb), std::max(ya, yb));
    }
    check(0, w, 0, h);
}

PN_BACKEND_TEST(MomentTableTest, ExactSumsMatchBruteForce)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    // 2 limbs (VSM, VSSM) and 3 (MSM, EVSM): pair planes with and without the limb-2 plane after them.
    for (int limbs : {2, 3})
        for (int moments : {2, 4})
            for (Size s : odd_sizes()) {
                const Image depth = testing::random_depth(s.w, s.h, 7u * s.w + s.h);
                MomentTable table(s.w, s.h, moments, Precision::Exact, limbs);
                build_moment_table(ctx, depth, table);
                for_rectangles(s.w, s.h, 11, [&](int x0, int x1, int y0, int y1) {
                    for (int k = 1; k <= table.planes(); ++k)
                        ASSERT_EQ(table.exact_box_sum(k, x0, x1, y0, y1),
                                  testing::brute_exact_sum(depth, k, table.limbs(), x0, x1, y0, y1))
                            << s.w << "x" << s.h << " limbs " << limbs << " plane " << k << " rect [" << x0 << ","
                            << x1 << ")x[" << y0 << "," << y1 << ")";
                });
            }
}

// The CPU build cuts the map into one column band per thread of the arena and
// runs its blocks as their left and upper neighbours finish
// (simd/cpu_moment_table.cpp). Arenas of more threads than the machine's cores
// give more bands than running threads; every count must give the same sums.
PN_BACKEND_TEST(MomentTableTest, ExactSumsMatchBruteForceOnEveryThreadCount)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int w = 397, h = 71;  // 2 to 4 bands of 128 to 256 columns, the last one partial; 3 row blocks
    const Image depth = testing::random_depth(w, h, 41u);
    for (int threads : {1, 2, 3, 5}) {
        MomentTable table(w, h, 2, Precision::Exact, 2);
        tbb::task_arena(threads).execute([&] { build_moment_table(ctx, depth, table); });
        for_rectangles(w, h, 13, [&](int x0, int x1, int y0, int y1) {
            for (int k = 1; k <= table.planes(); ++k)
                ASSERT_EQ(table.exact_box_sum(k, x0, x1, y0, y1),
                          testing::brute_exact_sum(depth, k, table.limbs(), x0, x1, y0, y1))
                    << threads << " threads, plane " << k << " rect [" << x0 << "," << x1 << ")x[" << y0 << ","
                    << y1 << ")";
        });
    }
}

// The CPU build's schedule depends on the arena's threads (one column band
// per thread, simd/cpu_moment_table.cpp; a schedule that split the values
// between threads was tried, docs/moment_table.md, "Session 17"): every
// table kind and thread count must store the one-thread build's bits,
// padding included.
constexpr int kEvsmTable = 1;  // PN_TABLE_EVSM (kernels/params.h)

struct TableKind {
    int moments, limbs;
    Precision precision;
    TableValues values;
};

std::vector<TableKind> table_kinds()
{
    const TableValues evsm{kEvsmTable, 5.0f, 3.0f, {}};
    return {{2, 2, Precision::Exact, {}},   {2, 3, Precision::Exact, {}},   {4, 2, Precision::Exact, {}},
            {4, 3, Precision::Exact, {}},   {2, 3, Precision::Exact, evsm}, {4, 3, Precision::Exact, evsm},
            {2, 1, Precision::Float, {}},   {4, 1, Precision::Float, {}}};
}

// The first element (4 bytes) where two tables' storages differ, or -1.
long first_difference(const MomentTable& a, const MomentTable& b)
{
    const auto* x = reinterpret_cast<const std::uint32_t*>(a.storage());
    const auto* y = reinterpret_cast<const std::uint32_t*>(b.storage());
    for (std::size_t i = 0; i < a.storage_elements(); ++i)
        if (x[i] != y[i]) return long(i);
    return -1;
}

PN_BACKEND_TEST(MomentTableTest, EveryThreadCountStoresTheOneThreadBuildsBits)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (Size s : std::vector<Size>{{1, 1}, {7, 3}, {33, 9}, {397, 71}})
        for (const TableKind& kind : table_kinds()) {
            const Image depth = testing::random_depth(s.w, s.h, 5u * s.w + s.h);
            auto build = [&](int threads) {
                MomentTable table(s.w, s.h, kind.moments, kind.precision, kind.limbs, kind.values);
                tbb::task_arena(threads).execute([&] { build_moment_table(ctx, depth, table); });
                return table;
            };
            const MomentTable one = build(1);
            for (int threads : {2, 3, 4, 5})
                ASSERT_EQ(first_difference(build(threads), one), -1)
                    << s.w << "x" << s.h << ", " << kind.moments << " values x " << kind.limbs << " limbs, "
                    << (kind.values.kind == kEvsmTable ? "evsm" : "powers") << ", " << threads << " threads";
        }
}

// Depths where rounding to 32 bits is delicate: exact ties (k + 1/2) 2^-32,
// their float neighbours, the carry into limb 0 at (2^16 - 1/2) 2^-32, tiny
// and subnormal depths, 1 and just below 1. A VSM table (2 values x 2 limbs)
// forms the depth's limbs in float (sat_depth_limbs2), z^2's in double; each
// texel's limbs must be the double rounding's (testing::exact_limb).
std::vector<float> rounding_edge_depths()
{
    std::vector<float> z{0.0f, 1.0f, std::nextafter(1.0f, 0.0f), 1e-40f, std::ldexp(1.0f, -24),
                         std::ldexp(1.0f, -9), std::ldexp(1.0f, -16)};
    for (double k : {0.0, 1.0, 2.0, 3.0, 65535.0, 65536.0, 1048575.0, 8388607.0}) {
        const float tie = float(std::ldexp(k + 0.5, -32));
        z.insert(z.end(), {tie, std::nextafter(tie, 0.0f), std::nextafter(tie, 1.0f)});
    }
    std::mt19937 rng(5);
    for (int i = 0; i < 200; ++i)  // every binade from 2^-40 to 1
        z.push_back(std::ldexp(std::uniform_real_distribution<float>(0.5f, 1.0f)(rng), -(i % 41)));
    return z;
}

PN_BACKEND_TEST(MomentTableTest, ExactLimbsAtRoundingEdges)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const std::vector<float> z = rounding_edge_depths();
    const int w = 37, h = int(z.size() + w - 1) / w;
    Image depth(w, h, 1);
    for (int i = 0; i < w * h; ++i) depth.at(0, i % w, i / w) = z[std::size_t(i) % z.size()];
    for (int moments : {2, 4}) {
        MomentTable table(w, h, moments, Precision::Exact, 2);
        build_moment_table(ctx, depth, table);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int k = 1; k <= table.planes(); ++k)
                    ASSERT_EQ(table.exact_box_sum(k, x, x + 1, y, y + 1),
                              testing::brute_exact_sum(depth, k, 2, x, x + 1, y, y + 1))
                        << "depth " << depth.at(0, x, y) << " plane " << k << " moments " << moments;
    }
}

// The pair planes' corner (0, 0) reads the two elements before their origin:
// in a 3-limb table the last two of the previous value's limb-2 plane, its
// last row's padding (kernels/moment_table.h, layout). Widths 15 and 31 are
// the ones a one-element padding would break.
TEST(MomentTableLayout, RowsKeepTwoZeroElementsOfPadding)
{
    for (int w : {1, 14, 15, 16, 17, 31, 47, 4095, 4096})
        for (int limbs : {1, 2, 3}) EXPECT_GE(MomentTable(w, 3, 4, Precision::Exact, limbs).pitch(), w + 2) << w;
}

// Depths in sixteenths keep every float partial sum of z and z^2 exact on
// these sizes, so float mode must match the brute force to the bit.
PN_BACKEND_TEST(MomentTableTest, FloatSumsMatchBruteForceExactlyOnDyadicMaps)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    for (Size s : odd_sizes()) {
        const Image depth = testing::random_depth(s.w, s.h, 3u * s.w + s.h, /*dyadic=*/true);
        const MomentTable table = build_moment_table(ctx, depth, 2, Precision::Float);
        for_rectangles(s.w, s.h, 5, [&](int x0, int x1, int y0, int y1) {
            for (int k = 1; k <= 2; ++k)
                ASSERT_EQ(table.box_sum(k, x0, x1, y0, y1), testing::brute_sum(depth, k, x0, x1, y0, y1))
                    << s.w << "x" << s.h << " moment " << k;
        });
    }
}

// Four float moments of random depths: rounding, bounded relative to the
// magnitude of the table entries involved (sequential float sums).
PN_BACKEND_TEST(MomentTableTest, FloatFourMomentsWithinRounding)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Image depth = testing::random_depth(157, 43, 99);
    const MomentTable table = build_moment_table(ctx, depth, 4, Precision::Float);
    for_rectangles(157, 43, 17, [&](int x0, int x1, int y0, int y1) {
        for (int k = 1; k <= 4; ++k) {
            const double magnitude = testing::brute_sum(depth, k, 0, x1, 0, y1);
            ASSERT_NEAR(table.box_sum(k, x0, x1, y0, y1), testing::brute_sum(depth, k, x0, x1, y0, y1),
                        4e-6 * magnitude + 1e-6);
        }
    });
}

PN_BACKEND_TEST(MomentTableTest, ExactOnConstantAndRampAt1024)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const int n = 1024;
    Image ramp(n, n, 1), flat(n, n, 1);
    flat.fill(0, 1.0f);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) ramp.at(0, x, y) = float((x + y) % 1000) / 999.0f;
    for (const Image* map : {&flat, &ramp}) {
        const MomentTable table = build_moment_table(ctx, *map, 2, Precision::Exact);
        for_rectangles(n, n, 23, [&](int x0, int x1, int y0, int y1) {
            if ((x1 - x0) * (y1 - y0) > kExactMaxWindowArea) return;
            for (int k = 1; k <= table.planes(); ++k)
                ASSERT_EQ(table.exact_box_sum(k, x0, x1, y0, y1),
                          testing::brute_exact_sum(*map, k, table.limbs(), x0, x1, y0, y1));
        });
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, MomentTableTest, ::testing::ValuesIn(backend_names()), backend_test_name);

// The exact claim at the largest supported size: every window of at most
// 65535 texels has exact sums, though the table itself wraps many times.
TEST(MomentTableSlowTest, ExactAt16384OnConstantAndRamp)
{
    Context ctx(ContextOptions{Backend::Simd, {}});
    const int n = 16384;
    Image map(n, n, 1);
    for (int pattern = 0; pattern < 2; ++pattern) {
        for (int y = 0; y < n; ++y) {
            float* row = map.row(0, y);
            for (int x = 0; x < n; ++x) row[x] = pattern == 0 ? 1.0f : float((x + 3 * y) % 4096) / 4095.0f;
        }
        const MomentTable table = build_moment_table(ctx, map, 2, Precision::Exact);
        std::mt19937 rng(5);
        std::uniform_int_distribution<int> pos(0, n - 1), len(1, 255);
        int checked = 0;
        auto check = [&](int x0, int x1, int y0, int y1) {
            for (int k = 1; k <= table.planes(); ++k)
                ASSERT_EQ(table.exact_box_sum(k, x0, x1, y0, y1),
                          testing::brute_exact_sum(map, k, table.limbs(), x0, x1, y0, y1))
                    << "pattern " << pattern << " rect [" << x0 << "," << x1 << ")x[" << y0 << "," << y1 << ")";
            ++checked;
        };
        for (int i = 0; i < 400; ++i) {
            const int x0 = pos(rng), y0 = pos(rng);
            check(x0, std::min(n, x0 + len(rng)), y0, std::min(n, y0 + len(rng)));
        }
        check(n - 255, n, n - 257, n);  // the far corner: the most wrapped entries
        check(0, 255, 0, 257);
        EXPECT_EQ(checked, 402);
    }
}

TEST(MomentTableErrors, RejectsBadMaps)
{
    Context ctx(ContextOptions{Backend::Scalar, {}});
    auto expect_error = [&](const Image& map, ErrorCategory category, const char* needle) {
        try {
            build_moment_table(ctx, map);
            FAIL() << "no error for " << needle;
        } catch (const Error& e) {
            EXPECT_EQ(e.category(), category);
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    expect_error(Image(0, 4, 1), ErrorCategory::InvalidArgument, "empty");
    expect_error(Image(4, 4, 2), ErrorCategory::InvalidArgument, "one channel");
    Image nan_map(4, 4, 1);
    nan_map.at(0, 2, 1) = std::nanf("");
    expect_error(nan_map, ErrorCategory::InvalidData, "non-finite");
    Image inf_map(4, 4, 1);
    inf_map.at(0, 3, 3) = INFINITY;
    expect_error(inf_map, ErrorCategory::InvalidData, "(3, 3)");
    Image outside(4, 4, 1);
    outside.at(0, 1, 0) = 1.5f;
    expect_error(outside, ErrorCategory::InvalidData, "outside [0, 1]");
    EXPECT_THROW(build_moment_table(ctx, Image(4, 4, 1), 3), Error);
}

}  // namespace
}  // namespace penumbra
