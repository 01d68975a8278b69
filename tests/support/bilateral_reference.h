// Independent references for the cross-bilateral filter tests: the filter of
// kernels/bilateral.h by brute force in double (clamp-to-edge, exp() from the
// C library, no shared code with the kernels), a plain Gaussian blur in
// closed form, and synthetic guides.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "penumbra/bilateral.h"
#include "penumbra/image.h"

namespace penumbra::testing {

// The kernel's floor on Gaussian weights (PN_BILATERAL_CUT): 2^-60.
inline constexpr double kBilateralWeightFloorLog2 = 60.0;

inline int clamp_index(int v, int size) { return std::clamp(v, 0, size - 1); }

struct Tap {
    int dx, dy;
};

// The window of `o` as offsets: square or disk, and 1D (dy = 0) for a pass.
inline std::vector<Tap> window_taps(const BilateralOptions& o, bool one_axis)
{
    std::vector<Tap> taps;
    const int r = o.radius;
    for (int dy = one_axis ? 0 : -r; dy <= (one_axis ? 0 : r); ++dy)
        for (int dx = -r; dx <= r; ++dx)
            if (one_axis || o.window == BilateralWindow::Square || dx * dx + dy * dy <= r * r) taps.push_back({dx, dy});
    return taps;
}

// w(p, q) in double, as the header of kernels/bilateral.h defines it, with
// the kernel's documented floor: Gaussian weights below 2^-60 are 2^-60, and
// taps whose spatial weight alone is below 2^-60 are not in the window.
// Returns a negative value for a tap outside the window.
inline double reference_weight(const BilateralOptions& o, int dx, int dy, double zp, double zq, const double* np,
                               const double* nq)
{
    const double ln2 = std::log(2.0);
    const double spatial_bits = (dx * dx + dy * dy) / (2.0 * o.spatial_sigma * o.spatial_sigma) / ln2;
    if (spatial_bits > kBilateralWeightFloorLog2) return -1.0;
    double d = zq - zp;
    if (o.relative) d /= std::max(std::fabs(zp), 1e-30);
    double normal_bits = 0.0;
    if (np) {
        const double ex = nq[0] - np[0], ey = nq[1] - np[1], ez = nq[2] - np[2];
        normal_bits = (ex * ex + ey * ey + ez * ez) / (2.0 * o.normal_sigma * o.normal_sigma) / ln2;
    }
    if (o.range == BilateralRange::Threshold) {
        if (std::fabs(d) > o.depth_threshold) return 0.0;
        return std::exp2(-spatial_bits) * std::exp2(-std::min(normal_bits, kBilateralWeightFloorLog2));
    }
    const double range_bits = d * d / (2.0 * o.depth_sigma * o.depth_sigma) / ln2;
    return std::exp2(-std::min(spatial_bits + range_bits + normal_bits, kBilateralWeightFloorLog2));
}

// One filtering pass over `taps` of `values` (double planes, w x h each).
inline std::vector<std::vector<double>> reference_pass(const BilateralOptions& o, const std::vector<Tap>& taps,
                                                        const std::vector<std::vector<double>>& values,
                                                        const Image& guide, const Image* normals, bool transpose)
{
    const int w = guide.width(), h = guide.height();
    std::vector<std::vector<double>> out(values.size(), std::vector<double>(std::size_t(w) * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double zp = guide.at(0, x, y);
            double np[3], nq[3];
            if (normals)
                for (int c = 0; c < 3; ++c) np[c] = normals->at(c, x, y);
            std::vector<double> sum(values.size(), 0.0);
            double total = 0.0;
            for (const Tap& t : taps) {
                const int dx = transpose ? t.dy : t.dx, dy = transpose ? t.dx : t.dy;
                const int qx = clamp_index(x + dx, w), qy = clamp_index(y + dy, h);
                if (normals)
                    for (int c = 0; c < 3; ++c) nq[c] = normals->at(c, qx, qy);
                const double wq = reference_weight(o, dx, dy, zp, guide.at(0, qx, qy), normals ? np : nullptr,
                                                   normals ? nq : nullptr);
                if (wq < 0.0) continue;
                total += wq;
                for (std::size_t c = 0; c < values.size(); ++c) sum[c] += wq * values[c][std::size_t(qy) * w + qx];
            }
            for (std::size_t c = 0; c < values.size(); ++c) out[c][std::size_t(y) * w + x] = sum[c] / total;
        }
    return out;
}

// cross_bilateral() by brute force: the full window, or the separable passes.
inline std::vector<std::vector<double>> reference_bilateral(const Image& mask, const Image& guide,
                                                             const BilateralOptions& o, const Image* normals = nullptr)
{
    std::vector<std::vector<double>> values(std::size_t(mask.channels()));
    for (int c = 0; c < mask.channels(); ++c)
        for (int y = 0; y < mask.height(); ++y)
            for (int x = 0; x < mask.width(); ++x) values[std::size_t(c)].push_back(mask.at(c, x, y));
    if (!o.separable) return reference_pass(o, window_taps(o, false), values, guide, normals, false);
    const std::vector<Tap> axis = window_taps(o, true);
    return reference_pass(o, axis, reference_pass(o, axis, values, guide, normals, false), guide, normals, true);
}

// A plain (not cross-bilateral) Gaussian blur in closed form, clamp-to-edge:
// what the filter must equal on a flat guide.
inline std::vector<double> gaussian_blur(const Image& mask, int c, int radius, double sigma, bool disk)
{
    const int w = mask.width(), h = mask.height();
    std::vector<double> out(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0.0, total = 0.0;
            for (int dy = -radius; dy <= radius; ++dy)
                for (int dx = -radius; dx <= radius; ++dx) {
                    if (disk && dx * dx + dy * dy > radius * radius) continue;
                    const double g = std::exp(-(dx * dx + dy * dy) / (2.0 * sigma * sigma));
                    sum += g * mask.at(c, clamp_index(x + dx, w), clamp_index(y + dy, h));
                    total += g;
                }
            out[std::size_t(y) * w + x] = sum / total;
        }
    return out;
}

// A guide with structure: a sloped plane in (0.3, 0.7) with a raised
// rectangle (0.15 nearer) and per-pixel noise of +-noise.
inline Image structured_guide(int w, int h, std::uint32_t seed, float noise = 0.01f)
{
    Image g(w, h, 1);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-noise, noise);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float z = 0.5f + 0.2f * (float(x) / float(std::max(w, 2)) - 0.5f) + 0.1f * float(y) / float(std::max(h, 2));
            if (x >= w / 4 && x < (3 * w) / 4 && y >= h / 3 && y < (2 * h) / 3) z -= 0.15f;
            g.at(0, x, y) = z + jitter(rng);
        }
    return g;
}

