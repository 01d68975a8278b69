// Pismo's three float64 estimates on a receivers' grid (support/pismo_estimates.h).
#include "support/pismo_estimates.h"

#include <tbb/blocked_range.h>
#include <cmath>
#include <variant>
#include <tbb/parallel_for.h>

namespace penumbra::testing {

PismoEstimates pismo_estimates(const reference::PismoMaps& maps, const reference::Receivers& rx,
                               const PismoReferenceOptions& options, bool normals)
{
    const auto layered = PismoReferenceMaps::layered(maps);
    const auto farthest = PismoReferenceMaps::maximum_depth(maps);
    const int w = rx.width(), h = rx.height();
    PismoEstimates out{Image(w, h, 1), Image(w, h, 1), Image(w, h, 1)};
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                if (rx.mask.at(0, x, y) == 0) continue;
                const reference::Vec3 p{rx.world_position.at(0, x, y), rx.world_position.at(1, x, y),
                                        rx.world_position.at(2, x, y)};
                const reference::Vec3 n = normals ? reference::Vec3{rx.normal.at(0, x, y), rx.normal.at(1, x, y),
                                                                    rx.normal.at(2, x, y)}
                                                  : reference::Vec3{};
                const int surface = options.surface_ids ? int(rx.surface.at(0, x, y)) : -1;
                out.pismo.at(0, x, y) = float(pismo_visibility(layered, p, options, n, surface));
                out.maximum_depth.at(0, x, y) = float(pismo_visibility(farthest, p, options, n, surface));
                out.averaged.at(0, x, y) = float(averaged_hard_shadows(layered, p, options, n, surface));
            }
    });
    return out;
}

Image receivers_on_planes(const reference::Scene& scene, const reference::Receivers& rx, bool on_planes)
{
    // Receivers are stored in float: within 1e-4 m of the plane is on it.
    constexpr double kOnPlane = 1e-4;
    Image mask(rx.width(), rx.height(), 1);
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            const reference::Vec3 p{rx.world_position.at(0, x, y), rx.world_position.at(1, x, y),
                                    rx.world_position.at(2, x, y)};
            bool on_plane = false;
            for (const reference::Primitive& primitive : scene.primitives)
                if (const auto* plane = std::get_if<reference::Plane>(&primitive))
                    on_plane = on_plane || std::fabs(dot(p - plane->point, normalize(plane->normal))) < kOnPlane;
            mask.at(0, x, y) = rx.mask.at(0, x, y) > 0.5f && on_plane == on_planes ? 1.0f : 0.0f;
        }
    return mask;
}

std::size_t pismo_layered_bytes(const reference::PismoMaps& maps)
{
    std::size_t bytes = 0;
    for (const LayeredDepthMap& map : maps.maps) bytes += map.bytes() + bleed_empty_pixels(map).bytes();
    return bytes;
}

}  // namespace penumbra::testing
