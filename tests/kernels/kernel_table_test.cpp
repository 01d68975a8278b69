// The kernel table (kernels/kernel_table.h) against every backend, and the
// purity of the kernel descriptions (STYLE.md items 2 and 7).
//
// Table -> CPU tables: CpuKernels's entry members are generated from the
// table and filled from it (simd/cpu_kernels.cpp), so an entry no description
// defines does not compile; here every member, and every hand-listed helper,
// is set on every ISA this build holds and this CPU runs. Table <-> OpenCL:
// tests/host/opencl_programs_test.cpp (each entry's program holds that
// kernel alone). Table <-> sources: every PN_KERNEL in kernels/ is
// an entry and every entry a PN_KERNEL.
#include "host/backend/kernel_id.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "penumbra/config.h"
#include "simd/cpu_kernels.h"
#include "support/backends.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using detail::KernelId;

std::vector<KernelId> table_ids()
{
    std::vector<KernelId> ids;
    for (int i = 0; i < detail::kKernelCount; ++i) ids.push_back(KernelId(i));
    return ids;
}

std::set<std::string> table_names()
{
    std::set<std::string> names;
    for (KernelId id : table_ids()) names.emplace(detail::kernel_name(id));
    return names;
}

TEST(KernelTable, NamesAreUniqueAndFamiliesNamed)
{
    ASSERT_GE(detail::kKernelCount, 8);
    EXPECT_EQ(table_names().size(), std::size_t(detail::kKernelCount)) << "two entries share a name";
    std::set<std::string_view> families;
    for (KernelId id : table_ids()) {
        EXPECT_FALSE(detail::kernel_name(id).empty());
        families.insert(detail::family_name(detail::kernel_family(id)));
    }
    EXPECT_EQ(families.size(), std::size_t(detail::kFamilyCount)) << "a family with no entry";
}

TEST(KernelTable, EveryEntryAndHelperIsSetInEveryCpuTable)
{
    for (const std::string& isa : testing::cpu_backend_names()) {
        const cpu::CpuKernels& table = cpu::kernels_for(isa);
        EXPECT_EQ(std::string(table.isa), isa);
        EXPECT_GE(table.lanes, 1);
#define PN_CHECK_ENTRY(family, name, shape, Params, buffers) \
    EXPECT_NE(cpu::entry<KernelId::name>(table), nullptr) << isa << " has no " #name;
        PN_KERNEL_TABLE(PN_CHECK_ENTRY)
#undef PN_CHECK_ENTRY
        for (const void* helper :
             {(const void*)table.sat_block_float, (const void*)table.sat_block_exact,
              (const void*)table.bilateral_full_span, (const void*)table.bilateral_horizontal_span,
              (const void*)table.bilateral_vertical_span, (const void*)table.depth_convert_rows,
              (const void*)table.receiver_v_bounds,
              (const void*)table.dialect_double_probe,
              (const void*)table.dialect_gather_pair_probe, (const void*)table.dialect_index_probe})
            EXPECT_NE(helper, nullptr) << isa;
    }
}

// The dialect's double lanes (kernels/dialect.h) on every CPU binding: lane
// order across the two halves of a SIMD pn_double, uint32 above 2^31, the
// roundings, and masks both ways. (OpenCL's binding is plain double; the
// moment kernels' cross-backend tests cover it.)
TEST(DialectDouble, ConversionsArithmeticAndMasksOnEveryCpuBinding)
{
    for (const std::string& isa : testing::cpu_backend_names()) {
        const cpu::CpuKernels& table = cpu::kernels_for(isa);
        const int n = table.lanes;
        std::vector<float> f(n), g(4 * std::size_t(n));
        std::vector<cpu::u32> u(n), v(n);
        std::vector<double> d(3 * std::size_t(n));
        for (int i = 0; i < n; ++i) {
            f[i] = 0.1f + 0.9f * float(i) / float(n);  // lane-distinct, some above 0.25 / 0.5 / 0.75
            u[i] = 0xFFFFFFFFu - cpu::u32(i) * 0x10001u;  // above 2^31: the unsigned conversion
        }
        table.dialect_double_probe(f.data(), u.data(), d.data(), g.data(), v.data());
        bool any_above = false;
        for (int i = 0; i < n; ++i) any_above |= double(f[i]) > 0.75;
        for (int i = 0; i < n; ++i) {
            const double x = f[i];
            EXPECT_EQ(d[i], x) << isa << " lane " << i;
            EXPECT_EQ(d[n + i], double(u[i])) << isa << " lane " << i;
            EXPECT_EQ(d[2 * n + i], (x * 3.0 - 1.0) / 7.0) << isa << " lane " << i;
            EXPECT_EQ(g[i], float(x * 3.0)) << isa << " lane " << i;
            EXPECT_EQ(g[n + i], x > 0.5 ? 1.0f : 0.0f) << isa << " lane " << i;
            EXPECT_EQ(g[2 * n + i], f[i] > 0.25f ? 1.0f : 0.0f) << isa << " lane " << i;
            EXPECT_EQ(g[3 * n + i], any_above ? 1.0f : 0.0f) << isa << " lane " << i;
            EXPECT_EQ(v[i], u[i] / 2u) << isa << " lane " << i;
        }
    }
}

