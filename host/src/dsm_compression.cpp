// Error-bounded compression of visibility functions (penumbra/dsm_compression.h).
//
// Lokovic & Veach's greedy construction: from the current output vertex (the
// origin) draw one segment as far in depth as it can go while passing within
// +-eps of every input vertex it spans. Each input vertex (z_i, t_i) is a
// "target window" [t_i - eps, t_i + eps] at z_i, which bounds the segment's
// slope to [(lo_i - t_o)/(z_i - z_o), (hi_i - t_o)/(z_i - z_o)]; the running
// intersection of those ranges is the set of segments that still fit. When
// the next window empties it, the segment ends at the last input depth that
// fitted, with the slope of the range that lands nearest the input's own
// value there (the seed does not fix which slope; the middle of the range,
// the first choice, tilted every flat stretch between two steps and ended it
// eps / 2 low: a systematic darkening), and that end is the next origin.
// One pass, O(n).
//
// Why the band then holds at every depth, not only at the vertices: every
// output depth is an input depth, so on each input segment both functions are
// linear and their difference is largest at its ends, which are windows.
// Additions of ours, each for a guarantee of the header:
//  - slopes are capped at 0 and windows clipped to [t_last, 1]: the output is
//    monotone, in [0, 1], and can always still reach the end;
//  - the last window has width 0: the end is exact;
//  - a window at the origin's own depth (an input step there) cannot bound a
//    slope: if the origin's value misses it, the output steps there too, to
//    the input's own value, so a kept step is exact in depth and in value.
#include "penumbra/dsm_compression.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>

#include "penumbra/error.h"

namespace penumbra {
namespace {

struct Window {
    double lo, hi;
};

// One pixel's compression; the input is a valid function with n >= 2.
class Compressor {
public:
    Compressor(std::span<const float> z, std::span<const float> t, double eps, std::vector<float>& out_z,
               std::vector<float>& out_t)
        : z_(z), t_(t), eps_(eps), out_z_(out_z), out_t_(out_t)
    {
    }

    void run()
    {
        const std::size_t n = z_.size(), begin = out_z_.size();
        emit(z_[0], 1.0f);
        std::size_t last_fitted = 0;
        for (std::size_t i = 1; i < n;) {
            const Window w = window(i);
            if (z_[i] == origin_z_) {
                // An input step at the origin: no slope to bound; keep the step
                // unless the origin's value already lies in the window.
                if (origin_t_ > w.hi) emit(origin_z_, t_[i]);
                last_fitted = i++;
                continue;
            }
            const double dz = double(z_[i]) - origin_z_;
            const double lo = std::max(slope_lo_, (w.lo - origin_t_) / dz);
            const double hi = std::min(slope_hi_, (w.hi - origin_t_) / dz);
            if (lo <= hi) {
                slope_lo_ = lo, slope_hi_ = hi;
                last_fitted = i++;
                continue;
            }
            end_segment_at(last_fitted);  // vertex i is tried again from the new origin
        }
        // The end, unless already there; always when only the start was emitted
        // (every vertex at z_0 with t = 1), since a function has 0 or >= 2 vertices.
        if (out_z_.size() - begin == 1 || out_z_.back() != z_[n - 1] || out_t_.back() != t_[n - 1])
            emit(z_[n - 1], t_[n - 1]);
    }

private:
    // The input vertex's window, clipped so that every output value lies in
    // [t_last, 1]; the last vertex's window is the point t_last itself.
    Window window(std::size_t i) const
    {
        const double last = t_.back();
        if (i + 1 == t_.size()) return {last, last};
        return {std::max(double(t_[i]) - eps_, last), std::min(double(t_[i]) + eps_, 1.0)};
    }

    // Ends the current segment at input vertex j (beyond the origin: a window
    // that empties the range always follows one that bounded it), on the
    // fitting slope nearest the one that reaches t_j itself.
    void end_segment_at(std::size_t j)
    {
        const double own = (double(t_[j]) - origin_t_) / (double(z_[j]) - origin_z_);
        const double slope = std::clamp(own, slope_lo_, slope_hi_);
        const Window w = window(j);
        // Clamped against rounding only: in exact arithmetic the value is in
        // the window, and not above the origin since the slope is <= 0.
        assert(z_[j] > origin_z_ && std::isfinite(slope));
        const double t = std::min(std::clamp(origin_t_ + slope * (double(z_[j]) - origin_z_), w.lo, w.hi), origin_t_);
        emit(z_[j], stored_inside(t, w));
    }

    // The float nearest t, moved by one ulp where rounding left the window: the
    // stored value must lie in it, since the next segment starts from it (and
    // the input's own t_j, a float, is always inside, so one exists).
    static float stored_inside(double t, const Window& w)
    {
        const float f = float(t);
        if (double(f) < w.lo) return std::nextafter(f, 2.0f);
        if (double(f) > w.hi) return std::nextafter(f, -1.0f);
        return f;
    }

    void emit(float z, float t)
    {
        out_z_.push_back(z);
        out_t_.push_back(t);
        origin_z_ = z;
        origin_t_ = t;  // the next segment starts from the value stored
        slope_lo_ = -std::numeric_limits<double>::infinity();
        slope_hi_ = 0.0;
    }

    std::span<const float> z_, t_;
    double eps_;
    std::vector<float>& out_z_;
    std::vector<float>& out_t_;
    double origin_z_ = 0.0, origin_t_ = 1.0;
    double slope_lo_ = 0.0, slope_hi_ = 0.0;
};

constexpr std::string_view kCompressOp = "compress_visibility";

void require_tolerance(float tolerance)
{
    require(std::isfinite(tolerance) && tolerance >= 0.0f, kCompressOp, "tolerance",
            "must be finite and >= 0, not " + std::to_string(tolerance));
}

}  // namespace

float dsm_default_tolerance(int samples_per_pixel)
{
    require(samples_per_pixel >= 1, "dsm_default_tolerance", "samples_per_pixel",
            "must be >= 1, not " + std::to_string(samples_per_pixel));
    return float(0.25 / std::sqrt(double(samples_per_pixel)));
}

void compress_visibility(std::span<const float> depths, std::span<const float> transmittances, float tolerance,
                         std::vector<float>& out_depths, std::vector<float>& out_transmittances)
{
    require_tolerance(tolerance);
    require_visibility_function(depths, transmittances);
    if (depths.empty()) return;
    Compressor(depths, transmittances, tolerance, out_depths, out_transmittances).run();
}

DeepShadowMap compress_deep_shadow_map(const DeepShadowMap& map, float tolerance)
{
    require_tolerance(tolerance);
    const int width = map.width(), height = map.height();
    struct Row {
        std::vector<float> z, t;
        std::vector<std::uint32_t> counts;
    };
    std::vector<Row> rows(std::size_t(std::max(height, 0)));
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& range) {
        for (int y = range.begin(); y < range.end(); ++y) {
            Row& row = rows[std::size_t(y)];
            for (int x = 0; x < width; ++x) {
                const std::size_t before = row.z.size();
                if (!map.depths(x, y).empty())
                    Compressor(map.depths(x, y), map.transmittances(x, y), tolerance, row.z, row.t).run();
                row.counts.push_back(std::uint32_t(row.z.size() - before));
            }
        }
    });
    DeepShadowMapBuilder builder(width, height);
    for (const Row& row : rows) {
        std::size_t at = 0;
        for (const std::uint32_t count : row.counts) {
            builder.add_pixel(std::span(row.z).subspan(at, count), std::span(row.t).subspan(at, count));
            at += count;
        }
    }
    return builder.build();
}

}  // namespace penumbra
