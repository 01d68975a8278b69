// The generic per-receiver lookup (host/backend/backend.h, receiver_lookup):
// every lookup-shaped entry of the kernel table runs through it on every
// backend of this machine and agrees with the scalar oracle, and anything
// else it is handed (an entry of another shape, a value that is no entry, a
// source of the wrong element type) is refused with a typed Error, never a
// crash.
//
// The reachability case of each entry is chosen by its Params and name
// (lookup_case below); a lookup-shaped entry with no case fails the test, so a
// new one is covered the day it joins the table. Tolerance: 2e-5 against the
// scalar oracle on the same source, the widest of the per-family cross-backend
// tolerances (EVSM's exp(), tests/kernels/moments_cross_backend_test.cpp);
// SIMD is bit-identical for the Chebyshev and MSM entries there.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <span>
#include <tuple>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "host/backend/backend.h"
#include "penumbra/ambient.h"
#include "penumbra/cascades.h"
#include "penumbra/chebyshev.h"
#include "penumbra/deep_shadow_map.h"
#include "penumbra/moments.h"
#include "penumbra/ssao.h"
#include "penumbra/pismo.h"
#include "support/backends.h"
#include "support/errors.h"
#include "support/maps.h"
#include "support/pismo_scenes.h"

namespace penumbra {
namespace {

using detail::KernelId;
using testing::backend_names;
using testing::backend_test_name;
using testing::expect_error;

constexpr double kLookupTolerance = 2e-5;

// A 9x5 map; receivers 7x3 (odd, below every lane count) and 33x1 (around
// 16 and 32 lanes) over its texel centres, depths straddling the map's.
const Image& depth_map()
{
    static const Image map = testing::random_depth(9, 5, 17);
    return map;
}

std::vector<Image> receiver_grids()
{
    return {testing::receivers_on_texels(7, 3, 9, 5, 0.1f, 0.9f, 5),
            testing::receivers_on_texels(33, 1, 9, 5, 0.1f, 0.9f, 6)};
}

template <class Params>
void set_dims(Params& p, const MomentTable& table, const Image& receivers, const Image& out)
{
    p.table = detail::dims_of(table);
    p.receivers = detail::dims_of(receivers);
    p.out = detail::dims_of(out);
    p.limbs = table.limbs();
}

// The sources, built once by the scalar oracle: every backend reads the same.
struct Sources {
    explicit Sources(Context& oracle)
        : chebyshev_float(build_moment_table(oracle, depth_map(), 2, Precision::Float)),
          chebyshev_exact(build_moment_table(oracle, depth_map(), 2, Precision::Exact)),
          msm_float(build_msm_table(oracle, depth_map(), Quantization::Bits32, Precision::Float)),
          msm_exact(build_msm_table(oracle, depth_map(), Quantization::None, Precision::Exact)),
          evsm_float(build_evsm_table(oracle, depth_map(), EvsmWarp{4, {}, {}, Quantization::Bits32}, Precision::Float)),
          evsm_exact(build_evsm_table(oracle, depth_map(), EvsmWarp{4, {}, {}, Quantization::None}, Precision::Exact)),
          deep(opaque_deep_map(depth_map())),
          deep_source({std::span(deep.offsets()), std::span(deep.depths()), std::span(deep.transmittances())})
    {
    }
    // The depth map as a deep map: an opaque step at each texel's depth.
    static DeepShadowMap opaque_deep_map(const Image& map)
    {
        DeepShadowMapBuilder builder(map.width(), map.height());
        for (int y = 0; y < map.height(); ++y)
            for (int x = 0; x < map.width(); ++x) {
                const float d = map.at(0, x, y);
                builder.add_pixel(std::vector<float>{d, d}, std::vector<float>{1.0f, 0.0f});
            }
        return builder.build();
    }
    MomentTable chebyshev_float, chebyshev_exact;
    MsmTable msm_float, msm_exact;
    EvsmTable evsm_float, evsm_exact;
    DeepShadowMap deep;
    detail::LookupSource deep_source;  // its three arrays (host/src/deep_lookup.cpp builds the same)
};

// One entry's run: fills `out` (the receivers' grid) on `context`.
using LookupRun = std::function<void(Context& context, const Image& receivers, Image& out)>;

template <KernelId K>
LookupRun run_of(const MomentTable& table, typename detail::KernelTraits<K>::Params p)
{
    return [&table, p](Context& context, const Image& receivers, Image& out) mutable {
        set_dims(p, table, receivers, out);
        std::vector<int> bad_rows(std::size_t(receivers.height()), 0);
        detail::receiver_lookup<K>(context.impl(), table, receivers, p, out, bad_rows.data());
    };
}

// A lookup of the raw depth map: the percentage-closer family reads no table
// (its Params' `depth` holds the map's dims), nor do the box methods' windows
// summed from the map (the `_direct` entries: `table` holds them, as
// checked_direct_lookup sets it).
template <KernelId K>
LookupRun map_run_of(const Image& map, typename detail::KernelTraits<K>::Params p,
                     pn_dims detail::KernelTraits<K>::Params::*map_dims)
{
    return [&map, p, map_dims](Context& context, const Image& receivers, Image& out) mutable {
        p.*map_dims = detail::dims_of(map);
        p.receivers = detail::dims_of(receivers);
        p.out = detail::dims_of(out);
        std::vector<int> bad_rows(std::size_t(receivers.height()), 0);
        detail::receiver_lookup<K>(context.impl(), map, receivers, p, out, bad_rows.data());
    };
}

// The ambient entries read volume records, not a map (penumbra/ambient.h):
// the factor of a box over the receivers' (u, v, z) as positions, and the
// red irradiance of one strong light along +x with the normals
// (u - 0.5, v - 0.5, z - 0.45), clamped into [0, 1] (the SH irradiance
// rings a little below 0 behind the light).
LookupRun ambient_volumes_run()
{
    AmbientVolume box;
    box.shape = AmbientVolume::Shape::Box;
    box.center = {0.5, 0.5, 0.5};
    box.half_size = {0.4, 0.4, 0.4};
    box.falloff_delay = 0.85;
    return [box](Context& context, const Image& receivers, Image& out) {
        const Image f = ambient_volume_factor(context, receivers, AmbientVolumes({box}));
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) out.at(0, x, y) = f.at(0, x, y);
    };
}

// One cascade: the map itself, the receivers' (u, v, z) as world positions
// (identity frame), selected by split depth so that every receiver is in it.
LookupRun cascade_mask_run()
{
    return [](Context& context, const Image& receivers, Image& out) {
        CascadeShadows s;
        s.axis_u = {1, 0, 0}, s.axis_v = {0, 1, 0}, s.axis_z = {0, 0, 1};
        s.cascades = {CascadeFrame{1, 0, 1, 0, 1, 0, 2}};
        s.maps = depth_map();
        Image rx(receivers.width(), receivers.height(), kCascadeReceiverChannels);
        for (int y = 0; y < rx.height(); ++y)
            for (int x = 0; x < rx.width(); ++x) {
                for (int c = 0; c < 3; ++c) rx.at(c, x, y) = receivers.at(c, x, y);
                rx.at(3, x, y) = 1;
                rx.at(4, x, y) = 1;
            }
        CascadeOptions o;  // biases of the other PCF cases' size: a texel of this map is 1/9
        o.selection = CascadeSelection::SplitDepth;
        o.bias_min = 0.01f, o.static_bias = 0.02f, o.bias_max = 0.1f;
        const Image mask = cascade_mask(context, s, rx, o);
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) out.at(0, x, y) = mask.at(0, x, y);
    };
}

