// CPU launches of the cross-bilateral filter (kernels/bilateral.h): a
// special schedule, not launch_pixels (simd/cpu_schedule.h), because one call
// of a span per band of rows measured faster than one call per strip
// (7.4-7.9 ms -> 6.3 ms, 1920x1080 disk, 1 channel, 1 thread, AVX-512;
// docs/bilateral.md, "Spans"), and the separable passes share a per-band buffer.
//
// Full schedule: bands of kRowsPerTask rows spread over TBB, one call of the
// description's span (bilateral_full_span) per band; a strip's taps are
// uniform-offset strip loads, which stay in L1 across the 2r+1 rows they touch.
// Separable schedule: bands of kBandRows rows; a band runs the horizontal pass
// over its rows and r rows above and below into a per-thread buffer, then the
// vertical pass out of that buffer, so that the intermediate stays in cache (a
// whole-image intermediate would go to memory and back). Halo rows are
// filtered twice, by the bands on either side: 2r / kBandRows extra work.
// Measured figures and the band choice: docs/bilateral.md.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "simd/cpu_backend.h"
#include "simd/cpu_schedule.h"

namespace penumbra::cpu {
namespace {

// 32 rows: a band's 4-channel pass buffer at 1920 wide (36 rows, 1.1 MB)
// stays in a 2 MB L2; 16 (more halo rows) and 64 or 128 (4-channel buffers
// that spill to L3) measured slower (docs/bilateral.md).
constexpr int kBandRows = 32;

// The calling thread's pass buffer, kept across calls (TBB's workers live as
// long as the process: one buffer of (32 + 2r) rows per thread stays
// allocated) and regrown when a call needs more.
Image& pass_buffer(int width, int rows, int channels)
{
    thread_local Image buffer;
    if (buffer.width() != width || buffer.height() < rows || buffer.channels() != channels)
        buffer = Image(width, rows, channels);
    return buffer;
}

// The kernels' pointer arguments, fetched once per call.
struct Planes {
    const float* mask;
    const float* guide;
    const float* normals;  // the guide when there are no normals: never read then
    const int* taps;
    const float* weights;
    float* out;
};

void separable(const CpuKernels& k, const Planes& in, const BilateralParams& params, int width, int height,
               int channels, int* bad_rows)
{
    const int r = params.radius;
    const int bands = (height + kBandRows - 1) / kBandRows;
    tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1), [&](const tbb::blocked_range<int>& range) {
        for (int band = range.begin(); band < range.end(); ++band) {
            const int y0 = band * kBandRows, y1 = std::min(height, y0 + kBandRows);
            const int h0 = std::max(0, y0 - r), h1 = std::min(height, y1 + r);
            Image& pass = pass_buffer(width, kBandRows + 2 * r, channels);
            float* rows = pass.plane(0);
            BilateralParams p = params;
            p.pass = detail::dims_of(pass);
            p.pass_first_row = h0;
            k.bilateral_horizontal_span(in.mask, in.guide, in.normals, in.taps, in.weights, rows, bad_rows, p, 0, width,
                                        h0, h1);
            k.bilateral_vertical_span(rows, in.guide, in.normals, in.taps, in.weights, in.out, p, 0, width, y0, y1);
        }
    });
}

}  // namespace

void CpuBackend::cross_bilateral(const Image& mask, const Image& guide, const Image* normals,
                                 const std::vector<int>& taps, const std::vector<float>& weights, bool separable_passes,
                                 const BilateralParams& params, Image& out, int* bad_rows)
{
    const Planes in{mask.plane(0), guide.plane(0), normals ? normals->plane(0) : guide.plane(0),
                    taps.data(),   weights.data(), out.plane(0)};
    if (separable_passes) {
        separable(kernels_, in, params, out.width(), out.height(), mask.channels(), bad_rows);
        return;
    }
    const CpuKernels& k = kernels_;
    tbb::parallel_for(tbb::blocked_range<int>(0, out.height(), kRowsPerTask), [&](const tbb::blocked_range<int>& rows) {
        k.bilateral_full_span(in.mask, in.guide, in.normals, in.taps, in.weights, in.out, bad_rows, params, 0,
                              out.width(), rows.begin(), rows.end());
    });
}

}  // namespace penumbra::cpu
