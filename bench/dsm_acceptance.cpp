// Issue 14's measured acceptance of deep shadow maps (docs/deep_shadow_maps.md,
// "Acceptance"): on hair, fog and layers, the error of the deep map (RMSE and
// p99 against the truth) and its bytes per pixel against the tolerance eps
// and the samples per pixel N, the compression ratio, the build time per
// million samples; and against single-depth shadow maps (PCF, VSM, MSM) of
// equal memory. Prints Markdown tables and writes every row to a CSV for
// bench/dsm_acceptance_chart.py. Figures, not checks.
//
// usage: dsm_acceptance [--quick] OUT.csv
//
// Two truths per receiver (the view's valid receivers that face the light):
//   exact  the scene's own: the point light's transmittance at the receiver,
//          exact (one segment);
//   pixel  the view pixel's antialiased truth: the mean of the exact truth of
//          4 x 4 receivers spread over the pixel (a pixel counts when all 16
//          are valid and face the light). Under hair the exact truth is 0 or
//          1 per point, which no filtered method can follow; the pixel truth
//          is the fraction a renderer's pixel shows, and depends on no
//          method's resolution or filter.
// Every method is evaluated once, at the pixel's centre receiver.
// The deep map is evaluated with the nearest pixel, the bilinear (tent)
// weights of the four nearest pixel centres or a box of pixels, each tap
//  - at the receiver's depth less a constant: the library's lookup (the
//    method table's `dsm`, deep_lookup, on the best backend), or
//  - at the receiver plane's depth there (the receiver's depth slope in light
//    space, from its view neighbours) less half the plane's depth change
//    across a pixel (a box pixel averages its footprint, and a sloped
//    receiver crosses it at every depth of that span): an experiment the
//    lookup kernel does not offer, evaluated here on the host by the lookup
//    contract of penumbra/deep_shadow_map.h (DeepShadowMap::visibility).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/deep_lookup.h"
#include "penumbra/deep_shadow_map.h"
#include "penumbra/methods.h"
#include "penumbra/reference.h"
#include "penumbra/reference/deep_map.h"
#include "penumbra/reference/metrics.h"

using namespace penumbra;

namespace {

struct Config {
    int deep_size = 512;
    int view_width = 320, view_height = 240;  // the demo's view
    std::vector<int> samples = {4, 16, 64, 256};
    std::vector<double> tolerance_scales = {0.0, 0.5, 2.0, 4.0};  // x 0.25 N^-1/2, at N = 16
    std::vector<int> equal_memory_samples = {16, 64};
};

constexpr int kSubpixels = 4;  // per axis, for the pixel truth
constexpr float kDeepBiasFloor = 1e-4f;
constexpr float kLargestDeepBias = 0.01f;

struct Truths {
    reference::Receivers rx;
    Image exact, pixel, mask;
};

// Valid receivers that face the light (the demo's scored_mask).
Image facing_mask(const reference::Scene& scene, const reference::Receivers& rx)
{
    Image mask(rx.width(), rx.height(), 1);
    const double light[3] = {scene.light.center.x, scene.light.center.y, scene.light.center.z};
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            double facing = 0;
            for (int c = 0; c < 3; ++c) facing += (light[c] - rx.world_position.at(c, x, y)) * rx.normal.at(c, x, y);
            mask.at(0, x, y) = rx.mask.at(0, x, y) > 0.5f && facing > 0 ? 1.0f : 0.0f;
        }
    return mask;
}

// The view at kSubpixels^2 the resolution, its exact truth averaged per pixel.
void pixel_truth(const reference::Scene& scene, const Config& c, Truths& t)
{
    const reference::Receivers fine =
        reference::render_receivers(scene, c.view_width * kSubpixels, c.view_height * kSubpixels);
    const Image fine_truth = reference::ground_truth(scene, fine, {1});
    const Image fine_mask = facing_mask(scene, fine);
    t.pixel = Image(c.view_width, c.view_height, 1);
    for (int y = 0; y < c.view_height; ++y)
        for (int x = 0; x < c.view_width; ++x) {
            double sum = 0;
            bool all = true;
            for (int b = 0; b < kSubpixels; ++b)
                for (int a = 0; a < kSubpixels; ++a) {
                    sum += fine_truth.at(0, x * kSubpixels + a, y * kSubpixels + b);
                    all = all && fine_mask.at(0, x * kSubpixels + a, y * kSubpixels + b) > 0.5f;
                }
            t.pixel.at(0, x, y) = float(sum / (kSubpixels * kSubpixels));
            if (!all) t.mask.at(0, x, y) = 0;
        }
}

