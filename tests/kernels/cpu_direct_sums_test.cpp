// The CPU's banded schedule of the direct window sums and soft discs
// (simd/cpu_direct_sums.h) against the per-tap conversion it replaces
// (launch_pixels over the stored map), on every CPU table (scalar, each ISA):
// the same bits for vsm_direct, msm_direct and evsm_direct (radii 1 and 2),
// pcss and burley in every non-normalised convention, on 1x1 and 7x3 maps
// and on maps of several bands with receiver widths around the lane counts;
// pcss's discs outgrowing their band run over the map; and a band holding
// NaN receivers and row tails reads inside its buffer and flags its rows.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "host/backend/backend.h"
#include "host/src/depth_conversion.h"
#include "simd/cpu_direct_sums.h"
#include "simd/cpu_schedule.h"
#include "support/backend_list.h"
#include "support/depth_conventions.h"
#include "support/maps.h"

namespace penumbra {
namespace {

using detail::KernelId;

// The Params of entry K as the host fills them for the whole stored map.
template <class Params>
Params direct_params(const Image& map, const Image& rx, const Image& out, int radius, const DepthConvention& c)
{
    Params p{};
    p.table = detail::dims_of(map);
    p.receivers = detail::dims_of(rx);
    p.out = detail::dims_of(out);
    p.radius = radius;
    p.min_variance = 2e-5f;
    p.convention = detail::kernel_conversion(c);
    p.direct = DirectMap{p.table, 0, p.convention};
    if constexpr (std::is_same_v<Params, MomentParams>) {
        p.channels = 4;
        p.moment_bias = 3e-5f;
        p.exponent_positive = 5.0f;
        p.exponent_negative = 5.0f;
    }
    return p;
}

struct Shaded {
    Image out;
    std::vector<int> bad_rows;
};

// pcss's or burley's Params as the host fills them (host/src/soft_pcf.cpp,
// pcf_family.h), their defaults' taps, discs a few texels wide on these maps:
// pcss's blocker disc 3.5 rows of 70, its band 7 rows either side (tap_reach).
SoftPcfParams soft_params(KernelId k, const Image& map, const Image& rx, const Image& out, const DepthConvention& c)
{
    SoftPcfParams p{};
    p.depth = detail::dims_of(map);
    p.receivers = detail::dims_of(rx);
    p.out = detail::dims_of(out);
    p.bias = PcfBias{PN_BIAS_CONSTANT, 0.002f, 0.0f, 0.0f, 0.0f};
    p.blocker_samples = 16;
    p.filter_samples = 24;
    if (k == KernelId::pcss) {
        p.light_size = 0.1f;
    } else {
        p.min_radius = 0.005f;
        p.max_radius = 0.05f;
        p.bias_slope = 2.0f;
    }
    p.convention = detail::kernel_conversion(c);
    p.direct = DirectMap{p.depth, 0, p.convention};
    return p;
}

// The Params of entry K for the whole stored map: a box window of `radius`, or a soft disc.
template <KernelId K>
typename detail::KernelTraits<K>::Params params_for(const Image& map, const Image& rx, const Image& out, int radius,
                                                    const DepthConvention& c)
{
    using Params = typename detail::KernelTraits<K>::Params;
    if constexpr (std::is_same_v<Params, SoftPcfParams>)
        return soft_params(K, map, rx, out, c);
    else
        return direct_params<Params>(map, rx, out, radius, c);
}

// Entry K on one CPU table, per tap (bands false) or in bands.
template <KernelId K>
Shaded shade(const cpu::CpuKernels& kernels, const Image& map, const Image& rx, int radius, const DepthConvention& c,
             bool bands)
{
    Shaded s{Image(rx.width(), rx.height(), 1), std::vector<int>(std::size_t(rx.height()), 0)};
    const auto p = params_for<K>(map, rx, s.out, radius, c);
    if (bands)
        cpu::launch_in_bands<K>(kernels, map.plane(0), rx, s.out, s.bad_rows.data(), p);
    else
        cpu::launch_pixels<K>(kernels, rx.width(), rx.height(), map.plane(0), rx.plane(0), s.out.plane(0),
                              s.bad_rows.data(), p);
    return s;
}

bool same_bits(const Image& a, const Image& b)
{
    for (int y = 0; y < a.height(); ++y)
        if (std::memcmp(a.row(0, y), b.row(0, y), sizeof(float) * std::size_t(a.width())) != 0) return false;
    return true;
}

template <KernelId K>
void expect_bands_equal_taps(const Image& normalized, const Image& receivers, int radius, const std::string& what)
{
    for (const std::string& isa : testing::cpu_backend_names())
        for (DepthConventionKind kind : testing::kAllConventions) {
            if (kind == DepthConventionKind::Normalized) continue;
            const DepthConvention c = testing::convention_of(kind);
            const Image map = testing::in_convention(normalized, 0, c);
            const Image rx = testing::in_convention(receivers, 2, c);
            const cpu::CpuKernels& kernels = cpu::kernels_for(isa);
            const Shaded taps = shade<K>(kernels, map, rx, radius, c, false);
            const Shaded bands = shade<K>(kernels, map, rx, radius, c, true);
            EXPECT_TRUE(same_bits(taps.out, bands.out))
                << detail::kernel_name(K) << " " << isa << " " << to_string(kind) << " r " << radius << " " << what;
            EXPECT_EQ(taps.bad_rows, bands.bad_rows) << isa << " " << what;
        }
}

template <KernelId K>
void expect_bands_equal_taps_at_odd_sizes()
{
    for (int radius : {1, 2}) {
        expect_bands_equal_taps<K>(testing::random_depth(1, 1, 3),
                                   testing::receivers_on_texels(1, 1, 1, 1, 0.1f, 0.9f, 4), radius, "1x1");
        expect_bands_equal_taps<K>(testing::random_depth(7, 3, 5),
                                   testing::receivers_on_texels(7, 3, 7, 3, 0.1f, 0.9f, 6), radius, "7x3");
        for (int width : {15, 16, 17, 33}) {
            // One receiver per texel over 70 rows: three bands, each converting its rows.
            const Image map = testing::random_depth(width, 70, 7 + width);
            const Image rx = testing::receivers_on_texels(width, 70, width, 70, 0.1f, 0.9f, 8);
            for (const std::string& isa : testing::cpu_backend_names()) {
                cpu::MapRows rows;
                const cpu::TapReach reach{detail::dims_of(map), 0.0f, radius, (2 * radius + 1) * (2 * radius + 1)};
                ASSERT_TRUE(cpu::band_map_rows(cpu::kernels_for(isa), rx, reach, 32, 64, rows));
                EXPECT_EQ(rows.first, 32 - radius) << isa;
                EXPECT_EQ(rows.last, 64 + radius) << isa;
            }
            expect_bands_equal_taps<K>(map, rx, radius, "width " + std::to_string(width));
        }
    }
}

TEST(DirectSumBands, VsmSameBitsAsThePerTapConversion) { expect_bands_equal_taps_at_odd_sizes<KernelId::vsm_direct>(); }
TEST(DirectSumBands, MsmSameBitsAsThePerTapConversion) { expect_bands_equal_taps_at_odd_sizes<KernelId::msm_direct>(); }
TEST(DirectSumBands, EvsmSameBitsAsThePerTapConversion)
{
    expect_bands_equal_taps_at_odd_sizes<KernelId::evsm_direct>();
}

// Depths in [0.4, 0.6] under receivers at z in [0.5, 0.9]: z_b >= 0.4, so
// pcss's filter disc, 0.05 (z - z_b) / z_b <= 0.0625 texture units, stays in
// its band (0.1 either side) and every strip reads the converted rows.
Image shallow_depth(int width, int height, std::uint32_t seed)
{
    Image map = testing::random_depth(width, height, seed);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) map.at(0, x, y) = 0.4f + 0.2f * map.at(0, x, y);
    return map;
}

template <KernelId K>
void expect_disc_bands_equal_taps_at_odd_sizes()
{
    expect_bands_equal_taps<K>(shallow_depth(1, 1, 3), testing::receivers_on_texels(1, 1, 1, 1, 0.5f, 0.9f, 4), 0,
                               "1x1");
    expect_bands_equal_taps<K>(shallow_depth(7, 3, 5), testing::receivers_on_texels(7, 3, 7, 3, 0.5f, 0.9f, 6), 0,
                               "7x3");
    for (int width : {15, 16, 17, 33}) {
        // One receiver per texel over 70 rows: three bands.
        const Image map = shallow_depth(width, 70, 7 + width);
        const Image rx = testing::receivers_on_texels(width, 70, width, 70, 0.5f, 0.9f, 8);
        const Image out(width, 70, 1);
        const cpu::TapReach reach = cpu::tap_reach(soft_params(K, map, rx, out, {}));
        for (const std::string& isa : testing::cpu_backend_names()) {
            cpu::MapRows rows;
            ASSERT_TRUE(cpu::band_map_rows(cpu::kernels_for(isa), rx, reach, 32, 64, rows)) << isa;
            // Rows 32 .. 63 at v = (y + 1/2) / 70, discs reaching 7 rows (pcss: rows 25 .. 70, clipped)
            // or 3.5 (burley: 29 .. 67), one margin row either side.
            EXPECT_EQ(rows.first, K == KernelId::pcss ? 24 : 28) << isa;
            EXPECT_EQ(rows.last, K == KernelId::pcss ? 70 : 69) << isa;
        }
        expect_bands_equal_taps<K>(map, rx, 0, "width " + std::to_string(width));
    }
}

TEST(DirectSumBands, PcssSameBitsAsThePerTapConversion) { expect_disc_bands_equal_taps_at_odd_sizes<KernelId::pcss>(); }
TEST(DirectSumBands, BurleySameBitsAsThePerTapConversion)
{
    expect_disc_bands_equal_taps_at_odd_sizes<KernelId::burley>();
}

// A blocker near the light (depth 0.02 in rows 40 .. 59 of 100) under
// receivers at z 0.8 .. 0.9: pcss's filter discs, 0.05 (z - z_b) / z_b up to
// 2.2 texture units, leave their band; the entry leaves those strips to the
// schedule (PN_BAND_RERUN), which runs them over the stored map: the same
// bits as per tap, and the rest of the band still reads converted rows.
TEST(DirectSumBands, PcssDiscsOutgrowingTheBandRunOverTheMap)
{
    Image normalized = shallow_depth(40, 100, 13);
    for (int y = 40; y < 60; ++y)
        for (int x = 10; x < 30; ++x) normalized.at(0, x, y) = 0.02f;
    const Image receivers = testing::receivers_on_texels(40, 100, 40, 100, 0.8f, 0.9f, 14);
    expect_bands_equal_taps<KernelId::pcss>(normalized, receivers, 0, "near blocker");
    const DepthConvention c = testing::convention_of(DepthConventionKind::Perspective);
    const Image map = testing::in_convention(normalized, 0, c);
    const Image rx = testing::in_convention(receivers, 2, c);
    for (const std::string& isa : testing::cpu_backend_names()) {
        const cpu::CpuKernels& kernels = cpu::kernels_for(isa);
        Image out(40, 100, 1);
        std::vector<int> bad_rows(100, 0);
        SoftPcfParams q = soft_params(KernelId::pcss, map, rx, out, c);
        std::vector<float> buffer;
        q.direct = cpu::convert_map_rows(kernels, map.plane(0), q.direct, cpu::MapRows{20, 90}, buffer);
        const auto entry = cpu::entry<KernelId::pcss>(kernels);
        entry(buffer.data(), rx.plane(0), out.plane(0), bad_rows.data(), q, 16, 50);  // over the blocker: wide discs
        EXPECT_EQ(out.at(0, 16, 50), PN_BAND_RERUN) << isa;
        entry(buffer.data(), rx.plane(0), out.plane(0), bad_rows.data(), q, 0, 30);  // 10 rows above: in the band
        EXPECT_GE(out.at(0, 0, 30), 0.0f) << isa;
    }
}

// Receivers spread over the whole map convert per tap: a band of one row
// whose windows read every map row converts more texels than it has taps.
TEST(DirectSumBands, ScatteredReceiversKeepThePerTapConversion)
{
    const Image map = testing::random_depth(64, 64, 9);
    Image rx = testing::receivers_on_texels(16, 1, 64, 64, 0.1f, 0.9f, 10);
    for (int x = 0; x < 16; ++x) rx.at(1, x, 0) = float(x) / 15.0f;
    for (const std::string& isa : testing::cpu_backend_names()) {
        cpu::MapRows rows;
        EXPECT_FALSE(cpu::band_map_rows(cpu::kernels_for(isa), rx, cpu::TapReach{detail::dims_of(map), 0.0f, 1, 9}, 0, 1, rows))
            << isa;
    }
}

// Rows 33 .. 35 of entry K's bands flagged; every other receiver as per tap.
template <KernelId K>
void expect_flagged_rows_alone(const cpu::CpuKernels& kernels, const Image& map, const Image& rx,
                               const DepthConvention& c, const std::string& isa)
{
    const Shaded taps = shade<K>(kernels, map, rx, 1, c, false);
    const Shaded bands = shade<K>(kernels, map, rx, 1, c, true);
    for (int y : {33, 34, 35}) EXPECT_EQ(bands.bad_rows[std::size_t(y)], 1) << isa << " row " << y;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            if (y >= 33 && y <= 35) continue;
            EXPECT_EQ(taps.out.at(0, x, y), bands.out.at(0, x, y))
                << detail::kernel_name(K) << " " << isa << " at " << x << ", " << y;
        }
}

