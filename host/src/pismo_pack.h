// Pismo's maps as the kernel's arrays (kernels/pismo.h, "Sources"; the record
// layouts are kernels/params.h's PN_PISMO_*): every map's layers in one pair
// of arrays, every camera in one. PismoMaps (penumbra/pismo.h) holds its maps
// in this form only, made once, so that a shading call copies no map.
#pragma once

#include <cstdint>
#include <vector>

#include "penumbra/layered_depth_map.h"

namespace penumbra::detail {

struct PismoLayers {
    std::vector<std::uint32_t> offsets;  // maps x W x H + 1: map j's pixel q at j W H + q
    std::vector<float> depths;           // at least one element (a stand-in 0 when no map holds a layer)
    std::size_t depth_count = 0;         // the real ones
};

struct PismoArrays {
    int width = 0, height = 0;           // of every map
    PismoLayers test, bled;              // the maps the test reads, and their bled copies
    // Parallel to test.depths: each layer's surface id (a float: ids below
    // kPismoMaxSurfaceId are exact), or one stand-in -1 without ids.
    std::vector<float> test_ids;
    std::vector<float> cameras;          // PN_PISMO_CAMERA_FLOATS a map
    std::vector<MapCamera> exact_cameras;
};

// Appends one map (of the arrays' size; fewer than 2^31 pixels and depths in
// all, PismoMaps checks) to `layers`, then closes them with the end entry.
void append_layers(PismoLayers& layers, const LayeredDepthMap& map);
void close_layers(PismoLayers& layers);
void append_camera(PismoArrays& arrays, const LayeredDepthMap& map);

// Map j of `layers` as a LayeredDepthMap again.
LayeredDepthMap unpack_map(const PismoArrays& arrays, const PismoLayers& layers, int j);

}  // namespace penumbra::detail