// 1000 elements spread over the whole uint32 range, all distinct.
std::vector<cpu::u32> spread_table()
{
    std::vector<cpu::u32> table(1000);
    for (std::size_t i = 0; i < table.size(); ++i) table[i] = cpu::u32(0x9E3779B9u * (i + 1));
    return table;
}

// pn_ugather_pair (kernels/dialect.h) on every CPU binding: lane order across
// the two 64-bit gathers of a strip, odd (not 8-byte aligned) indices.
TEST(DialectGatherPair, AdjacentElementsPerLaneOnEveryCpuBinding)
{
    const std::vector<cpu::u32> table = spread_table();
    for (const std::string& isa : testing::cpu_backend_names()) {
        const cpu::CpuKernels& t = cpu::kernels_for(isa);
        const int n = t.lanes;
        std::vector<int> index(n);
        std::vector<cpu::u32> first(n), second(n);
        for (int i = 0; i < n; ++i) index[i] = (i * 37 + 11) % 900;  // odd and even, out of order
        t.dialect_gather_pair_probe(table.data(), index.data(), first.data(), second.data());
        for (int i = 0; i < n; ++i) {
            EXPECT_EQ(first[i], table[index[i]]) << isa << " lane " << i;
            EXPECT_EQ(second[i], table[index[i] + 1]) << isa << " lane " << i;
        }
    }
}

// Index patterns a coherent strip of receivers produces, and their near
// misses: a run over every lane from an odd (not 8-byte aligned) start, a run
// in the first or the second half only, two half runs that do not join, a
// run of the other step, and one lane off by one. Session 15 read runs by
// vector loads instead of gathers and then reverted it (docs/moment_table.md,
// "Session 15"); the gathers must read these as any other indices.
std::vector<std::vector<int>> run_patterns(int lanes, int step)
{
    const int other = step == 1 ? 2 : 1;
    std::vector<std::vector<int>> patterns(6, std::vector<int>(lanes));
    for (int i = 0; i < lanes; ++i) {
        patterns[0][i] = 11 + step * i;
        patterns[1][i] = i < lanes / 2 ? 11 + step * i : 500 + 7 * i;
        patterns[2][i] = i < lanes / 2 ? 300 - 5 * i : 11 + step * i;
        patterns[3][i] = i < lanes / 2 ? 11 + step * i : 400 + step * i;
        patterns[4][i] = 11 + other * i;
        patterns[5][i] = 11 + step * i + (i == lanes - 1);
    }
    return patterns;
}

TEST(DialectGatherPair, RunsOfAdjacentIndicesReadTheSameElements)
{
    const std::vector<cpu::u32> table = spread_table();
    for (const std::string& isa : testing::cpu_backend_names()) {
        const cpu::CpuKernels& t = cpu::kernels_for(isa);
        const int n = t.lanes;
        for (const std::vector<int>& index : run_patterns(n, 1)) {
            std::vector<cpu::u32> first(n), second(n);
            t.dialect_gather_pair_probe(table.data(), index.data(), first.data(), second.data());
            for (int i = 0; i < n; ++i) {
                EXPECT_EQ(first[i], table[index[i]]) << isa << " lane " << i << " from " << index[0];
                EXPECT_EQ(second[i], table[index[i] + 1]) << isa << " lane " << i << " from " << index[0];
            }
        }
    }
}

// pn_ugather_upair through the probe on every CPU binding: pattern p's pairs
// minus pattern (p + shift)'s, each part wrapping, joined exactly.
void expect_upair_patterns(const std::function<std::vector<std::vector<int>>(int lanes)>& make, std::size_t shift)
{
    const std::vector<cpu::u32> table = spread_table();
    for (const std::string& isa : testing::cpu_backend_names()) {
        const cpu::CpuKernels& t = cpu::kernels_for(isa);
        const int n = t.lanes;
        const std::vector<std::vector<int>> patterns = make(n);
        for (std::size_t p = 0; p < patterns.size(); ++p) {
            const std::vector<int>& a = patterns[p];
            const std::vector<int>& b = patterns[(p + shift) % patterns.size()];
            std::vector<double> joined(n);
            t.dialect_upair_probe(table.data(), a.data(), b.data(), joined.data());
            for (int i = 0; i < n; ++i) {
                const cpu::u32 first = table[a[i]] - table[b[i]], second = table[a[i] + 1] - table[b[i] + 1];
                EXPECT_EQ(joined[i], double(first) * 65536.0 + double(second)) << isa << " lane " << i << " pattern " << p;
            }
        }
    }
}

