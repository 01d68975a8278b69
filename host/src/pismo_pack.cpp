// Pismo's maps as the kernel's arrays (pismo_pack.h).
#include "pismo_pack.h"

#include "kernels/params.h"

namespace penumbra::detail {

void append_layers(PismoLayers& layers, const LayeredDepthMap& map)
{
    const auto base = std::uint32_t(layers.depths.size());
    const std::vector<std::uint32_t>& offsets = map.offsets();
    for (std::size_t q = 0; q + 1 < offsets.size(); ++q) layers.offsets.push_back(base + offsets[q]);
    layers.depths.insert(layers.depths.end(), map.depths().begin(), map.depths().end());
}

void close_layers(PismoLayers& layers)
{
    layers.offsets.push_back(std::uint32_t(layers.depths.size()));
    layers.depth_count = layers.depths.size();
    if (layers.depths.empty()) layers.depths.push_back(0.0f);  // the kernel gathers index 0 even when no pixel holds a layer
    layers.offsets.shrink_to_fit();
    layers.depths.shrink_to_fit();
}

void append_camera(PismoArrays& arrays, const LayeredDepthMap& map)
{
    const MapCamera& c = map.camera();
    for (const auto* axis : {&c.position, &c.right, &c.down, &c.forward})
        for (double e : *axis) arrays.cameras.push_back(float(e));
    arrays.cameras.push_back(float(2 * c.tan_half_fov));
    arrays.cameras.push_back(float(2 * c.tan_half_fov / map.width()));
    arrays.cameras.push_back(0.0f);
    arrays.cameras.push_back(0.0f);
    arrays.exact_cameras.push_back(c);
}

LayeredDepthMap unpack_map(const PismoArrays& arrays, const PismoLayers& layers, int j)
{
    const std::size_t pixels = std::size_t(arrays.width) * std::size_t(arrays.height);
    const auto first = layers.offsets.begin() + std::ptrdiff_t(std::size_t(j) * pixels);
    const std::uint32_t base = *first;
    std::vector<std::uint32_t> offsets(first, first + std::ptrdiff_t(pixels + 1));
    for (std::uint32_t& o : offsets) o -= base;
    std::vector<float> depths(layers.depths.begin() + base, layers.depths.begin() + offsets.back() + base);
    return LayeredDepthMap(arrays.width, arrays.height, arrays.exact_cameras[std::size_t(j)], std::move(offsets),
                           std::move(depths));
}

}  // namespace penumbra::detail
