// The samples of a deep EXR as read, and their translation into a deep shadow
// map's vertices with every check a hostile file needs (deep_exr_read.cpp;
// the mapping is penumbra/deep_exr.h's, the other direction deep_exr_write.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "penumbra/deep_exr.h"
#include "penumbra/deep_shadow_map.h"

namespace penumbra::detail {

struct DeepSamples {
    // The channels, in the order of channel(c) and of BadPixel::channel in errors.
    static constexpr const char* kNames[4] = {"Z", "ZBack", "A", kDeepTransmittanceChannel};

    std::vector<unsigned> counts;       // samples per pixel, row-major over the data window
    std::vector<std::uint64_t> first;   // per pixel, the index of its first sample
    std::vector<float> z, zback, a, t;  // zback and t stay empty when the file lacks them
    int origin_x = 0, origin_y = 0;     // the data window's top-left corner (file coordinates)

    // Sizes the arrays for `total` samples (from counts) and fills `first`.
    void allocate(std::uint64_t total, bool has_zback, bool has_t);
    std::vector<float>& channel(int c);
    const std::vector<float>& channel(int c) const;
};

// The map the samples describe. Error(InvalidData) naming `path`, the pixel (file
// coordinates) and the sample for a bad value (penumbra/deep_exr.h lists them).
DeepShadowMap deep_map_from_samples(const DeepSamples& samples, int width, int height, const std::string& path);

}  // namespace penumbra::detail
