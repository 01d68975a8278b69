#include "support/overlap_scene.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <optional>

#include "penumbra/chebyshev.h"
#include "penumbra/moments.h"
#include "penumbra/reference/metrics.h"

namespace penumbra::testing {
namespace {

// The scene with only the ground and primitive `keep`.
reference::Scene only(const reference::Scene& scene, std::size_t keep)
{
    reference::Scene s = scene;
    s.primitives = {scene.primitives[0], scene.primitives[keep]};
    return s;
}

// 1 where the receiver lies behind `map` at its texel (a hard shadow test).
bool behind(const Image& map, const Image& uvz, int x, int y)
{
    const int tx = std::min(int(uvz.at(0, x, y) * float(map.width())), map.width() - 1);
    const int ty = std::min(int(uvz.at(1, x, y) * float(map.height())), map.height() - 1);
    return map.at(0, tx, ty) < uvz.at(2, x, y) - 1e-3f;
}

struct LeakMethod {
    std::string name;
    std::function<Image(Context&, const OverlapFrame&)> run;
};

// The methods of the table, each with its default settings and the box radius
// `radius` (VSM's default is 2), on exact tables (16-bit) and float tables.
// EVSM4 on float tables also at c+ = 20 and 42 (the default is 10). MSM
// also with a receiver-plane depth bias of 3e-4 (half a texel's depth
// change on the sloped ground at 512^2, docs/moments.md), and the soft
// methods with the scene's light size.
std::vector<LeakMethod> leak_methods(int radius)
{
    auto evsm_method = [radius](int channels, Quantization q, Precision p, std::optional<float> positive = {}) {
        return [=](Context& ctx, const OverlapFrame& f) {
            EvsmWarp warp;
            warp.channels = channels;
            warp.quantization = q;
            warp.positive = positive;
            return evsm(ctx, build_evsm_table(ctx, f.map, warp, p), f.receivers.light_uvz, EvsmOptions{radius});
        };
    };
    auto msm_method = [radius](Quantization q, Precision p, std::optional<float> depth_bias) {
        return [=](Context& ctx, const OverlapFrame& f) {
            return msm(ctx, build_msm_table(ctx, f.map, q, p), f.receivers.light_uvz,
                       MsmOptions{radius, {}, depth_bias});
        };
    };
    const Quantization b16 = Quantization::Bits16, b32 = Quantization::Bits32;
    return {
        {"vsm exact", [radius](Context& ctx, const OverlapFrame& f) {
             return vsm(ctx, build_moment_table(ctx, f.map), f.receivers.light_uvz, VsmOptions{radius});
         }},
        {"vsm float", [radius](Context& ctx, const OverlapFrame& f) {
             return vsm(ctx, build_moment_table(ctx, f.map, 2, Precision::Float), f.receivers.light_uvz,
                        VsmOptions{radius});
         }},
        {"evsm2 16 exact", evsm_method(2, b16, Precision::Exact)},
        {"evsm2 32 float", evsm_method(2, b32, Precision::Float)},
        {"evsm4 16 exact", evsm_method(4, b16, Precision::Exact)},
        {"evsm4 32 float", evsm_method(4, b32, Precision::Float)},
        {"evsm4 32 float c+ 20", evsm_method(4, b32, Precision::Float, 20.0f)},
        {"evsm4 32 float c+ 42", evsm_method(4, b32, Precision::Float, 42.0f)},
        {"msm 16 exact", msm_method(b16, Precision::Exact, {})},
        {"msm 16 exact db 3e-4", msm_method(b16, Precision::Exact, 3e-4f)},
        {"msm 16 float db 3e-4", msm_method(b16, Precision::Float, 3e-4f)},
        {"msm 32 float db 3e-4", msm_method(b32, Precision::Float, 3e-4f)},
        {"vssm exact (L scene)", [](Context& ctx, const OverlapFrame& f) {
             const float light = float(reference::light_size(f.scene));
             return vssm(ctx, build_moment_table(ctx, f.map), f.receivers.light_uvz, VssmOptions{light});
         }},
        {"msm-soft 16 exact db 3e-4", [](Context& ctx, const OverlapFrame& f) {
             const float light = float(reference::light_size(f.scene));
             return msm_soft(ctx, build_msm_table(ctx, f.map), f.receivers.light_uvz,
                             MsmSoftOptions{light, {}, 3e-4f});
         }},
    };
}

LeakScore score(const Image& estimate, const OverlapFrame& f)
{
    return {reference::light_leaking(estimate, f.truth, &f.receivers.mask), reference::light_leaking(estimate, f.truth, &f.two_layers),
            reference::rmse(estimate, f.truth, &f.receivers.mask), reference::over_darkening(estimate, f.truth, &f.receivers.mask)};
}

}  // namespace

// The overlap scene's primitives: 0 ground, 1 lower slab, 2 upper slab, 3 box.
OverlapFrame render_overlap_frame(int map_size, int width, int height, int strata)
{
    OverlapFrame f;
    f.scene = reference::builtin_scene("overlap");
    f.map = reference::render_shadow_map(f.scene, map_size, map_size);
    f.receivers = reference::render_receivers(f.scene, width, height);
    f.truth = reference::ground_truth(f.scene, f.receivers, {strata});
    const Image lower = reference::render_shadow_map(only(f.scene, 1), map_size, map_size);
    const Image upper = reference::render_shadow_map(only(f.scene, 2), map_size, map_size);
    f.two_layers = Image(width, height, 1);
    const Image& uvz = f.receivers.light_uvz;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            f.two_layers.at(0, x, y) =
                float(f.receivers.mask.at(0, x, y) > 0.5f && behind(lower, uvz, x, y) && behind(upper, uvz, x, y));
    return f;
}

LeakTable overlap_leak_table(const OverlapFrame& f, int radius)
{
    Context ctx(ContextOptions{Backend::Simd, {}});
    LeakTable rows;
    for (const LeakMethod& m : leak_methods(radius)) rows.push_back({m.name, score(m.run(ctx, f), f)});
    return rows;
}

void print_leak_table(const LeakTable& rows)
{
    std::printf("%-26s %9s %16s %9s %15s\n", "method", "leaking", "leaking 2 slabs", "RMSE", "over-darkening");
    for (const auto& [name, s] : rows)
        std::printf("%-26s %9.5f %16.5f %9.5f %15.5f\n", name.c_str(), s.leak, s.leak_two_layers, s.rmse, s.dark);
}

}  // namespace penumbra::testing
