// Deep shadow maps (Lokovic & Veach, "Deep Shadow Maps", SIGGRAPH 2000): per
// pixel, the fraction of the light's power that reaches each depth along the
// pixel's beam, a piecewise-linear visibility (transmittance) function V(z).
//
// One pixel's function is a list of vertices (z_i, t_i), i = 0..n-1, with
//  - z finite and non-decreasing (light-space depth, the units of the map);
//  - t in [0, 1] and non-increasing, t_0 = 1;
//  - n = 0 (nothing along the beam: V = 1 at every depth) or n >= 2.
// V is 1 before z_0, t_{n-1} after z_{n-1}, and linear between consecutive
// vertices. Two vertices at one depth are a step (an opaque or semi-transparent
// surface). At a step's own depth V takes the value before the step, so a
// surface does not shadow itself: the same choice as the depth comparison of
// PCF (kernels/depth_bias.h: lit when depth >= z - bias).
//
// Storage, for lookup kernels to index (docs/deep_shadow_maps.md):
//   offsets         uint32, width*height + 1 entries: pixel p = x + y*width
//                   owns vertices offsets[p] .. offsets[p+1]-1
//   depths          float, one per vertex (z_i), all pixels packed row-major
//   transmittances  float, one per vertex (t_i), same indexing
// Planar, like the moment maps: a search through a pixel's depths touches
// only depths (16 per cache line), and reads two transmittances at the end.
// Bytes: 8 per vertex plus 4 per pixel (plus 4 once).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace penumbra {

class DeepShadowMap {
public:
    DeepShadowMap() = default;  // 0 x 0

    // Takes the three arrays and checks every invariant above, throwing
    // Error(InvalidArgument) for inconsistent sizes and Error(InvalidData)
    // naming the pixel (BadPixel: x, y; channel 0 for a depth, 1 for a
    // transmittance) and the vertex for a bad value. At most 2^32 - 1 vertices.
    DeepShadowMap(int width, int height, std::vector<std::uint32_t> offsets, std::vector<float> depths,
                  std::vector<float> transmittances);

    int width() const noexcept { return width_; }
    int height() const noexcept { return height_; }
    std::size_t vertex_count() const noexcept { return depths_.size(); }
    // The storage the lookup kernels index (layout above).
    const std::vector<std::uint32_t>& offsets() const noexcept { return offsets_; }
    const std::vector<float>& depths() const noexcept { return depths_; }
    const std::vector<float>& transmittances() const noexcept { return transmittances_; }
    // Bytes of the three arrays.
    std::size_t bytes() const noexcept;

    // One pixel's vertices (x in [0, width), y in [0, height); unchecked).
    std::span<const float> depths(int x, int y) const noexcept;
    std::span<const float> transmittances(int x, int y) const noexcept;

    // V(z) of pixel (x, y) (deep_visibility below).
    float visibility(int x, int y, float z) const noexcept;

private:
    std::size_t pixel(int x, int y) const noexcept { return std::size_t(y) * std::size_t(width_) + std::size_t(x); }

    int width_ = 0, height_ = 0;
    std::vector<std::uint32_t> offsets_{0};
    std::vector<float> depths_, transmittances_;
};

// Throws Error(InvalidData) naming pixel (x, y) and the vertex unless the
// vertices form a function as above (the check the constructor makes per pixel).
void require_visibility_function(std::span<const float> depths, std::span<const float> transmittances, int x = 0,
                                 int y = 0);

// V(depth) of one function (vertices as above, n = 0 or n >= 2): 1 before the
// first vertex, the last t after the last, linear between, the value before a
// step at a step's own depth (the last vertex with z < depth and the first with
// z >= depth bracket it). A reference implementation for tests and the host;
// the lookup kernels do the same search in the dialect.
float deep_visibility(std::span<const float> depths, std::span<const float> transmittances, float depth) noexcept;

// Collects pixels in row-major order (a generator appends each pixel's
// function as it finishes it), then builds the map, checked as above.
class DeepShadowMapBuilder {
public:
    DeepShadowMapBuilder(int width, int height);  // Error(InvalidArgument) unless both >= 1

    // Appends the next pixel's vertices; Error(InvalidArgument) when the
    // spans differ in length or every pixel has been added.
    void add_pixel(std::span<const float> depths, std::span<const float> transmittances);
    // Error(InvalidArgument) unless every pixel was added; the builder is left empty.
    DeepShadowMap build();

private:
    int width_, height_;
    std::vector<std::uint32_t> offsets_{0};
    std::vector<float> depths_, transmittances_;
};

}  // namespace penumbra
