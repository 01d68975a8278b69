// Compression of deep shadow map visibility functions within an error bound
// (Lokovic & Veach, "Deep Shadow Maps", SIGGRAPH 2000, the compression
// section): a function with fewer vertices that is within +-tolerance of the
// input at every depth. docs/deep_shadow_maps.md derives it.
//
// Guarantees, for an input that is a valid function (penumbra/deep_shadow_map.h):
//  - |compressed(z) - input(z)| <= tolerance (plus float rounding of t, under
//    1e-7) at every depth z, between vertices too, and on both sides of a step;
//  - the output is a valid function: non-increasing, in [0, 1], t_0 = 1;
//  - exact at the ends: the first vertex (z_0, 1) and the last (z_{n-1},
//    t_{n-1}) are the input's, bit for bit;
//  - every output depth is an input depth, bit for bit (never interpolated),
//    and every step of the input larger than 2*tolerance is kept as a step at
//    its exact depth: so compression moves no surface towards the light and
//    adds no self-shadowing beyond the tolerance itself;
//  - one pass, O(n) time, no allocation beyond the output.
#pragma once

#include <span>
#include <vector>

#include "penumbra/deep_shadow_map.h"

namespace penumbra {

// The paper's default tolerance for N samples per pixel: 0.25 / sqrt(N), half
// the expected noise magnitude O(N^-1/2) of the sampled function.
// Error(InvalidArgument) unless samples_per_pixel >= 1.
float dsm_default_tolerance(int samples_per_pixel);

// Appends the compressed function of (depths, transmittances) to the two
// output vectors (nothing for an empty function). Error(InvalidArgument)
// unless tolerance is finite and >= 0; Error(InvalidData) naming the vertex
// unless the input is a valid function.
void compress_visibility(std::span<const float> depths, std::span<const float> transmittances, float tolerance,
                         std::vector<float>& out_depths, std::vector<float>& out_transmittances);

// Every pixel of `map` compressed (pixels in parallel).
DeepShadowMap compress_deep_shadow_map(const DeepShadowMap& map, float tolerance);

}  // namespace penumbra
