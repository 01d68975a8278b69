// Pismo's layered depth maps: storage, invariants, bleeding and the
// maximum-depth variant (penumbra/layered_depth_map.h).
#include "penumbra/layered_depth_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "penumbra/error.h"

namespace penumbra {
namespace {

constexpr std::string_view kLayeredMapOp = "layered_depth_map";

double dot3(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void require_camera(const MapCamera& cam)
{
    for (double v : {cam.position[0], cam.position[1], cam.position[2], cam.tan_half_fov})
        require(std::isfinite(v), kLayeredMapOp, "camera", "the camera's position and field of view must be finite");
    require(cam.tan_half_fov > 0, kLayeredMapOp, "camera", "the field of view must be in (0, 180) degrees");
    constexpr double kTolerance = 1e-9;
    const auto unit = [&](const std::array<double, 3>& a) { return std::fabs(dot3(a, a) - 1) <= kTolerance; };
    const auto orthogonal = [&](const std::array<double, 3>& a, const std::array<double, 3>& b) {
        return std::fabs(dot3(a, b)) <= kTolerance;
    };
    const std::array<double, 3> r = cam.right, d = cam.down, f = cam.forward;
    const std::array<double, 3> r_x_d{r[1] * d[2] - r[2] * d[1], r[2] * d[0] - r[0] * d[2], r[0] * d[1] - r[1] * d[0]};
    require(unit(r) && unit(d) && unit(f) && orthogonal(r, d) && orthogonal(r, f) && orthogonal(d, f) &&
                dot3(r_x_d, f) > 0,
            kLayeredMapOp, "camera", "right, down and forward must be a right-handed orthonormal frame");
}

[[noreturn]] void bad_depth(int x, int y, std::size_t layer, float value, const std::string& what)
{
    throw Error(ErrorCategory::InvalidData, kLayeredMapOp, "depths",
                "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "), layer " + std::to_string(layer) +
                    ": " + what,
                BadPixel{0, x, y, value});
}

void require_layers(std::span<const float> z, int x, int y)
{
    for (std::size_t i = 0; i < z.size(); ++i) {
        if (!(std::isfinite(z[i]) && z[i] > 0)) bad_depth(x, y, i, z[i], "a depth must be finite and > 0");
        if (i > 0 && !(z[i] > z[i - 1]))
            bad_depth(x, y, i, z[i], "depths must increase within a pixel (nearest first, no repeats)");
    }
}

// One pass of the squared Euclidean distance transform along a line of n
// cells (Felzenszwalb and Huttenlocher, "Distance Transforms of Sampled
// Functions", 2012): f[q] is a site's cost (infinite: no site), and on return
// nearest[i] is the q minimising (i - q)^2 + f[q] (-1 when no q is finite) and
// f[i] that minimum.
void distance_transform_line(std::vector<double>& f, std::vector<int>& nearest)
{
    const int n = int(f.size());
    std::vector<int> sites;
    std::vector<double> starts;  // where each envelope parabola starts to be lowest
    for (int q = 0; q < n; ++q) {
        if (!std::isfinite(f[q])) continue;
        const auto crossing = [&](int p) {
            return ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * (q - p));
        };
        while (!sites.empty() && crossing(sites.back()) <= starts.back()) {
            sites.pop_back();
            starts.pop_back();
        }
        starts.push_back(sites.empty() ? -std::numeric_limits<double>::infinity() : crossing(sites.back()));
        sites.push_back(q);
    }
    const std::vector<double> cost = f;
    std::size_t k = 0;
    for (int i = 0; i < n; ++i) {
        if (sites.empty()) {
            nearest[i] = -1;
            continue;
        }
        while (k + 1 < sites.size() && starts[k + 1] <= i) ++k;
        const int q = sites[k];
        nearest[i] = q;
        f[i] = double(i - q) * (i - q) + cost[q];
    }
}

// For every pixel, the index of its nearest non-empty pixel (-1: none at all).
std::vector<long long> nearest_non_empty(const LayeredDepthMap& map)
{
    const int w = map.width(), h = map.height();
    constexpr double kNone = std::numeric_limits<double>::infinity();
    std::vector<double> column_cost(std::size_t(w) * h);
    std::vector<int> column_nearest(std::size_t(w) * h);
    std::vector<double> f(h);
    std::vector<int> near(h);
    for (int x = 0; x < w; ++x) {
        for (int y = 0; y < h; ++y) f[y] = map.layers(x, y).empty() ? kNone : 0.0;
        distance_transform_line(f, near);
        for (int y = 0; y < h; ++y) {
            column_cost[std::size_t(y) * w + x] = near[y] < 0 ? kNone : f[y];
            column_nearest[std::size_t(y) * w + x] = near[y];
        }
    }
    std::vector<long long> nearest(std::size_t(w) * h, -1);
    std::vector<double> g(w);
    std::vector<int> along(w);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) g[x] = column_cost[std::size_t(y) * w + x];
        distance_transform_line(g, along);
        for (int x = 0; x < w; ++x) {
            if (along[x] < 0) continue;
            const int source_y = column_nearest[std::size_t(y) * w + along[x]];
            nearest[std::size_t(y) * w + x] = (long long)source_y * w + along[x];
        }
    }
    return nearest;
}

}  // namespace