LookupRun ambient_sh_run()
{
    return [](Context& context, const Image& receivers, Image& out) {
        Image normals(receivers.width(), receivers.height(), 3);
        const float centre[3] = {0.5f, 0.5f, 0.45f};
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < receivers.height(); ++y)
                for (int x = 0; x < receivers.width(); ++x) normals.at(c, x, y) = receivers.at(c, x, y) - centre[c];
        AmbientLighting l;
        l.light = project_rig(AmbientRig{{{{1, 0, 0}, {1, 1, 1}, 1.5}}});
        const Image e = ambient_irradiance(context, normals, l);
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) out.at(0, x, y) = std::clamp(e.at(0, x, y), 0.0f, 1.0f);
    };
}

// ssao_vo reads its pattern as the source and a view depth as the
// receivers: 1 + 2 z of the receivers' random z plane, the sphere 3 pixels
// wide (a narrow view, no cap), no falloff, 16 pairs renormalised over the
// samples on screen, the AO term: the nearest pixels are open (near 1), the
// farthest nearly closed.
LookupRun ssao_vo_run()
{
    return [](Context& context, const Image& receivers, Image& out) {
        Image depth(receivers.width(), receivers.height(), 1);
        for (int y = 0; y < depth.height(); ++y)
            for (int x = 0; x < depth.width(); ++x) depth.at(0, x, y) = 1.0f + 2.0f * receivers.at(2, x, y);
        SsaoOptions o;
        o.radius = 1.0;
        o.pairs = 16;
        o.falloff = 1000;
        o.max_screen_radius = 1.0;
        o.unusable = SsaoUnusable::Renormalise;
        ssao_obscurance(context, depth, 10.0, o, out);
    };
}

