// Generating a deep shadow map from a reference scene (Lokovic and Veach
// 2000, "Deep Shadow Maps", the sections on generation and sampling; notes in
// ../shared/seeds/001). docs/reference.md, "Generating a deep shadow map",
// states the choices and their error bounds.
//
// Per map pixel: K stratified jittered samples on the light's image plane; per
// sample, the ray through the light camera and its transmittance function of
// light-space linear depth z (the shadow maps' z: 0 at near, 1 at far), the
// surface steps of (1 - opacity) merged with the sampled volume transmittance;
// the pixel's visibility function is the filter-weighted average of the
// functions of the samples within the filter's radius of its centre, then
// compressed within the tolerance (penumbra/dsm_compression.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/deep_shadow_map.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/scene.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {

// The pixel filter, in pixel units about the pixel's centre.
//   Box       radius 1/2: the pixel's own K samples, equal weights.
//   Gaussian  radius 1, separable, g(x) = exp(-x^2 / (2 s^2)) - exp(-r^2 / (2 s^2))
//             with s = 1/2 (pbrt's truncated Gaussian): the samples of the
//             3 x 3 neighbourhood that lie within one pixel of the centre.
enum class DeepMapFilter { Box, Gaussian };
inline constexpr double kDeepBoxRadius = 0.5;
inline constexpr double kDeepGaussianRadius = 1.0;
inline constexpr double kDeepGaussianSigma = 0.5;

// "box", "gaussian"; Error(InvalidArgument) naming `parameter` otherwise.
DeepMapFilter deep_map_filter_from_name(const std::string& name, const std::string& parameter);
const char* deep_map_filter_name(DeepMapFilter filter);

struct DeepMapOptions {
    int size = 512;       // the map is size x size, in [1, 16384]
    int samples = 16;     // K per pixel, in [1, 4096]
    DeepMapFilter filter = DeepMapFilter::Box;
    // Compression tolerance, in [0, 1]; unset: the paper's 0.25 K^-1/2.
    std::optional<float> tolerance;
    // Bound on the volume sampling's own error (the step rule in
    // ray_transmittance), in [1e-6, 1]; unset: max(tolerance / 4, 1e-5).
    std::optional<double> volume_error;
    std::uint64_t seed = 0;  // names each pixel's sample stream
};

// What a render produced, for reports: the vertex counts before and after
// compression.
struct DeepMapStats {
    std::size_t filtered_vertices = 0;   // the filtered functions, uncompressed
    std::size_t compressed_vertices = 0;
    std::size_t samples = 0;             // sample rays traced (halo included)
    float tolerance = 0, volume_error = 0;
    // Bytes of a map holding the uncompressed functions (DeepShadowMap::bytes()).
    std::size_t uncompressed_bytes(int width, int height) const;
};

// The deep shadow map of `scene` (validated). Rows in parallel (TBB); the
// result depends on the options only, not on the thread count.
// Error(InvalidArgument) naming the option for any option out of range.
DeepShadowMap render_deep_shadow_map(const Scene& scene, const DeepMapOptions& options,
                                     DeepMapStats* stats = nullptr);

// One ray's transmittance function of z (vertices as penumbra/deep_shadow_map.h
// defines them; t in double), over the ray's events in (near, far):
//  - a surface multiplies T by 1 - opacity: two vertices at its depth;
//  - inside media, k is sampled at regular steps of each span between media
//    events (k along the ray is linear there for the linear media of
//    scene.h), the optical depth accumulated by the trapezoid of those
//    samples, and T evaluated at each sample; between samples T is linear.
//    A span of world length L gets n = ceil(L / h) equal steps with
//    h = sqrt(8 volume_error / (k_max^2 + |dk/ds|)), the largest step for
//    which linear interpolation of exp(-tau) stays within volume_error
//    (|T''| <= k^2 + |dk/ds| for T <= 1); once T <= volume_error the span
//    ends in one step (T stays between its end values), and a span takes at
//    most 2^16 steps (beyond, for media of extinction ~10^5, the bound is not
//    met).
struct RayFunction {
    std::vector<float> z;
    std::vector<double> t;
};
RayFunction ray_transmittance(const PreparedScene& prepared, const LightProjection& projection, const Ray& ray,
                              double near, double far, double volume_error);

}  // namespace penumbra::reference
