// Layered depth maps for Pismo (Neulander, "Pismo: Parallax-Interpolated
// Shadow Map Occlusion", Rhythm & Hues; notes in ../shared/seeds/002).
//
// A perspective depth map rendered from one vertex of an area light's mesh
// that stores, per pixel, the ordered depths of every distinct surface its
// ray crosses (after proximity pruning), not only the first. Pismo needs them
// to find the occluder nearest a shaded point, which is not the surface
// nearest the light once a caster shadows itself. docs/pismo.md.
//
// Depth is the distance from the camera's position along the pixel's ray, in
// world units (not the distance along the axis): Pismo displaces a point on
// the light by an occluder distance along a shadow ray, and a radial depth is
// that distance at a corner of the light's triangle.
//
// Storage, planar like penumbra/deep_shadow_map.h:
//   offsets  uint32, width*height + 1 entries: pixel p = x + y*width owns
//            depths offsets[p] .. offsets[p+1]-1
//   depths   float, finite, > 0, strictly increasing within a pixel
// A pixel with no depth is empty: its ray meets no caster.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace penumbra {

// The camera of one map: a perspective projection centred on `position`,
// looking along `forward`, image columns along `right`, rows along `down`
// (an orthonormal, right-handed frame: right x down = forward). A point at
// local (x, y, d) = ((p-o).right, (p-o).down, (p-o).forward), d > 0, lands at
//   u = 1/2 + x / (2 d tan_half_fov),  v = 1/2 + y / (2 d tan_half_fov),
// pixel (floor(u W), floor(v H)); its depth is |p - o|.
struct MapCamera {
    std::array<double, 3> position{0, 0, 0};
    std::array<double, 3> right{1, 0, 0}, down{0, 1, 0}, forward{0, 0, 1};
    double tan_half_fov = 1;
};

class LayeredDepthMap {
public:
    LayeredDepthMap() = default;  // 0 x 0

    // Checks every invariant above: Error(InvalidArgument) for inconsistent
    // sizes or a camera whose frame is not orthonormal or whose field of view
    // is not in (0, 180) degrees, Error(InvalidData) naming the pixel for a
    // bad depth.
    LayeredDepthMap(int width, int height, MapCamera camera, std::vector<std::uint32_t> offsets,
                    std::vector<float> depths);

    int width() const noexcept { return width_; }
    int height() const noexcept { return height_; }
    const MapCamera& camera() const noexcept { return camera_; }
    const std::vector<std::uint32_t>& offsets() const noexcept { return offsets_; }
    const std::vector<float>& depths() const noexcept { return depths_; }
    std::size_t bytes() const noexcept { return 4 * (offsets_.size() + depths_.size()); }

    // One pixel's depths, nearest first (x in [0, width), y in [0, height); unchecked).
    std::span<const float> layers(int x, int y) const noexcept;
    // The most layers any pixel holds.
    int max_layers() const noexcept;

private:
    int width_ = 0, height_ = 0;
    MapCamera camera_;
    std::vector<std::uint32_t> offsets_{0};
    std::vector<float> depths_;
};

// The "bled" map of Pismo's first estimate: every empty pixel takes the
// layers of its nearest non-empty pixel (Euclidean distance between pixel
// centres; of equally near pixels, one chosen deterministically), a one-time
// preprocess, O(pixels) by the two-pass distance transform of Felzenszwalb and
// Huttenlocher (2012) with the nearest pixel carried along. A map with no non-empty pixel is returned as it is.
LayeredDepthMap bleed_empty_pixels(const LayeredDepthMap& map);

// The single-channel variant the source warns about: each non-empty pixel
// keeps only its maximum (farthest) depth.
LayeredDepthMap maximum_depth_map(const LayeredDepthMap& map);

// Collects pixels in row-major order, then builds the map, checked as above.
class LayeredDepthMapBuilder {
public:
    LayeredDepthMapBuilder(int width, int height, MapCamera camera);  // Error unless both >= 1
    void add_pixel(std::span<const float> depths);  // Error(InvalidArgument) once every pixel was added
    LayeredDepthMap build();                        // Error(InvalidArgument) unless every pixel was added

private:
    int width_, height_;
    MapCamera camera_;
    std::vector<std::uint32_t> offsets_{0};
    std::vector<float> depths_;
};

}  // namespace penumbra