Truths truths_for(const reference::Scene& scene, const Config& c)
{
    Truths t;
    t.rx = reference::render_receivers(scene, c.view_width, c.view_height);
    t.mask = facing_mask(scene, t.rx);
    t.exact = reference::ground_truth(scene, t.rx, {1});
    pixel_truth(scene, c, t);
    return t;
}

// The receiver plane's depth slope (dz/du, dz/dv) at view pixel (x, y), from
// the neighbour on each axis whose depth differs least (across a silhouette
// the other side belongs to another surface); 0 where it is degenerate.
struct DepthSlope {
    double du = 0, dv = 0;
};

DepthSlope depth_slope(const reference::Receivers& rx, int x, int y)
{
    auto uvz = [&](int i, int j, int c) { return double(rx.light_uvz.at(c, i, j)); };
    auto nearer = [&](int ax, int ay, int bx, int by) {
        const bool a_ok = ax >= 0 && ay >= 0 && ax < rx.width() && ay < rx.height() && rx.mask.at(0, ax, ay) > 0.5f;
        const bool b_ok = bx >= 0 && by >= 0 && bx < rx.width() && by < rx.height() && rx.mask.at(0, bx, by) > 0.5f;
        if (!b_ok || (a_ok && std::abs(uvz(ax, ay, 2) - uvz(x, y, 2)) <= std::abs(uvz(bx, by, 2) - uvz(x, y, 2))))
            return std::pair{ax, ay};
        return std::pair{bx, by};
    };
    const auto [hx, hy] = nearer(x + 1, y, x - 1, y);
    const auto [vx, vy] = nearer(x, y + 1, x, y - 1);
    if (rx.mask.at(0, hx, hy) < 0.5f || rx.mask.at(0, vx, vy) < 0.5f) return {};
    const double u1 = uvz(hx, hy, 0) - uvz(x, y, 0), v1 = uvz(hx, hy, 1) - uvz(x, y, 1), z1 = uvz(hx, hy, 2) - uvz(x, y, 2);
    const double u2 = uvz(vx, vy, 0) - uvz(x, y, 0), v2 = uvz(vx, vy, 1) - uvz(x, y, 1), z2 = uvz(vx, vy, 2) - uvz(x, y, 2);
    const double det = u1 * v2 - u2 * v1;
    if (std::abs(det) < 1e-14) return {};
    return {(z1 * v2 - z2 * v1) / det, (u1 * z2 - u2 * z1) / det};
}

// The lookup filters: the nearest pixel, the bilinear (tent) weights of the
// four nearest pixel centres, and a box of (2 r + 1)^2 pixels about the
// nearest one (the radius swept as the single-depth methods' is). Each tap
// at a depth by one of two rules:
//   plane     the receiver plane's depth at the tap's pixel centre, less half
//             the plane's depth change across a pixel (and 1e-4);
//   constant  the receiver's depth less 0.003 (kDeepDefaultBias, the `dsm`
//             lookup's default, which DeepMap.NearestPixelLookupFollowsThePointLightTruth
//             chose for fog and layers): the library's lookup itself.
struct Lookup {
    enum Kind { Nearest, Bilinear, Box } kind;
    int radius = 0;
    bool plane = true;
    std::string name() const
    {
        return std::string(kind == Nearest ? "dsm-nearest" : kind == Bilinear ? "dsm-bilinear" : "dsm-box") +
               (plane ? "" : "-const");
    }
};
const Lookup kLookups[] = {{Lookup::Nearest},        {Lookup::Bilinear},        {Lookup::Box, 1},
                           {Lookup::Box, 2},         {Lookup::Nearest, 0, false}, {Lookup::Bilinear, 0, false},
                           {Lookup::Box, 1, false}, {Lookup::Box, 2, false}};
constexpr float kConstantDeepBias = 0.003f;

// One tap: pixel (i, j) (clamped to the map) at the depth of the filter's rule.
float tap(const DeepShadowMap& map, const Lookup& filter, int i, int j, float u, float v, float z,
          const DepthSlope& slope)
{
    const int w = map.width(), h = map.height();
    i = std::clamp(i, 0, w - 1), j = std::clamp(j, 0, h - 1);
    if (!filter.plane) return map.visibility(i, j, z - kConstantDeepBias);
    const double du = (i + 0.5) / w - u, dv = (j + 0.5) / h - v;
    const double bias = std::min(double(kLargestDeepBias),
                                 kDeepBiasFloor + 0.5 * (std::abs(slope.du) / w + std::abs(slope.dv) / h));
    return map.visibility(i, j, float(z + slope.du * du + slope.dv * dv - bias));
}

