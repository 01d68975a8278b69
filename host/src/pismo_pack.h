// Pismo's maps as the kernel's arrays (kernels/pismo.h, "Sources"; the record
// layouts are kernels/params.h's PN_PISMO_*): every map's layers in one pair
// of arrays, every camera in one.
#pragma once

#include <cstdint>
#include <vector>

#include "penumbra/layered_depth_map.h"

namespace penumbra::detail {

struct PismoLayers {
    std::vector<std::uint32_t> offsets;  // maps x W x H + 1: map j's pixel q at j W H + q
    std::vector<float> depths;           // at least one element (a stand-in 0 when no map holds a layer)
    int depth_count = 0;                 // the real ones
};

// Maps of one size, fewer than 2^31 pixels and depths in all (PismoMaps checks).
PismoLayers pack_layers(const std::vector<LayeredDepthMap>& maps);

std::vector<float> pack_cameras(const std::vector<LayeredDepthMap>& maps);

}  // namespace penumbra::detail
