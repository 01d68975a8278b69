// The CPU's banded schedule of the direct window sums (simd/cpu_direct_sums.h)
// against the per-tap conversion it replaces (launch_pixels over the stored
// map), on every CPU table (scalar, each ISA): the same bits for vsm_direct,
// msm_direct and evsm_direct in every non-normalised convention, at radii 1
// and 2, on 1x1 and 7x3 maps and on maps of several bands with receiver
// widths around the lane counts; and a band holding NaN receivers and row
// tails reads inside its buffer and flags its rows.
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
#include "support/depth_conventions.h"
#include "support/maps.h"

namespace penumbra {
namespace {

using detail::KernelId;

std::vector<std::string> cpu_tables()
{
    std::vector<std::string> names{"scalar"};
    for (std::string_view isa : cpu::supported_isas()) names.emplace_back(isa);
    return names;
}

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

// Entry K on one CPU table, per tap (bands false) or in bands.
template <KernelId K>
Shaded shade(const cpu::CpuKernels& kernels, const Image& map, const Image& rx, int radius, const DepthConvention& c,
             bool bands)
{
    Shaded s{Image(rx.width(), rx.height(), 1), std::vector<int>(std::size_t(rx.height()), 0)};
    const auto p = direct_params<typename detail::KernelTraits<K>::Params>(map, rx, s.out, radius, c);
    if (bands)
        cpu::launch_direct_sums<K>(kernels, map.plane(0), rx, s.out, s.bad_rows.data(), p);
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
    for (const std::string& isa : cpu_tables())
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
            for (const std::string& isa : cpu_tables()) {
                cpu::MapRows rows;
                ASSERT_TRUE(cpu::band_map_rows(cpu::kernels_for(isa), rx, detail::dims_of(map), radius, 32, 64, rows));
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

// Receivers spread over the whole map convert per tap: a band of one row
// whose windows read every map row converts more texels than it has taps.
TEST(DirectSumBands, ScatteredReceiversKeepThePerTapConversion)
{
    const Image map = testing::random_depth(64, 64, 9);
    Image rx = testing::receivers_on_texels(16, 1, 64, 64, 0.1f, 0.9f, 10);
    for (int x = 0; x < 16; ++x) rx.at(1, x, 0) = float(x) / 15.0f;
    for (const std::string& isa : cpu_tables()) {
        cpu::MapRows rows;
        EXPECT_FALSE(cpu::band_map_rows(cpu::kernels_for(isa), rx, detail::dims_of(map), 1, 0, 1, rows)) << isa;
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
    for (const std::string& isa : cpu_tables()) {
        const cpu::CpuKernels& kernels = cpu::kernels_for(isa);
        const Shaded taps = shade<KernelId::vsm_direct>(kernels, map, rx, 1, c, false);
        const Shaded bands = shade<KernelId::vsm_direct>(kernels, map, rx, 1, c, true);
        for (int y : {33, 34, 35}) EXPECT_EQ(bands.bad_rows[std::size_t(y)], 1) << isa << " row " << y;
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 17; ++x) {
                if (y >= 33 && y <= 35) continue;
                EXPECT_EQ(taps.out.at(0, x, y), bands.out.at(0, x, y)) << isa << " at " << x << ", " << y;
            }
    }
}

}  // namespace
}  // namespace penumbra