TEST(DialectUpair, RunsOfPairsReadTheSameElements)
{
    expect_upair_patterns([](int lanes) { return run_patterns(lanes, 2); }, 1);
}

// Spans of a raster denser than the map (the session 15 attempt read them by
// masked loads and a permute, reverted): lanes that repeat a corner or skip
// one, out of order, a span of exactly 30 elements and of 32, one ending at
// the table's last element, one from an odd start.
std::vector<std::vector<int>> span_patterns(int lanes, int table_size)
{
    std::vector<std::vector<int>> patterns(6, std::vector<int>(lanes));
    for (int i = 0; i < lanes; ++i) {
        const int h = i % std::max(lanes / 2, 1), last = std::max(lanes / 2 - 1, 1);
        patterns[0][i] = 100 + 2 * (i * 3 / 5);
        patterns[1][i] = 240 - 2 * ((i * 7) % lanes);
        patterns[2][i] = 300 + (h * 30) / last;
        patterns[3][i] = 400 + (h == last ? 32 : h);
        patterns[4][i] = table_size - 2 - (h * 30) / last;
        patterns[5][i] = 511 + 2 * ((h * 5) % 8);
    }
    return patterns;
}

TEST(DialectUpair, SpansOfPairsReadTheSameElements)
{
    expect_upair_patterns([](int lanes) { return span_patterns(lanes, int(spread_table().size())); }, 3);
}

// pn_upair (kernels/dialect.h) on every CPU binding: both parts of a gathered
// pair subtract on their own, wrapping (the table's values are spread over the
// whole uint32 range), and join exactly as first 2^16 + second, lane by lane.
TEST(DialectUpair, WrappingDifferencesJoinExactlyOnEveryCpuBinding)
{
    const std::vector<cpu::u32> table = spread_table();
    for (const std::string& isa : testing::cpu_backend_names()) {
        const cpu::CpuKernels& t = cpu::kernels_for(isa);
        const int n = t.lanes;
        std::vector<int> a(n), b(n);
        std::vector<double> joined(n);
        for (int i = 0; i < n; ++i) {
            a[i] = (i * 37 + 11) % 900;
            b[i] = (i * 53 + 4) % 900;
        }
        t.dialect_upair_probe(table.data(), a.data(), b.data(), joined.data());
        for (int i = 0; i < n; ++i) {
            const cpu::u32 first = table[a[i]] - table[b[i]], second = table[a[i] + 1] - table[b[i] + 1];
            EXPECT_EQ(joined[i], double(first) * 65536.0 + double(second)) << isa << " lane " << i;
        }
    }
}

// The dialect's index lanes (kernels/dialect.h: pn_iless, pn_iselect,
// pn_uint_to_index) on every CPU binding: signed compares across the lanes,
// equal values, negative ints from uints at and above 2^31. (OpenCL's binding
// is plain int; the deep map lookup's tests cover it on every backend.)
TEST(DialectIndex, ComparesAndSelectsIntLanesOnEveryCpuBinding)
{
    for (const std::string& isa : testing::cpu_backend_names()) {
        const cpu::CpuKernels& t = cpu::kernels_for(isa);
        const int n = t.lanes;
        std::vector<cpu::u32> a(n), b(n);
        for (int i = 0; i < n; ++i) {
            a[i] = cpu::u32(i * 7919 % 23);
            b[i] = i % 3 == 0 ? a[i] : cpu::u32(i * 104729 % 29);
            if (i % 5 == 4) a[i] = 0x80000000u + cpu::u32(i);  // negative as an index
        }
        std::vector<float> less(n);
        std::vector<int> selected(n);
        t.dialect_index_probe(a.data(), b.data(), less.data(), selected.data());
        for (int i = 0; i < n; ++i) {
            const int ia = int(a[i]), ib = int(b[i]);
            EXPECT_EQ(less[i], ia < ib ? 1.0f : 0.0f) << isa << " lane " << i;
            EXPECT_EQ(selected[i], ia < ib ? ia : ib) << isa << " lane " << i;
        }
    }
}

// ---- the kernel descriptions ------------------------------------------------------

struct Source {
    std::string name, text;
};

std::vector<Source> kernel_sources()
{
    std::vector<Source> sources;
    for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(PENUMBRA_SOURCE_DIR) / "kernels")) {
        if (!entry.is_regular_file()) continue;
        std::ifstream in(entry.path(), std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        sources.push_back({entry.path().filename().string(), text.str()});
    }
    return sources;
}