inline Image random_mask(int w, int h, int channels, std::uint32_t seed)
{
    Image m(w, h, channels);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int c = 0; c < channels; ++c)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) m.at(c, x, y) = u(rng);
    return m;
}

// Unit normals that turn across the image (and jump inside the rectangle of
// structured_guide), so that normal weights matter.
inline Image structured_normals(int w, int h)
{
    Image n(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool box = x >= w / 4 && x < (3 * w) / 4 && y >= h / 3 && y < (2 * h) / 3;
            const double a = box ? 1.2 : 0.02 * x, b = 0.01 * y;
            const double v[3] = {std::sin(a) * std::cos(b), std::sin(b), std::cos(a) * std::cos(b)};
            for (int c = 0; c < 3; ++c) n.at(c, x, y) = float(v[c]);
        }
    return n;
}

// max |a - b| over every channel and pixel.
inline double max_difference(const Image& image, const std::vector<std::vector<double>>& reference)
{
    double worst = 0.0;
    for (int c = 0; c < image.channels(); ++c)
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
                worst = std::max(worst, std::fabs(image.at(c, x, y) -
                                                  reference[std::size_t(c)][std::size_t(y) * image.width() + x]));
    return worst;
}

inline double max_difference(const Image& a, const Image& b)
{
    double worst = 0.0;
    for (int c = 0; c < a.channels(); ++c)
        for (int y = 0; y < a.height(); ++y)
            for (int x = 0; x < a.width(); ++x)
                worst = std::max(worst, double(std::fabs(a.at(c, x, y) - b.at(c, x, y))));
    return worst;
}

}  // namespace penumbra::testing
