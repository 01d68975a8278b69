// The deep shadow map's storage, its invariants and its reference evaluation
// (penumbra/deep_shadow_map.h).
#include "penumbra/deep_shadow_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "penumbra/error.h"

namespace penumbra {
namespace {

constexpr std::string_view kDeepMapOp = "deep_shadow_map";

[[noreturn]] void bad_vertex(int x, int y, std::size_t vertex, int channel, float value, const std::string& what)
{
    throw Error(ErrorCategory::InvalidData, kDeepMapOp, channel == 0 ? "depths" : "transmittances",
                "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "), vertex " + std::to_string(vertex) +
                    ": " + what,
                BadPixel{channel, x, y, value});
}

}  // namespace

void require_visibility_function(std::span<const float> z, std::span<const float> t, int x, int y)
{
    require(z.size() == t.size(), kDeepMapOp, "transmittances",
            "one transmittance per depth: " + std::to_string(z.size()) + " depths, " + std::to_string(t.size()) +
                " transmittances");
    const std::size_t n = z.size();
    if (n == 1)
        bad_vertex(x, y, 0, 0, z[0],
                   "a function has no vertices or at least two; one vertex describes no segment");
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(z[i])) bad_vertex(x, y, i, 0, z[i], "the depth is not finite");
        if (!(t[i] >= 0.0f && t[i] <= 1.0f))
            bad_vertex(x, y, i, 1, t[i], "the transmittance is not in [0, 1]");
        if (i == 0 && t[i] != 1.0f)
            bad_vertex(x, y, i, 1, t[i], "the first vertex's transmittance must be 1 (all light arrives)");
        if (i > 0 && z[i] < z[i - 1])
            bad_vertex(x, y, i, 0, z[i], "depths decrease (" + std::to_string(z[i - 1]) + " before it); sort them");
        if (i > 0 && t[i] > t[i - 1])
            bad_vertex(x, y, i, 1, t[i],
                       "the transmittance increases (" + std::to_string(t[i - 1]) +
                           " before it); light is only ever absorbed along a beam");
    }
}

DeepShadowMap::DeepShadowMap(int width, int height, std::vector<std::uint32_t> offsets, std::vector<float> depths,
                             std::vector<float> transmittances)
    : width_(width), height_(height), offsets_(std::move(offsets)), depths_(std::move(depths)),
      transmittances_(std::move(transmittances))
{
    require(width >= 1 && height >= 1, kDeepMapOp, "size",
            "a deep shadow map needs at least one pixel, not " + std::to_string(width) + "x" + std::to_string(height));
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    require(offsets_.size() == pixels + 1, kDeepMapOp, "offsets",
            "needs width*height + 1 = " + std::to_string(pixels + 1) + " entries, not " +
                std::to_string(offsets_.size()));
    require(depths_.size() == transmittances_.size(), kDeepMapOp, "transmittances",
            "one transmittance per depth: " + std::to_string(depths_.size()) + " depths, " +
                std::to_string(transmittances_.size()) + " transmittances");
    require(depths_.size() <= std::numeric_limits<std::uint32_t>::max(), kDeepMapOp, "depths",
            "at most 2^32 - 1 vertices can be indexed by 32-bit offsets");
    require(offsets_.front() == 0 && offsets_.back() == depths_.size(), kDeepMapOp, "offsets",
            "must start at 0 and end at the vertex count " + std::to_string(depths_.size()));
    // Every offset is checked before any pixel's vertices are read: with
    // {0, 5, 2} over 2 vertices, pixel 0 would otherwise read 5.
    for (std::size_t p = 0; p < pixels; ++p)
        require(offsets_[p] <= offsets_[p + 1], kDeepMapOp, "offsets",
                "decrease at pixel " + std::to_string(p) + "; they must be non-decreasing");
    for (std::size_t p = 0; p < pixels; ++p) {
        const int x = int(p % std::size_t(width)), y = int(p / std::size_t(width));
        require_visibility_function(this->depths(x, y), this->transmittances(x, y), x, y);
    }
}

std::size_t DeepShadowMap::bytes() const noexcept
{
    return offsets_.size() * sizeof(std::uint32_t) + (depths_.size() + transmittances_.size()) * sizeof(float);
}

std::span<const float> DeepShadowMap::depths(int x, int y) const noexcept
{
    const std::size_t p = pixel(x, y);
    return {depths_.data() + offsets_[p], offsets_[p + 1] - offsets_[p]};
}

std::span<const float> DeepShadowMap::transmittances(int x, int y) const noexcept
{
    const std::size_t p = pixel(x, y);
    return {transmittances_.data() + offsets_[p], offsets_[p + 1] - offsets_[p]};
}

float DeepShadowMap::visibility(int x, int y, float z) const noexcept
{
    return deep_visibility(depths(x, y), transmittances(x, y), z);
}

float deep_visibility(std::span<const float> depths, std::span<const float> transmittances, float depth) noexcept
{
    // The first vertex at or beyond `depth`: at a step's depth that is the
    // step's first vertex, so the value before the step is returned.
    const std::size_t i = std::size_t(std::lower_bound(depths.begin(), depths.end(), depth) - depths.begin());
    if (i == 0) return 1.0f;  // before the first vertex (or no vertices), or at it: t_0 = 1
    if (i == depths.size()) return transmittances.back();
    const double z0 = depths[i - 1], z1 = depths[i], t0 = transmittances[i - 1], t1 = transmittances[i];
    // z0 < depth <= z1, so z1 > z0 and the weight is in (0, 1].
    return float(t0 + (t1 - t0) * ((double(depth) - z0) / (z1 - z0)));
}

DeepShadowMapBuilder::DeepShadowMapBuilder(int width, int height) : width_(width), height_(height)
{
    require(width >= 1 && height >= 1, kDeepMapOp, "size",
            "a deep shadow map needs at least one pixel, not " + std::to_string(width) + "x" + std::to_string(height));
    offsets_.reserve(std::size_t(width) * std::size_t(height) + 1);
}

void DeepShadowMapBuilder::add_pixel(std::span<const float> depths, std::span<const float> transmittances)
{
    require(depths.size() == transmittances.size(), kDeepMapOp, "transmittances",
            "one transmittance per depth: " + std::to_string(depths.size()) + " depths, " +
                std::to_string(transmittances.size()) + " transmittances");
    require(offsets_.size() <= std::size_t(width_) * std::size_t(height_), kDeepMapOp,
            "every pixel has been added already");
    require(depths_.size() + depths.size() <= std::numeric_limits<std::uint32_t>::max(), kDeepMapOp, "depths",
            "at most 2^32 - 1 vertices can be indexed by 32-bit offsets");
    depths_.insert(depths_.end(), depths.begin(), depths.end());
    transmittances_.insert(transmittances_.end(), transmittances.begin(), transmittances.end());
    offsets_.push_back(std::uint32_t(depths_.size()));
}

DeepShadowMap DeepShadowMapBuilder::build()
{
    const std::size_t pixels = std::size_t(width_) * std::size_t(height_);
    require(offsets_.size() == pixels + 1, kDeepMapOp,
            std::to_string(offsets_.size() - 1) + " of " + std::to_string(pixels) +
                " pixels were added; add every pixel before building");
    DeepShadowMap map(width_, height_, std::exchange(offsets_, {0}), std::exchange(depths_, {}),
                      std::exchange(transmittances_, {}));
    return map;
}

}  // namespace penumbra