// Pismo's two passes run together (penumbra/pismo.h): the grid's (u, v) as
// ground points x = 4u - 2, z = v - 1/2 of the half-plane scene, across its
// penumbra and on both sides (support/pismo_scenes.h).
LookupRun pismo_run()
{
    return [](Context& context, const Image& receivers, Image& out) {
        reference::LayeredMapOptions mo;
        mo.size = 64;
        static const PismoMaps maps =
            testing::library_maps(reference::render_pismo_maps(testing::half_plane_scene(), 0, mo));
        Image world(receivers.width(), receivers.height(), 3);
        for (int y = 0; y < receivers.height(); ++y)
            for (int x = 0; x < receivers.width(); ++x) {
                world.at(0, x, y) = 4 * receivers.at(0, x, y) - 2;
                world.at(2, x, y) = receivers.at(1, x, y) - 0.5f;
            }
        pismo_shade(context, maps, world, {}, out);
    };
}

// The Params of each lookup-shaped entry, as its operation fills them
// (host/src/chebyshev.cpp, moments.cpp); an empty run for an entry with no case.
template <KernelId K>
LookupRun lookup_case(const Sources& s)
{
    using Params = typename detail::KernelTraits<K>::Params;
    constexpr bool exact = std::is_same_v<detail::LookupSourcesOf<K>, std::tuple<std::uint32_t>>;
    const std::string_view name = detail::kernel_name(K);
    const bool direct = name.ends_with("_direct");
    if constexpr (std::is_same_v<Params, ChebyshevParams>) {
        const MomentTable& table = exact ? s.chebyshev_exact : s.chebyshev_float;
        ChebyshevParams p{};
        p.min_variance = kDefaultMinVariance;
        p.bleed = 0.1f;
        p.radius = 1;
        p.light_size = 0.2f;
        p.max_radius = exact ? kExactMaxRadius - 1 : 9;
        if (name == "vsm_direct") return map_run_of<K>(depth_map(), p, &Params::table);
        if (name.starts_with("vsm_") || name.starts_with("vssm_")) return run_of<K>(table, p);
    } else if constexpr (std::is_same_v<Params, MomentParams>) {
        MomentParams p{};
        p.radius = 1;
        if (name.starts_with("evsm_")) {
            const EvsmTable& t = exact || direct ? s.evsm_exact : s.evsm_float;
            p.channels = 4;
            p.exponent_positive = t.positive;
            p.exponent_negative = t.negative;
            p.min_variance = kDefaultMinVariance;
            if (direct) return map_run_of<K>(depth_map(), p, &Params::table);
            return run_of<K>(t.sums, p);
        }
        const Quantization q = exact || direct ? Quantization::None : Quantization::Bits32;
        p.storage = PN_MOMENTS_POWER;
        p.moment_bias = default_moment_bias(q);
        p.depth_bias = default_depth_bias(q);
        p.pivot_floor = exact || direct ? 0x1p-45f : 0x1p-22f;
        p.light_size = 0.2f;
        p.max_radius = exact ? kExactMaxRadius - 1 : 9;
        if (name == "msm_direct") return map_run_of<K>(depth_map(), p, &Params::table);
        if (name.starts_with("msm_")) return run_of<K>((exact ? s.msm_exact : s.msm_float).sums, p);
    } else if constexpr (std::is_same_v<Params, PcfParams>) {
        PcfParams p{};
        p.bias = PcfBias{PN_BIAS_CONSTANT, 1e-3f, 1.0f, 0.0f, 0.02f};
        p.radius = 0;  // a wider box of random depths is never all lit
        p.grid = 4;
        p.sigma = 1.0f;
        p.taps = 16;
        p.disc_radius = 2.0f;
        p.rotate = 1;
        if (name.starts_with("pcf")) return map_run_of<K>(depth_map(), p, &Params::depth);
    } else if constexpr (std::is_same_v<Params, DsmParams>) {
        DsmParams p{};  // host/src/deep_lookup.cpp
        p.map = pn_dims{s.deep.width(), s.deep.height(), s.deep.width(), s.deep.width() * s.deep.height()};
        p.filter = PN_DSM_BOX;  // nearest pixel: its opaque step is lit or shadowed, as PCF r = 0
        p.search_top = 2;
        p.vertices = int(s.deep.vertex_count());
        p.last_vertex = p.vertices - 1;
        p.bias = 1e-3f;
        return [&source = s.deep_source, p](Context& context, const Image& receivers, Image& out) mutable {
            p.receivers = detail::dims_of(receivers);
            p.out = detail::dims_of(out);
            std::vector<int> bad_rows(std::size_t(receivers.height()), 0);
            detail::receiver_lookup<K>(context.impl(), source, receivers, p, out, bad_rows.data());
        };
    } else if constexpr (std::is_same_v<Params, SoftPcfParams>) {
        SoftPcfParams p{};  // host/src/soft_pcf.cpp; discs a few texels wide on the 9x5 map
        p.bias = PcfBias{PN_BIAS_CONSTANT, 1e-3f, 1.0f, 0.0f, 0.02f};
        p.blocker_samples = 16;
        p.filter_samples = 24;
        p.light_size = 0.3f;
        p.min_radius = 0.02f;
        p.max_radius = 0.3f;
        p.bias_slope = 2.0f;
        if (name == "pcss" || name == "burley") return map_run_of<K>(depth_map(), p, &Params::depth);
    } else if constexpr (std::is_same_v<Params, CascadeParams>) {
        if (name == "cascade_mask") return cascade_mask_run();
    } else if constexpr (std::is_same_v<Params, AmbientParams>) {
        if (name == "ambient_volumes") return ambient_volumes_run();
        if (name == "ambient_sh") return ambient_sh_run();
    } else if constexpr (std::is_same_v<Params, SsaoParams>) {
        if (name == "ssao_vo") return ssao_vo_run();
    } else if constexpr (std::is_same_v<Params, PismoParams>) {
        return pismo_run();
    }
    return {};
}