// The tail lanes of a row (u = v = 0 beyond the width) in a band whose
// windows lie far from row 0, and a NaN, an infinite and a negative v in the
// next band: no read outside the band's buffer (ASan in CI), the NaN and
// infinity rows flagged, every other receiver as per tap.
TEST(DirectSumBands, NanReceiversAndTailsReadInsideTheBand)
{
    const Image normalized = testing::random_depth(17, 90, 11);
    Image receivers = testing::receivers_on_texels(17, 40, 17, 90, 0.1f, 0.9f, 12);
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 17; ++x) receivers.at(1, x, y) = (float(y) + 45.5f) / 90.0f;
    receivers.at(1, 3, 33) = std::numeric_limits<float>::quiet_NaN();
    receivers.at(0, 4, 34) = std::numeric_limits<float>::quiet_NaN();
    receivers.at(1, 5, 35) = std::numeric_limits<float>::infinity();
    receivers.at(1, 6, 36) = -1.0f;
    const DepthConvention c = testing::convention_of(DepthConventionKind::Perspective);
    const Image map = testing::in_convention(normalized, 0, c);
    const Image rx = testing::in_convention(receivers, 2, c);
    for (const std::string& isa : testing::cpu_backend_names()) {
        const cpu::CpuKernels& kernels = cpu::kernels_for(isa);
        expect_flagged_rows_alone<KernelId::vsm_direct>(kernels, map, rx, c, isa);
        expect_flagged_rows_alone<KernelId::pcss>(kernels, map, rx, c, isa);
        expect_flagged_rows_alone<KernelId::burley>(kernels, map, rx, c, isa);
    }
}

}  // namespace
}  // namespace penumbra
