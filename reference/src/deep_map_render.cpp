// render_deep_shadow_map (deep_map.h): the sampling of the light's image
// plane, the bands of rows the work is split into, and the assembly of the
// compressed pixels into a DeepShadowMap.
//
// Schedule: bands of up to kBandRows rows over TBB. A band traces the samples
// of its pixels and, for the Gaussian, of a one-pixel halo around them (the
// samples of neighbouring pixels within its radius), so no sample is traced
// twice inside a band; across bands the halo rows are traced again, 2 of
// every 16 + 2 rows. A band holds at most about kBandSamples samples (at
// some 60 bytes each with their vertices), so wide maps with many samples get
// fewer rows per band (down to 1, where the Gaussian traces 3 rows per row). Every pixel's samples come from its own stream,
// so the map does not depend on the bands or the thread count.
#include <algorithm>
#include <cmath>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "deep_map_parts.h"
#include "penumbra/dsm_compression.h"
#include "penumbra/error.h"
#include "splitmix64.h"

namespace penumbra::reference {
namespace {

constexpr const char* kRenderDeepMapOp = "render_deep_shadow_map";
constexpr int kBandRows = 16;
constexpr std::size_t kBandSamples = std::size_t(1) << 21;

int band_rows(const DeepMapOptions& o)
{
    const std::size_t row_samples = (std::size_t(o.size) + 2) * std::size_t(o.samples);
    return int(std::clamp<std::size_t>(kBandSamples / row_samples, 1, kBandRows));
}

// A stratum grid of exactly K cells: `rows` the largest divisor of K not
// above sqrt(K), so a square K gets a square grid and a prime K strips.
struct Strata {
    int columns = 1, rows = 1;
    explicit Strata(int samples)
    {
        for (int r = 1; r * r <= samples; ++r)
            if (samples % r == 0) rows = r;
        columns = samples / rows;
    }
};

// The stream of pixel (i, j), halo pixels (-1 or size) included; hashed once
// so that neighbouring pixels get unrelated jitter.
SplitMix64 pixel_stream(std::uint64_t seed, int i, int j, int size)
{
    const std::uint64_t index = std::uint64_t(j + 1) * std::uint64_t(size + 2) + std::uint64_t(i + 1);
    return SplitMix64(SplitMix64(seed ^ (index * 0x9e3779b97f4a7c15ull)).next());
}

struct Setup {
    const Scene& scene;
    PreparedScene prepared;
    LightProjection projection;
    DeepMapOptions options;
    float tolerance;
    double volume_error;
    Strata strata;
    int halo;
};

// K jittered samples of pixel (i, j), one per stratum, traced into `set`.
void trace_pixel(const Setup& s, int i, int j, SampleSet& set)
{
    SplitMix64 rng = pixel_stream(s.options.seed, i, j, s.options.size);
    const double n = s.options.size;
    const double near = s.scene.light_camera.near, far = s.scene.light_camera.far;
    for (int k = 0; k < s.options.samples; ++k) {
        const double fx = (k % s.strata.columns + rng.uniform()) / s.strata.columns;
        const double fy = (k / s.strata.columns + rng.uniform()) / s.strata.rows;
        const Ray ray = s.projection.ray_through((i + fx) / n, (j + fy) / n);
        set.add(i + fx, j + fy,
                ray_transmittance(s.prepared, s.projection, ray, near, far, s.volume_error));
    }
}

// The samples that pixel (i, j) filters, from a band whose traced pixels start
// at row `row0` (halo included) and span `width` columns from column -halo.
void pixel_samples(const Setup& s, const SampleSet& set, int i, int j, int row0, int width,
                   std::vector<WeightedSample>& out)
{
    out.clear();
    const int k = s.options.samples;
    double total = 0;
    for (int dj = -s.halo; dj <= s.halo; ++dj)
        for (int di = -s.halo; di <= s.halo; ++di) {
            const std::size_t pixel = std::size_t(j + dj - row0) * std::size_t(width) + std::size_t(i + di + s.halo);
            for (int q = 0; q < k; ++q) {
                const std::uint32_t index = std::uint32_t(pixel * std::size_t(k) + std::size_t(q));
                const double w = s.options.filter == DeepMapFilter::Box
                                     ? 1.0
                                     : gaussian_weight(set.x[index] - (i + 0.5), set.y[index] - (j + 0.5));
                if (w > 0) out.push_back({index, w});
                total += w;
            }
        }
    for (WeightedSample& w : out) w.weight /= total;
}

// One row's compressed pixels, appended to the builder in row order.
struct RowOut {
    std::vector<float> z, t;
    std::vector<std::uint32_t> first{0};
    std::size_t filtered = 0;
};

void render_band(const Setup& s, int j0, int j1, std::vector<RowOut>& rows, std::size_t& traced)
{
    const int n = s.options.size, width = n + 2 * s.halo, row0 = j0 - s.halo;
    SampleSet set;
    for (int j = row0; j < j1 + s.halo; ++j)
        for (int i = -s.halo; i < n + s.halo; ++i) trace_pixel(s, i, j, set);
    traced = set.x.size();
    std::vector<WeightedSample> weights;
    CombineScratch scratch;
    std::vector<float> fz, ft;
    for (int j = j0; j < j1; ++j) {
        RowOut& row = rows[std::size_t(j)];
        for (int i = 0; i < n; ++i) {
            pixel_samples(s, set, i, j, row0, width, weights);
            combine_functions(set, weights, scratch, fz, ft);
            row.filtered += fz.size();
            compress_visibility(fz, ft, s.tolerance, row.z, row.t);
            row.first.push_back(std::uint32_t(row.z.size()));
        }
    }
}

// The options with their defaults resolved; what render_band reads.
struct Resolved {
    DeepMapOptions options;
    float tolerance;
    double volume_error;
};

Resolved checked(const DeepMapOptions& o)
{
    require(o.size >= 1 && o.size <= 16384, kRenderDeepMapOp, "size",
            "must be in [1, 16384] (got " + std::to_string(o.size) + ")");
    require(o.samples >= 1 && o.samples <= 4096, kRenderDeepMapOp, "samples",
            "must be in [1, 4096] (got " + std::to_string(o.samples) + ")");
    require(o.filter == DeepMapFilter::Box || o.filter == DeepMapFilter::Gaussian, kRenderDeepMapOp, "filter",
            "must be DeepMapFilter::Box or Gaussian");
    const float tolerance = o.tolerance.value_or(dsm_default_tolerance(o.samples));
    require(tolerance >= 0 && tolerance <= 1, kRenderDeepMapOp, "tolerance",
            "must be in [0, 1] (got " + std::to_string(tolerance) + ")");
    // A zero tolerance still needs a finite volume step.
    const double volume_error = o.volume_error.value_or(std::max(double(tolerance) / 4, 1e-5));
    require(volume_error >= 1e-6 && volume_error <= 1, kRenderDeepMapOp, "volume_error",
            "must be in [1e-6, 1] (got " + std::to_string(volume_error) + ")");
    return {o, tolerance, volume_error};
}

}  // namespace

std::size_t DeepMapStats::uncompressed_bytes(int width, int height) const
{
    return (std::size_t(width) * std::size_t(height) + 1) * sizeof(std::uint32_t) +
           filtered_vertices * 2 * sizeof(float);
}

DeepShadowMap render_deep_shadow_map(const Scene& scene, const DeepMapOptions& options, DeepMapStats* stats)
{
    const Resolved r = checked(options);
    const DeepMapOptions& o = r.options;
    validate_scene(scene, kRenderDeepMapOp);
    const Setup setup{scene, PreparedScene(scene), LightProjection(scene), o, r.tolerance, r.volume_error,
                      Strata(o.samples),
                      o.filter == DeepMapFilter::Box ? 0 : int(std::ceil(kDeepGaussianRadius - 0.5))};
    std::vector<RowOut> rows(std::size_t(o.size));
    const int rows_per_band = band_rows(o);
    const int bands = (o.size + rows_per_band - 1) / rows_per_band;
    std::vector<std::size_t> traced(std::size_t(bands), 0);
    tbb::parallel_for(
        tbb::blocked_range<int>(0, bands, 1),
        [&](const tbb::blocked_range<int>& range) {
            for (int b = range.begin(); b != range.end(); ++b)
                render_band(setup, b * rows_per_band, std::min(o.size, (b + 1) * rows_per_band), rows,
                            traced[std::size_t(b)]);
        },
        tbb::simple_partitioner());
    DeepShadowMapBuilder builder(o.size, o.size);
    DeepMapStats s{0, 0, 0, r.tolerance, float(r.volume_error)};
    for (const RowOut& row : rows) {
        for (std::size_t p = 0; p + 1 < row.first.size(); ++p)
            builder.add_pixel(std::span(row.z).subspan(row.first[p], row.first[p + 1] - row.first[p]),
                              std::span(row.t).subspan(row.first[p], row.first[p + 1] - row.first[p]));
        s.filtered_vertices += row.filtered;
    }
    for (std::size_t t : traced) s.samples += t;
    DeepShadowMap map = builder.build();
    s.compressed_vertices = map.vertex_count();
    if (stats) *stats = s;
    return map;
}

}  // namespace penumbra::reference
