// Pismo's maps as the kernel's arrays (pismo_pack.h).
#include "pismo_pack.h"

#include <algorithm>

#include "kernels/params.h"

namespace penumbra::detail {

PismoLayers pack_layers(const std::vector<LayeredDepthMap>& maps)
{
    PismoLayers out;
    std::size_t pixels = 0, depths = 0;
    for (const LayeredDepthMap& m : maps) {
        pixels += m.offsets().size() - 1;
        depths += m.depths().size();
    }
    out.offsets.reserve(pixels + 1);
    out.depths.reserve(std::max<std::size_t>(depths, 1));
    for (const LayeredDepthMap& m : maps) {
        const auto base = std::uint32_t(out.depths.size());
        const std::vector<std::uint32_t>& offsets = m.offsets();
        for (std::size_t q = 0; q + 1 < offsets.size(); ++q) out.offsets.push_back(base + offsets[q]);
        out.depths.insert(out.depths.end(), m.depths().begin(), m.depths().end());
    }
    out.offsets.push_back(std::uint32_t(out.depths.size()));
    out.depth_count = int(out.depths.size());
    if (out.depths.empty()) out.depths.push_back(0.0f);  // the kernel gathers index 0 even when no pixel holds a layer
    return out;
}

std::vector<float> pack_cameras(const std::vector<LayeredDepthMap>& maps)
{
    std::vector<float> out;
    out.reserve(maps.size() * PN_PISMO_CAMERA_FLOATS);
    for (const LayeredDepthMap& m : maps) {
        const MapCamera& c = m.camera();
        for (const auto* axis : {&c.position, &c.right, &c.down, &c.forward})
            for (double e : *axis) out.push_back(float(e));
        out.push_back(float(2 * c.tan_half_fov));
        out.push_back(float(2 * c.tan_half_fov / m.width()));
        out.push_back(0.0f);
        out.push_back(0.0f);
    }
    return out;
}

}  // namespace penumbra::detail