using ReceiverLookup = ::testing::TestWithParam<std::string>;

PN_BACKEND_TEST(ReceiverLookup, EveryLookupShapedEntryAgreesWithTheScalarOracle)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    Context& oracle = testing::scalar_oracle(backend);
    const Sources sources(oracle);
    int entries = 0;
    for (int i = 0; i < detail::kKernelCount; ++i) {
        const KernelId id = KernelId(i);
        detail::visit_kernel(
            id,
            [&](auto k) {
                constexpr KernelId K = decltype(k)::value;
                if constexpr (detail::is_lookup_shaped<K>) {
                    ++entries;
                    const LookupRun run = lookup_case<K>(sources);
                    if (!run) {
                        ADD_FAILURE() << "lookup-shaped entry " << detail::kernel_name(K)
                                      << " has no case in lookup_case(): add one";
                        return;
                    }
                    int lit = 0, shadowed = 0;  // a case that shades nothing would prove nothing
                    for (const Image& rx : receiver_grids()) {
                        Image expected(rx.width(), rx.height(), 1), got(rx.width(), rx.height(), 1);
                        run(oracle, rx, expected);
                        run(ctx, rx, got);
                        const testing::Difference d = testing::difference(got, expected);
                        EXPECT_LE(d.max, kLookupTolerance) << detail::kernel_name(K) << " " << rx.width() << "x"
                                                     << rx.height() << " on " << backend;
                        for (int y = 0; y < rx.height(); ++y)
                            for (int x = 0; x < rx.width(); ++x) {
                                const float v = expected.at(0, x, y);
                                ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << detail::kernel_name(K) << ": oracle " << v;
                                lit += v > 0.9f;
                                shadowed += v < 0.1f;
                            }
                    }
                    EXPECT_GT(lit, 0) << detail::kernel_name(K);
                    EXPECT_GT(shadowed, 0) << detail::kernel_name(K) << " (lit " << lit << ")";
                }
            },
            [] { ADD_FAILURE() << "visit_kernel missed a table entry"; });
    }
    EXPECT_GE(entries, 10) << "the table's lookups: vsm, vssm, msm, msm_soft, evsm, float and exact";
}