// Comments replaced by a space (string literals do not occur in descriptions).
// A loop, not a regex: libstdc++'s regex recurses once per character of a
// match, and a long block comment overflowed the stack under AddressSanitizer.
std::string without_comments(const std::string& text)
{
    std::string code;
    code.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        if (text.compare(i, 2, "/*") == 0) {
            const std::size_t end = text.find("*/", i + 2);
            i = end == std::string::npos ? text.size() : end + 2;
            code += ' ';
        } else if (text.compare(i, 2, "//") == 0) {
            i = std::min(text.find('\n', i), text.size());
            code += ' ';
        } else {
            code += text[i++];
        }
    }
    return code;
}

// What a description must not say: the ISA, xsimd, OpenCL's own spellings, or
// a lane count (the bindings' PN_LANES / kLanes, or a macro of the sort).
const std::vector<std::pair<std::string, std::regex>>& forbidden()
{
    static const std::vector<std::pair<std::string, std::regex>> patterns = {
        {"xsimd", std::regex("xsimd", std::regex::icase)},
        {"get_global_id", std::regex("get_global_id")},
        {"__kernel", std::regex("__kernel")},
        {"_mm intrinsic", std::regex(R"((^|[^A-Za-z0-9])_mm)", std::regex::icase)},
        {"batch<", std::regex(R"(batch\s*<)")},
        {"avx", std::regex(R"((^|[^A-Za-z0-9])avx)", std::regex::icase)},
        {"sse", std::regex(R"((^|[^A-Za-z0-9])sse)", std::regex::icase)},
        {"lane count macro", std::regex(R"(\b([A-Z0-9]+_)*LANES?(_[A-Z0-9]+)*\b|\bkLanes\b|#\s*define\s+\w*(WIDTH|VECTOR|SIMD)\w*\s+[0-9])")},
    };
    return patterns;
}

std::vector<std::string> violations(const std::string& text)
{
    std::vector<std::string> found;
    for (const auto& [what, pattern] : forbidden()) {
        std::smatch m;
        if (std::regex_search(text, m, pattern)) found.push_back(what + " (\"" + m.str() + "\")");
    }
    return found;
}

TEST(DialectPurity, PatternsCatchWhatTheyShould)
{
    for (const char* bad : {"xsimd::batch<float> v;", "__m512 a = _mm512_add_ps(b, c);", "size_t i = get_global_id(0);",
                            "__kernel void f()", "#if defined(__AVX2__)", "// for SSE4.2", "#define PN_LANES 8", "PN_LANE_COUNT",
                            "x += kLanes;", "#define PN_SIMD_WIDTH 16", "batch <float>"})
        EXPECT_FALSE(violations(bad).empty()) << bad;
    for (const char* fine : {"it passes the classes", "pn_float pn_lane_x;", "PN_KERNEL void vsm_float(",
                             "/* plane */ PN_PLANE(ptr, d, 0)", "pn_mm", "#define PN_EXACT_STEPS 65535.0f"})
        EXPECT_TRUE(violations(fine).empty()) << fine << ": " << ::testing::PrintToString(violations(fine));
}

TEST(DialectPurity, KernelDescriptionsNameNoIsaNoLanesNoOpenCl)
{
    const std::vector<Source> sources = kernel_sources();
    ASSERT_GE(sources.size(), 6u) << "read kernels/ from " << PENUMBRA_SOURCE_DIR;
    bool saw_dialect = false;
    for (const Source& s : sources) {
        // dialect.h's comment is the contract and names what it forbids; its code must not.
        const bool dialect = s.name == "dialect.h";
        saw_dialect |= dialect;
        const std::string text = dialect ? without_comments(s.text) : s.text;
        ASSERT_GT(text.size(), 100u) << s.name;
        for (const std::string& v : violations(text)) ADD_FAILURE() << "kernels/" << s.name << " mentions " << v;
    }
    EXPECT_TRUE(saw_dialect);
}

// An entry written once for both table types (kernels/dialect.h,
// PN_TABLE_VARIANTS) is `PN_KERNEL void NAME_##variant(`: entries NAME_float
// and NAME_exact.
TEST(DialectPurity, EveryKernelEntryPointIsInTheTable)
{
    std::set<std::string> declared;
    const std::regex entry(R"(PN_KERNEL\s+void\s+(\w+?)(##\s*variant)?\s*\()");
    for (const Source& s : kernel_sources()) {
        if (s.name == "dialect.h") continue;
        const std::string code = without_comments(s.text);
        for (auto it = std::sregex_iterator(code.begin(), code.end(), entry); it != std::sregex_iterator(); ++it) {
            if (!(*it)[2].matched) {
                declared.insert((*it)[1].str());
                continue;
            }
            for (const char* variant : {"float", "exact"}) declared.insert((*it)[1].str() + variant);
        }
    }
    EXPECT_EQ(declared, table_names()) << "a PN_KERNEL missing from kernels/kernel_table.h, or an entry with no kernel";
}

}  // namespace
}  // namespace penumbra
