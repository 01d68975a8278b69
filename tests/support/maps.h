// Small synthetic inputs and independent references for kernel tests.
#pragma once

#include <cstdint>
#include <random>

#include "penumbra/image.h"

namespace penumbra::testing {

// Depths uniform in [0, 1]; with `dyadic`, multiples of 1/16, so that float
// sums of z and z^2 stay exact on small maps (an exact reference for float mode).
Image random_depth(int width, int height, std::uint32_t seed, bool dyadic = false);

// Receivers (u, v, z) on a grid: u, v at texel centres of a map of size
// map_w x map_h (cycling when the grid is larger), z uniform in [z_lo, z_hi].
Image receivers_on_texels(int width, int height, int map_w, int map_h, float z_lo, float z_hi,
                          std::uint32_t seed);

// Depths of only 0 and 1: each texel, row by row, is 1 where the next draw of
// std::mt19937(seed) is a multiple of `one_in` (about one texel in one_in).
Image binary_depth(int width, int height, std::uint32_t seed, unsigned one_in);

// Receivers (u, v, z) anywhere: per pixel, row by row, u, v uniform in
// [uv_lo, uv_hi] and z uniform in [z_lo, z_hi], drawn from std::mt19937(seed)
// in that order.
Image scattered_receivers(int width, int height, float uv_lo, float uv_hi, float z_lo, float z_hi,
                          std::uint32_t seed);

// One receiver per texel centre of the map, all at depth z.
Image receivers_at_depth(int map_w, int map_h, float z);

// Limb l (0-based, most significant first) of value k = z^k (1-based) of an
// exact limb table with `limbs` limbs per value, as the kernel computes it.
std::uint32_t exact_limb(float z, int k, int limbs, int l);

// Brute-force sums over texels [x0, x1) x [y0, y1).
double brute_sum(const Image& depth, int k, int x0, int x1, int y0, int y1);
// The mean of z^k over the window of half-width `radius` around texel (x, y),
// clipped to the map (the box filter's window at a map's edge).
double window_mean(const Image& depth, int k, int x, int y, int radius);
// The wrapped sum of plane `plane` (1-based, as MomentTable::exact_box_sum).
std::uint32_t brute_exact_sum(const Image& depth, int plane, int limbs, int x0, int x1, int y0, int y1);

// Channel 0 of two images of one size: the largest |a - b| and how many
// pixels differ at all (cross-backend agreement: bit-exact or within a bound).
struct Difference {
    double max = 0.0;
    int differing = 0;
};
Difference difference(const Image& a, const Image& b);

}  // namespace penumbra::testing
