// The samples of a deep EXR as read, and their translation into a deep shadow
// map's vertices with every check a hostile file needs (deep_exr_read.cpp;
// the mapping is penumbra/deep_exr.h's, the other direction deep_exr_write.cpp).
#pragma once

#include <OpenEXR/ImfHeader.h>

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/deep_exr.h"
#include "penumbra/deep_shadow_map.h"

namespace penumbra::detail {

struct DeepSamples {
    // The channels, in the order of channel(c) and of BadPixel::channel in errors.
    static constexpr const char* kNames[4] = {"Z", "ZBack", "A", kDeepTransmittanceChannel};

    std::vector<unsigned> counts;       // samples per pixel, row-major over the data window
    std::vector<std::uint64_t> first;   // per pixel, the index of its first sample
    std::vector<float> z, zback, a, t;  // zback, a and t stay empty when the file lacks them (or a is not read)
    std::vector<std::uint32_t> ids;     // DeepFileKind::id_channel's samples, when read (has_ids)
    bool has_ids = false;
    int origin_x = 0, origin_y = 0;     // the data window's top-left corner (file coordinates)
    int width = 0, height = 0;          // the data window's size
    bool has[4] = {};                   // channel(c) is read from the file (it may hold no sample)

    // Sizes the arrays for `total` samples (from counts) and fills `first`.
    void allocate(std::uint64_t total, bool has_zback, bool has_a, bool has_t);
    std::vector<float>& channel(int c);
    const std::vector<float>& channel(int c) const;
};

// What a reader of deep files reads: its operation (its errors name it), what
// such a file holds and which command writes one (for the errors), and
// whether A is required and read (deep shadow maps) or not (layered depth
// maps, penumbra/layered_exr.h: Z alone), and the name of an optional UINT
// channel of ids it reads too (layered maps: "surface"; empty: none).
struct DeepFileKind {
    std::string_view operation, what, writer;
    bool needs_opacity;
    std::string_view id_channel{};
};

// Every sample of the file's channels Z, ZBack, A (when kind.needs_opacity),
// penumbra.T and kind.id_channel (which must be UINT), after the checks of deep_exr_read.cpp's header comment:
// nothing is allocated on the file's word alone. `header`, when given, sees
// the file's header (its attributes) before any sample is read. Error(Io)
// naming the file and kind.operation.
DeepSamples read_deep_samples(const std::string& path, const ExrReadLimits& limits, const DeepFileKind& kind,
                              const std::function<void(const Imf::Header&)>& header = {});

// The map the samples describe. Error(InvalidData) naming `path`, the pixel (file
// coordinates) and the sample for a bad value (penumbra/deep_exr.h lists them).
DeepShadowMap deep_map_from_samples(const DeepSamples& samples, int width, int height, const std::string& path);

}  // namespace penumbra::detail
