#include "support/maps.h"

#include <algorithm>
#include <cmath>

namespace penumbra::testing {

Image random_depth(int width, int height, std::uint32_t seed, bool dyadic)
{
    Image depth(width, height, 1);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    std::uniform_int_distribution<int> sixteenths(0, 16);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) depth.at(0, x, y) = dyadic ? float(sixteenths(rng)) / 16.0f : uniform(rng);
    return depth;
}

Image receivers_on_texels(int width, int height, int map_w, int map_h, float z_lo, float z_hi, std::uint32_t seed)
{
    Image rx(width, height, 3);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> depth(z_lo, z_hi);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            rx.at(0, x, y) = (float(x % map_w) + 0.5f) / float(map_w);
            rx.at(1, x, y) = (float(y % map_h) + 0.5f) / float(map_h);
            rx.at(2, x, y) = depth(rng);
        }
    return rx;
}

Image binary_depth(int width, int height, std::uint32_t seed, unsigned one_in)
{
    Image depth(width, height, 1);
    std::mt19937 rng(seed);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) depth.at(0, x, y) = float(rng() % one_in == 0);
    return depth;
}

Image scattered_receivers(int width, int height, float uv_lo, float uv_hi, float z_lo, float z_hi,
                          std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uv(uv_lo, uv_hi), z(z_lo, z_hi);
    Image rx(width, height, 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            rx.at(0, x, y) = uv(rng);
            rx.at(1, x, y) = uv(rng);
            rx.at(2, x, y) = z(rng);
        }
    return rx;
}

Image receivers_at_depth(int map_w, int map_h, float z)
{
    Image rx = receivers_on_texels(map_w, map_h, map_w, map_h, 0.0f, 0.0f, 1);
    rx.fill(2, z);
    return rx;
}

std::uint32_t exact_limb(float z, int k, int limbs, int l)
{
    // Same operations as sat_texel_values and sat_limbs (kernels/moment_table.h):
    // z^k by repeated double products, rounded to 16 limbs bits.
    double v = z;
    for (int i = 1; i < k; ++i) v *= double(z);
    double rest = v + std::ldexp(0.5, -16 * limbs);
    std::uint32_t limb = 0;
    for (int i = 0; i <= l; ++i) {
        rest *= 65536.0;
        const double whole = std::floor(rest);
        limb = std::uint32_t(whole);
        rest -= whole;
    }
    return limb;
}

double brute_sum(const Image& depth, int k, int x0, int x1, int y0, int y1)
{
    double sum = 0.0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += std::pow(double(depth.at(0, x, y)), k);
    return sum;
}

double window_mean(const Image& depth, int k, int x, int y, int radius)
{
    const int x0 = std::max(x - radius, 0), x1 = std::min(x + radius + 1, depth.width());
    const int y0 = std::max(y - radius, 0), y1 = std::min(y + radius + 1, depth.height());
    return brute_sum(depth, k, x0, x1, y0, y1) / (double(x1 - x0) * (y1 - y0));
}

std::uint32_t brute_exact_sum(const Image& depth, int plane, int limbs, int x0, int x1, int y0, int y1)
{
    const int k = (plane - 1) / limbs + 1, l = (plane - 1) % limbs;
    std::uint64_t sum = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += exact_limb(depth.at(0, x, y), k, limbs, l);
    return std::uint32_t(sum);
}

Difference difference(const Image& a, const Image& b)
{
    Difference d;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const double diff = std::abs(double(a.at(0, x, y)) - b.at(0, x, y));
            d.max = std::max(d.max, diff);
            d.differing += diff != 0.0;
        }
    return d;
}

}  // namespace penumbra::testing
