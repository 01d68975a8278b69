#include "support/fidelity_cases.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "penumbra/chebyshev.h"
#include "penumbra/moment_table.h"
#include "penumbra/moments.h"
#include "support/moment_reference.h"

namespace penumbra::testing::fidelity {

namespace {

template <class F>
Image map_of(int width, int height, F depth)
{
    Image map(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            map.at(0, x, y) = std::clamp(float(depth((x + 0.5) / width, (y + 0.5) / height, x, y)), 0.0f, 1.0f);
    return map;
}

double ground(double s, double t) { return 0.45 + 0.25 * s + 0.1 * t + 0.05 * std::sin(6.0 * s) * std::cos(4.0 * t); }

}  // namespace

Image smooth_map(int width, int height)
{
    return map_of(width, height, [](double s, double t, int, int) { return ground(s, t); });
}

Image two_layer_map(int width, int height)
{
    return map_of(width, height, [](double s, double t, int, int) {
        // Occluder patches: discs and a bar, themselves slightly tilted.
        const bool disc = std::hypot(s - 0.3, t - 0.4) < 0.18 || std::hypot(s - 0.72, t - 0.7) < 0.12;
        const bool bar = std::fabs(t - 0.15) < 0.05 && s > 0.5;
        return disc || bar ? 0.3 + 0.05 * s : 0.8 + 0.1 * (s - t) * 0.5;
    });
}

Image constant_map(int width, int height, float z)
{
    return map_of(width, height, [z](double, double, int, int) { return z; });
}

Image checker_map(int width, int height, float a, float b)
{
    return map_of(width, height, [a, b](double, double, int x, int y) { return (x + y) % 2 ? b : a; });
}

Image receivers_for(const Image& map, int count, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::uniform_real_distribution<double> log_front(std::log(1e-3), std::log(3e-2));
    std::uniform_real_distribution<double> log_behind(std::log(1e-4), std::log(5e-2));
    Image rx(count, 1, 3);
    for (int i = 0; i < count; ++i) {
        const float u = unit(rng), v = unit(rng);
        const Box texel = texel_window(map.width(), map.height(), u, v, 0);
        const float surface = map.at(0, texel.x0, texel.y0);
        float z = surface;
        if (i % 4 == 1) z = surface - float(std::exp(log_front(rng)));
        if (i % 4 >= 2) z = surface + float(std::exp(log_behind(rng)));
        rx.at(0, i, 0) = u;
        rx.at(1, i, 0) = v;
        rx.at(2, i, 0) = z;
    }
    return rx;
}

Image receivers_at_texels(const Image& map, float dz)
{
    Image rx(map.width(), map.height(), 3);
    for (int y = 0; y < map.height(); ++y)
        for (int x = 0; x < map.width(); ++x) {
            rx.at(0, x, y) = (float(x) + 0.5f) / float(map.width());
            rx.at(1, x, y) = (float(y) + 0.5f) / float(map.height());
            rx.at(2, x, y) = map.at(0, x, y) + dz;
        }
    return rx;
}

bool is_soft(Method m) { return m == Method::Vssm || m == Method::MsmSoft; }

std::vector<Mode> modes_of(Method m)
{
    if (m == Method::MsmSoft) return {Mode::Default, Mode::Msm16};
    if (m == Method::Msm) return {Mode::Default, Mode::Msm16, Mode::Direct};
    if (m == Method::Vssm) return {Mode::Default};
    return {Mode::Default, Mode::Direct};
}

std::string mode_name(Method, Mode mode)
{
    if (mode == Mode::Direct) return "direct sums";
    return mode == Mode::Msm16 ? "--quantize 16" : "default table";
}

namespace {

// The opt-in 16-bit table's texels: n_k steps of o_k = n_k / 65535, decoded
// with the paper's inverse (tests/support/moment_reference.h, Peters & Klein
// 2015's printed matrix and offset, as the library's decoding uses them).
StoredMoments dequantized(const MsmTable& t)
{
    StoredMoments d{t.sums.width(), t.sums.height(), {}};
    d.texel.resize(std::size_t(d.width) * std::size_t(d.height));
    for (int y = 0; y < d.height; ++y)
        for (int x = 0; x < d.width; ++x) {
            std::array<double, 4> o{};
            for (int k = 0; k < 4; ++k) o[std::size_t(k)] = t.sums.exact_box_sum(k + 1, x, x + 1, y, y + 1) / 65535.0;
            const Moments4 b = optimized_decode(o);
            auto& texel = d.texel[std::size_t(y) * std::size_t(d.width) + std::size_t(x)];
            for (int k = 0; k < 4; ++k) texel[std::size_t(k)] = real(b[std::size_t(k + 1)]);
        }
    return d;
}

}  // namespace

namespace {

// Every setting's lookup in one table; `p` holds the table's parameters.
template <class Table, class Lookup>
std::vector<LibraryRun> lookups(const Table& table, const std::vector<Setting>& settings, const Params& p, Lookup lookup)
{
    std::vector<LibraryRun> runs;
    for (Setting s : settings) {
        LibraryRun r{lookup(table, s), p};
        r.params.radius = s.radius;
        r.params.light_size = s.light_size;
        runs.push_back(std::move(r));
    }
    return runs;
}

}  // namespace

std::vector<LibraryRun> run_library(Context& ctx, Method m, Mode mode, const Image& map, const Image& rx,
                             const std::vector<Setting>& settings, StoredMoments* stored)
{
    Params p;
    p.max_radius = kExactMaxRadius - 1;  // exact tables: the filter window and its slivers within 255 texels
    // The default mode is whatever the API's default arguments are: what
    // `penumbra shade` builds with no precision or quantization option.
    // Mode::Direct: the box methods' `Image depth` overloads, under the
    // default table's parameters (the same method, no table).
    const bool direct = mode == Mode::Direct;
    if (direct && is_soft(m)) throw std::invalid_argument(method_name(m) + " has no direct window sums");
    if (m == Method::Vsm && direct)
        return lookups(map, settings, p, [&](const Image& depth, Setting s) {
            return vsm(ctx, depth, rx, VsmOptions{s.radius, p.min_variance, p.bleed});
        });
    if (m == Method::Vsm || m == Method::Vssm) {
        return lookups(build_moment_table(ctx, map), settings, p, [&](const MomentTable& t, Setting s) {
            return m == Method::Vsm ? vsm(ctx, t, rx, VsmOptions{s.radius, p.min_variance, p.bleed})
                                    : vssm(ctx, t, rx, VssmOptions{s.light_size, p.min_variance, p.bleed});
        });
    }
    if (m == Method::Msm && direct) {
        p.moment_bias = default_moment_bias(Quantization::None);
        p.msm_depth_bias = default_depth_bias(Quantization::None);
        return lookups(map, settings, p, [&](const Image& depth, Setting s) {
            return msm(ctx, depth, rx, MsmOptions{s.radius, {}, {}});
        });
    }
    if (m == Method::Msm || m == Method::MsmSoft) {
        const MsmTable t = mode == Mode::Msm16 ? build_msm_table(ctx, map, Quantization::Bits16, Precision::Exact)
                                               : build_msm_table(ctx, map);
        if (mode == Mode::Msm16 && stored) {
            *stored = dequantized(t);
            p.stored = stored;
        }
        p.moment_bias = default_moment_bias(t.quantization);
        p.msm_depth_bias = default_depth_bias(t.quantization);
        return lookups(t, settings, p, [&](const MsmTable& table, Setting s) {
            return m == Method::Msm ? msm(ctx, table, rx, MsmOptions{s.radius, {}, {}})
                                    : msm_soft(ctx, table, rx, MsmSoftOptions{s.light_size, {}, {}});
        });
    }
    EvsmWarp warp;
    warp.channels = m == Method::Evsm2 ? 2 : 4;
    const EvsmTable t = direct ? EvsmTable{} : build_evsm_table(ctx, map, warp);
    p.positive = direct ? default_evsm_exponent(Quantization::None, true) : t.positive;
    p.negative = direct ? (warp.channels == 4 ? default_evsm_exponent(Quantization::None, false) : 0.0f) : t.negative;
    const EvsmOptions defaults;
    p.min_variance = defaults.min_variance;
    p.bleed = defaults.bleed;
    p.evsm_depth_bias = defaults.depth_bias;
    return lookups(t, settings, p, [&](const EvsmTable& table, Setting s) {
        EvsmOptions o;
        o.radius = s.radius;
        return direct ? evsm(ctx, map, warp, rx, o) : evsm(ctx, table, rx, o);
    });
}

std::vector<double> reference_all(Method m, const Image& map, const Image& rx, const Params& params)
{
    const WarpedMap warped = m == Method::Evsm2 || m == Method::Evsm4 ? warp_map(map, params) : WarpedMap{};
    Params p = params;
    if (m == Method::Evsm2 || m == Method::Evsm4) p.warped = &warped;
    std::vector<double> refs(std::size_t(rx.width()) * std::size_t(rx.height()));
    tbb::parallel_for(0, int(refs.size()), [&](int i) {
        refs[std::size_t(i)] = double(evaluate(m, map, receiver_at(rx, i % rx.width(), i / rx.width()), p, false).visibility);
    });
    return refs;
}

Tally judge_all(Method m, const Image& map, const Image& rx, const Image& library, const Params& params,
                int max_lines, const std::vector<double>* references)
{
    const WarpedMap warped = m == Method::Evsm2 || m == Method::Evsm4 ? warp_map(map, params) : WarpedMap{};
    Params p = params;
    if (m == Method::Evsm2 || m == Method::Evsm4) p.warped = &warped;
    Tally t;
    const int n = rx.width() * rx.height();
    t.receivers = n;
    t.deviations.resize(std::size_t(n));
    std::vector<Verdict> verdicts(static_cast<std::size_t>(n));
    tbb::parallel_for(0, n, [&](int i) {
        const int x = i % rx.width(), y = i / rx.width();
        verdicts[std::size_t(i)] = judge(m, map, receiver_at(rx, x, y), p, library.at(0, x, y),
                                          references ? &(*references)[std::size_t(i)] : nullptr);
    });
    for (int i = 0; i < n; ++i) {
        const Verdict& v = verdicts[std::size_t(i)];
        const double d = std::isfinite(v.deviation) ? v.deviation : 1.0;
        t.deviations[std::size_t(i)] = d;
        t.worst = std::max(t.worst, d);
        t.beyond += d > tolerance(m);
        t.beyond_1e2 += d > 1e-2;
        t.ill += v.ill_conditioned;
        if (!v.pass) {
            if (t.failed < max_lines) {
                const int x = i % rx.width(), y = i / rx.width();
                const Receiver r = receiver_at(rx, x, y);
                char line[256];
                std::snprintf(line, sizeof line,
                              "  receiver %d (u %.9g v %.9g z %.9g): library %.9g reference %.9g |diff| %.3g bound %.3g "
                              "movement %.3g\n",
                              i, r.u, r.v, r.z, library.at(0, x, y), v.reference, v.deviation, v.bound, v.movement);
                t.first_failures += line;
            }
            ++t.failed;
        }
    }
    return t;
}

}  // namespace penumbra::testing::fidelity