float lookup(const DeepShadowMap& map, const Lookup& filter, float u, float v, float z, const DepthSlope& slope)
{
    const int w = map.width(), h = map.height();
    auto at = [&](int i, int j) { return tap(map, filter, i, j, u, v, z, slope); };
    if (filter.kind == Lookup::Bilinear) {
        const float x = u * w - 0.5f, y = v * h - 0.5f;
        const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
        const float fx = x - x0, fy = y - y0;
        return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
               fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
    }
    const int i0 = int(u * w), j0 = int(v * h), r = filter.radius;
    double sum = 0;
    for (int j = j0 - r; j <= j0 + r; ++j)
        for (int i = i0 - r; i <= i0 + r; ++i) sum += at(i, j);
    return float(sum / ((2 * r + 1) * (2 * r + 1)));
}

// The library's lookup with the filter's constant-bias rule.
Image library_estimate(Context& ctx, const DeepShadowMap& map, const Lookup& filter, const reference::Receivers& rx)
{
    MethodSettings s;
    s.deep_filter = filter.kind == Lookup::Bilinear ? DeepFilter::Tent : DeepFilter::Box;
    s.radius = filter.radius;
    s.depth_bias = kConstantDeepBias;
    return find_method("dsm").run(ctx, map, rx.light_uvz, s);
}

Image deep_estimate(Context& ctx, const DeepShadowMap& map, const Lookup& filter, const reference::Receivers& rx)
{
    if (!filter.plane) return library_estimate(ctx, map, filter, rx);
    Image out(rx.width(), rx.height(), 1);
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x)
            out.at(0, x, y) = lookup(map, filter, rx.light_uvz.at(0, x, y), rx.light_uvz.at(1, x, y),
                                     rx.light_uvz.at(2, x, y), depth_slope(rx, x, y));
    return out;
}

struct Row {
    std::string scene, method, setting;
    int samples = 0;
    double tolerance = 0, bytes = 0, bytes_per_pixel = 0, ratio = 0, build_s = 0, s_per_msample = 0;
    double rmse_exact = 0, p99_exact = 0, rmse_pixel = 0, p99_pixel = 0;
};

void score(Row& row, const Image& estimate, const Truths& t)
{
    row.rmse_exact = reference::rmse(estimate, t.exact, &t.mask);
    row.p99_exact = reference::p99_abs_error(estimate, t.exact, &t.mask);
    row.rmse_pixel = reference::rmse(estimate, t.pixel, &t.mask);
    row.p99_pixel = reference::p99_abs_error(estimate, t.pixel, &t.mask);
}

struct DeepRun {
    DeepShadowMap map;
    Row row;  // without the lookup's name and errors
};

DeepRun build_deep(const reference::Scene& scene, const Config& c, int samples, double tolerance_scale)
{
    reference::DeepMapOptions o;
    o.size = c.deep_size;
    o.samples = samples;
    const float default_tolerance = 0.25f / std::sqrt(float(samples));
    if (tolerance_scale != 1.0) o.tolerance = float(tolerance_scale) * default_tolerance;
    reference::DeepMapStats stats;
    const auto start = std::chrono::steady_clock::now();
    DeepRun run{reference::render_deep_shadow_map(scene, o, &stats), {}};
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double pixels = double(c.deep_size) * c.deep_size;
    Row& r = run.row;
    r.scene = scene.name;
    r.samples = samples;
    r.tolerance = stats.tolerance;
    r.bytes = double(run.map.bytes());
    r.bytes_per_pixel = r.bytes / pixels;
    r.ratio = double(stats.uncompressed_bytes(c.deep_size, c.deep_size)) / r.bytes;
    r.build_s = seconds;
    r.s_per_msample = seconds / (double(stats.samples) / 1e6);
    char setting[64];
    std::snprintf(setting, sizeof setting, "N=%d eps=%.4g", samples, stats.tolerance);
    r.setting = setting;
    return run;
}

void deep_rows(Context& ctx, const DeepRun& run, const Truths& t, std::vector<Row>& rows)
{
    for (const Lookup& filter : kLookups) {
        Row row = run.row;
        row.method = filter.name();
        if (filter.kind == Lookup::Box) row.setting += " r=" + std::to_string(filter.radius);
        score(row, deep_estimate(ctx, run.map, filter, t.rx), t);
        rows.push_back(row);
    }
}