INSTANTIATE_TEST_SUITE_P(Backends, ReceiverLookup, ::testing::ValuesIn(testing::non_scalar_backends()),
                         backend_test_name);

using ReceiverLookupRefusal = ::testing::TestWithParam<std::string>;

PN_BACKEND_TEST(ReceiverLookupRefusal, RefusesWhatIsNoLookupWithATypedError)
{
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    const Sources sources(ctx);
    const Image rx = receiver_grids().front();
    Image out(rx.width(), rx.height(), 1);
    std::vector<int> bad_rows(std::size_t(rx.height()), 0);
    ChebyshevParams p{};
    set_dims(p, sources.chebyshev_exact, rx, out);
    p.radius = 1;
    auto run = [&](KernelId id, const detail::LookupSource& source) {
        ctx.impl().receiver_lookup(id, source, rx, &p, out, bad_rows.data());
    };
    int refused = 0;
    for (int i = 0; i < detail::kKernelCount; ++i) {
        const KernelId id = KernelId(i);
        const bool lookup = detail::visit_kernel(
            id, [](auto k) { return detail::is_lookup_shaped<decltype(k)::value>; }, [] { return false; });
        if (lookup) continue;
        ++refused;
        expect_error([&] { run(id, sources.chebyshev_exact); }, ErrorCategory::InvalidArgument, "receiver_lookup",
                     std::string(detail::kernel_name(id)));
        const Error e = testing::error_from([&] { run(id, sources.chebyshev_exact); }).value();
        EXPECT_EQ(e.parameter(), "kernel");
    }
    EXPECT_GE(refused, 8) << "the table builds, bilateral and SDF entries are not lookups";
    for (int outside : {-1, detail::kKernelCount, 1000})
        expect_error([&] { run(KernelId(outside), sources.chebyshev_exact); }, ErrorCategory::InvalidArgument,
                     "receiver_lookup", "number " + std::to_string(outside));
    // A source of the wrong element type: an exact entry given a float table or
    // an image, a float entry given an exact table.
    expect_error([&] { run(KernelId::vsm_exact, sources.chebyshev_float); }, ErrorCategory::InvalidArgument,
                 "receiver_lookup", "exact moment table");
    expect_error([&] { run(KernelId::vsm_exact, depth_map()); }, ErrorCategory::InvalidArgument, "receiver_lookup",
                 "exact moment table");
    expect_error([&] { run(KernelId::vsm_float, sources.chebyshev_exact); }, ErrorCategory::InvalidArgument,
                 "receiver_lookup", "float values");
    // A source of several arrays for an entry of one buffer, and the reverse.
    expect_error([&] { run(KernelId::vsm_float, sources.deep_source); }, ErrorCategory::InvalidArgument,
                 "receiver_lookup", "one float buffer");
    expect_error([&] { run(KernelId::dsm_lookup, sources.chebyshev_float); }, ErrorCategory::InvalidArgument,
                 "receiver_lookup", "reads 3 source arrays");
    const std::vector<float> values(4, 0.5f);
    const detail::LookupSource swapped({std::span(values), std::span(values), std::span(values)});
    expect_error([&] { run(KernelId::dsm_lookup, swapped); }, ErrorCategory::InvalidArgument, "receiver_lookup",
                 "a uint array");
}

INSTANTIATE_TEST_SUITE_P(Backends, ReceiverLookupRefusal, ::testing::ValuesIn(backend_names()), backend_test_name);

}  // namespace
}  // namespace penumbra