LayeredDepthMap::LayeredDepthMap(int width, int height, MapCamera camera, std::vector<std::uint32_t> offsets,
                                 std::vector<float> depths)
    : width_(width), height_(height), camera_(camera), offsets_(std::move(offsets)), depths_(std::move(depths))
{
    require(width >= 1 && height >= 1, kLayeredMapOp, "size",
            "a layered depth map needs at least one pixel, not " + std::to_string(width) + "x" +
                std::to_string(height));
    require_camera(camera_);
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    require(offsets_.size() == pixels + 1, kLayeredMapOp, "offsets",
            "the offsets need width*height + 1 = " + std::to_string(pixels + 1) + " entries, not " +
                std::to_string(offsets_.size()));
    require(depths_.size() <= std::numeric_limits<std::uint32_t>::max(), kLayeredMapOp, "depths",
            "at most 2^32 - 1 depths can be indexed by 32-bit offsets");
    require(offsets_.front() == 0 && offsets_.back() == depths_.size(), kLayeredMapOp, "offsets",
            "the offsets must start at 0 and end at the depth count " + std::to_string(depths_.size()));
    for (std::size_t p = 0; p < pixels; ++p)  // all checked before any pixel is read
        require(offsets_[p] <= offsets_[p + 1], kLayeredMapOp, "offsets",
                "the offsets decrease at pixel " + std::to_string(p) + "; they must be non-decreasing");
    for (std::size_t p = 0; p < pixels; ++p)
        require_layers(layers(int(p % std::size_t(width)), int(p / std::size_t(width))), int(p % std::size_t(width)),
                       int(p / std::size_t(width)));
}

std::span<const float> LayeredDepthMap::layers(int x, int y) const noexcept
{
    const std::size_t p = std::size_t(y) * std::size_t(width_) + std::size_t(x);
    return {depths_.data() + offsets_[p], offsets_[p + 1] - offsets_[p]};
}

int LayeredDepthMap::max_layers() const noexcept
{
    std::uint32_t most = 0;
    for (std::size_t p = 0; p + 1 < offsets_.size(); ++p) most = std::max(most, offsets_[p + 1] - offsets_[p]);
    return int(most);
}

LayeredDepthMap bleed_empty_pixels(const LayeredDepthMap& map)
{
    const std::vector<long long> nearest = nearest_non_empty(map);
    LayeredDepthMapBuilder bled(map.width(), map.height(), map.camera());
    for (int y = 0; y < map.height(); ++y)
        for (int x = 0; x < map.width(); ++x) {
            const long long source = nearest[std::size_t(y) * map.width() + x];
            bled.add_pixel(source < 0 ? std::span<const float>{}
                                      : map.layers(int(source % map.width()), int(source / map.width())));
        }
    return bled.build();
}

LayeredDepthMap maximum_depth_map(const LayeredDepthMap& map)
{
    LayeredDepthMapBuilder farthest(map.width(), map.height(), map.camera());
    for (int y = 0; y < map.height(); ++y)
        for (int x = 0; x < map.width(); ++x) {
            const std::span<const float> layers = map.layers(x, y);
            farthest.add_pixel(layers.empty() ? layers : layers.last(1));
        }
    return farthest.build();
}

LayeredDepthMapBuilder::LayeredDepthMapBuilder(int width, int height, MapCamera camera)
    : width_(width), height_(height), camera_(camera)
{
    require(width >= 1 && height >= 1, kLayeredMapOp, "size",
            "a layered depth map needs at least one pixel, not " + std::to_string(width) + "x" +
                std::to_string(height));
    offsets_.reserve(std::size_t(width) * std::size_t(height) + 1);
}

void LayeredDepthMapBuilder::add_pixel(std::span<const float> depths)
{
    require(offsets_.size() <= std::size_t(width_) * std::size_t(height_), kLayeredMapOp, "pixels",
            "every pixel has been added");
    depths_.insert(depths_.end(), depths.begin(), depths.end());
    offsets_.push_back(std::uint32_t(depths_.size()));
}

LayeredDepthMap LayeredDepthMapBuilder::build()
{
    require(offsets_.size() == std::size_t(width_) * std::size_t(height_) + 1, kLayeredMapOp, "pixels",
            "only " + std::to_string(offsets_.size() - 1) + " of " +
                std::to_string(std::size_t(width_) * std::size_t(height_)) + " pixels were added");
    LayeredDepthMap map(width_, height_, camera_, std::move(offsets_), std::move(depths_));
    offsets_ = {0};
    depths_.clear();
    return map;
}

}  // namespace penumbra