// The single-depth methods at equal memory: the bytes a renderer stores per
// texel for the method's map (PCF a float depth; VSM two float moments; MSM
// four 16-bit moments, Peters and Klein's 64-bit form), the settings the demo
// uses (receiver-plane bias for PCF, MSM's 3e-4 depth bias), the radius swept.
struct SingleDepth {
    const char* method;
    int bytes_per_texel;
};
constexpr SingleDepth kSingleDepth[] = {{"pcf", 4}, {"vsm", 8}, {"msm", 8}};

MethodSettings single_depth_settings(const std::string& method, int radius)
{
    MethodSettings s;
    s.radius = radius;
    if (method == "pcf") s.bias_mode = BiasMode::ReceiverPlane;
    if (method == "msm") s.depth_bias = 3e-4f;
    return s;
}

void equal_memory_rows(Context& ctx, const reference::Scene& scene, const Truths& t, const Row& deep,
                       std::vector<Row>& rows)
{
    for (const SingleDepth& m : kSingleDepth) {
        const int side = int(std::floor(std::sqrt(deep.bytes / m.bytes_per_texel)));
        const Image map = reference::render_shadow_map(scene, side, side);
        for (int radius : {1, 2, 4}) {
            Row row;
            row.scene = scene.name;
            row.method = m.method;
            row.samples = deep.samples;  // the deep map whose memory it matches
            row.bytes = double(side) * side * m.bytes_per_texel;
            row.bytes_per_pixel = row.bytes / (double(deep.bytes) / deep.bytes_per_pixel);
            row.setting = std::to_string(side) + "^2 r=" + std::to_string(radius);
            score(row, find_method(m.method).run(ctx, map, t.rx.light_uvz, single_depth_settings(m.method, radius)), t);
            rows.push_back(row);
        }
    }
}

void write_csv(const std::string& path, const std::vector<Row>& rows)
{
    std::ofstream out(path);
    out << "scene,method,setting,samples,tolerance,bytes,bytes_per_pixel,ratio,build_s,s_per_msample,rmse_exact,"
           "p99_exact,rmse_pixel,p99_pixel\n";
    for (const Row& r : rows)
        out << r.scene << "," << r.method << ",\"" << r.setting << "\"," << r.samples << "," << r.tolerance << ","
            << r.bytes << "," << r.bytes_per_pixel << "," << r.ratio << "," << r.build_s << "," << r.s_per_msample
            << "," << r.rmse_exact << "," << r.p99_exact << "," << r.rmse_pixel << "," << r.p99_pixel << "\n";
}

void print_rows(const std::vector<Row>& rows)
{
    std::printf("| scene | method | setting | bytes/px | ratio | build s | s/Msample | RMSE exact | p99 exact | "
                "RMSE pixel | p99 pixel |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows)
        std::printf("| %s | %s | %s | %.1f | %.2f | %.2f | %.2f | %.4f | %.4f | %.4f | %.4f |\n", r.scene.c_str(),
                    r.method.c_str(), r.setting.c_str(), r.bytes_per_pixel, r.ratio, r.build_s, r.s_per_msample,
                    r.rmse_exact, r.p99_exact, r.rmse_pixel, r.p99_pixel);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv)
{
    Config c;
    std::string csv;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--quick") {
            c.deep_size = 128, c.view_width = 64, c.view_height = 48;
            c.samples = {4, 16}, c.tolerance_scales = {0.0}, c.equal_memory_samples = {16};
        } else csv = arg;
    }
    if (csv.empty()) {
        std::fprintf(stderr, "usage: dsm_acceptance [--quick] OUT.csv\n");
        return 2;
    }
    Context ctx;
    std::printf("dsm_acceptance: %dx%d receivers, %d^2 deep maps, %s\n", c.view_width, c.view_height, c.deep_size,
                ctx.description().c_str());
    std::vector<Row> rows;
    for (const char* name : {"hair", "fog", "layers"}) {
        const reference::Scene scene = reference::builtin_scene(name);
        const Truths t = truths_for(scene, c);
        std::vector<Row> scene_rows;
        for (int n : c.samples) {
            const DeepRun run = build_deep(scene, c, n, 1.0);
            deep_rows(ctx, run, t, scene_rows);
            if (std::find(c.equal_memory_samples.begin(), c.equal_memory_samples.end(), n) !=
                c.equal_memory_samples.end())
                equal_memory_rows(ctx, scene, t, run.row, scene_rows);
        }
        const int tolerance_samples = 16;
        for (double scale : c.tolerance_scales) deep_rows(ctx, build_deep(scene, c, tolerance_samples, scale), t, scene_rows);
        print_rows(scene_rows);
        rows.insert(rows.end(), scene_rows.begin(), scene_rows.end());
        write_csv(csv, rows);  // after each scene, so a long run leaves its rows
    }
    return 0;
}
