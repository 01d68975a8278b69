#include "support/pcf_reference.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace penumbra::testing {

double tap_reference(const Image& map, const RefReceiver& r, const RefBias& b, int tx, int ty)
{
    const double u = std::clamp(r.u, 0.0, 1.0), v = std::clamp(r.v, 0.0, 1.0);
    switch (b.mode) {
    case RefBiasMode::Constant:
        return r.z - b.constant;
    case RefBiasMode::Slope: {
        if (!r.plane) return r.z - b.constant;
        const double step = std::abs(r.dzdu) / map.width() + std::abs(r.dzdv) / map.height();
        return r.z - std::clamp(b.constant + b.slope_scale * step, b.low, b.high);
    }
    case RefBiasMode::ReceiverPlane: {
        if (!r.plane) return r.z - b.constant;
        const double du = (tx + 0.5) / map.width() - u, dv = (ty + 0.5) / map.height() - v;
        return r.z - std::clamp(b.constant - (r.dzdu * du + r.dzdv * dv), b.low, b.high);
    }
    }
    return r.z;
}

namespace {

// 1 when the texel (tx, ty) (inside the map) is lit; records the margin.
double lit(const Image& map, const RefReceiver& r, const RefBias& b, int tx, int ty, RefResult& result)
{
    const double d = map.at(0, tx, ty), ref = tap_reference(map, r, b, tx, ty);
    result.margin = std::min(result.margin, std::abs(d - ref));
    return d >= ref ? 1.0 : 0.0;
}

int clamp_texel(double t, int size) { return std::clamp(int(std::floor(t)), 0, size - 1); }

}  // namespace

RefReceiver ref_receiver(const Image& receivers, int x, int y)
{
    RefReceiver r{receivers.at(0, x, y), receivers.at(1, x, y), receivers.at(2, x, y)};
    if (receivers.channels() >= 6) {
        r.dzdu = receivers.at(3, x, y);
        r.dzdv = receivers.at(4, x, y);
        r.plane = receivers.at(5, x, y) > 0.5f;
    }
    r.x = x;
    r.y = y;
    return r;
}

// The window contract: the (2r+1)^2 block centred on the receiver's texel, clipped.
RefResult pcf_box_reference(const Image& map, const RefReceiver& r, const RefBias& bias, int radius)
{
    const int W = map.width(), H = map.height();
    const int cx = clamp_texel(std::clamp(r.u, 0.0, 1.0) * W, W), cy = clamp_texel(std::clamp(r.v, 0.0, 1.0) * H, H);
    RefResult result;
    const double x = std::clamp(r.u, 0.0, 1.0) * W, y = std::clamp(r.v, 0.0, 1.0) * H;
    if (x > 0.0 && x < W) result.margin = std::abs(x - std::round(x));  // which texel holds (u, v)
    if (y > 0.0 && y < H) result.margin = std::min(result.margin, std::abs(y - std::round(y)));
    double lit_taps = 0.0, taps = 0.0;
    for (int ty = std::max(cy - radius, 0); ty <= std::min(cy + radius, H - 1); ++ty)
        for (int tx = std::max(cx - radius, 0); tx <= std::min(cx + radius, W - 1); ++tx) {
            lit_taps += lit(map, r, bias, tx, ty, result);
            taps += 1.0;
        }
    result.visibility = lit_taps / taps;
    return result;
}

// n x n taps one texel apart, centred on the receiver (texel k's centre at
// k + 1/2 in texel units), each a bilinear PCF of its four texels
// (clamp-to-edge), weighted by the normalised separable Gaussian.
RefResult pcf_gauss_reference(const Image& map, const RefReceiver& r, const RefBias& bias, int grid, double sigma)
{
    const int W = map.width(), H = map.height();
    const double centre = 0.5 * (grid - 1);
    double norm = 0.0;
    for (int i = 0; i < grid; ++i) norm += std::exp(-(i - centre) * (i - centre) / (2.0 * sigma * sigma));
    const double px = std::clamp(r.u, 0.0, 1.0) * W - 0.5, py = std::clamp(r.v, 0.0, 1.0) * H - 0.5;
    RefResult result;
    double visibility = 0.0;
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            const double gi = std::exp(-(i - centre) * (i - centre) / (2.0 * sigma * sigma)) / norm;
            const double gj = std::exp(-(j - centre) * (j - centre) / (2.0 * sigma * sigma)) / norm;
            const double x = px + (i - centre), y = py + (j - centre);
            const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
            double tap = 0.0;
            for (int b = 0; b < 2; ++b)
                for (int a = 0; a < 2; ++a) {
                    const int tx = std::clamp(int(x0) + a, 0, W - 1), ty = std::clamp(int(y0) + b, 0, H - 1);
                    const double w = (a ? fx : 1.0 - fx) * (b ? fy : 1.0 - fy);
                    tap += w * lit(map, r, bias, tx, ty, result);
                }
            visibility += gi * gj * tap;
        }
    result.visibility = visibility;
    return result;
}

// Vogel's spiral: tap i at radius R sqrt((i + 1/2) / N), angle i gamma + phi,
// phi = 2 pi k / 16 from Toy Story 3's randomized 4 x 4 tile at the pixel.
RefResult pcf_disc_reference(const Image& map, const RefReceiver& r, const RefBias& bias, int taps, double radius,
                             bool rotate)
{
    static const int kTile[4][4] = {{4, 1, 3, 7}, {8, 11, 15, 6}, {10, 2, 14, 5}, {0, 13, 12, 9}};
    const double pi = std::numbers::pi, golden = pi * (3.0 - std::sqrt(5.0));
    // cos and sin of phi exact at multiples of pi / 2 (cos(pi / 2) is 6e-17 in
    // double), so that a tap on the receiver's own row or column stays there
    // exactly, as in the kernel's table of 16 rotations.
    const int k = rotate ? kTile[r.y % 4][r.x % 4] : 0;
    const double exact[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    const double cos_phi = k % 4 ? std::cos(2.0 * pi * k / 16.0) : exact[k / 4][0];
    const double sin_phi = k % 4 ? std::sin(2.0 * pi * k / 16.0) : exact[k / 4][1];
    const int W = map.width(), H = map.height();
    const double px = std::clamp(r.u, 0.0, 1.0) * W, py = std::clamp(r.v, 0.0, 1.0) * H;
    RefResult result;
    double lit_taps = 0.0;
    for (int i = 0; i < taps; ++i) {
        const double rho = radius * std::sqrt((i + 0.5) / taps), c = std::cos(i * golden), s = std::sin(i * golden);
        const double x = px + rho * (c * cos_phi - s * sin_phi), y = py + rho * (s * cos_phi + c * sin_phi);
        for (const double t : {x, y})  // an exact integer is no ambiguity: both sides hold it exactly
            if (t != std::round(t)) result.margin = std::min(result.margin, std::abs(t - std::round(t)));
        lit_taps += lit(map, r, bias, clamp_texel(x, W), clamp_texel(y, H), result);
    }
    result.visibility = lit_taps / taps;
    return result;
}

}  // namespace penumbra::testing
