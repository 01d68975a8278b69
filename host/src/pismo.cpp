// Pismo's shadow-ray test (penumbra/pismo.h): the maps checked and prepared
// once (PismoMaps), then per chunk of receiver rows the two passes of
// kernels/pismo.h through the generic lookup: the first estimates of every
// map, then the rays.
#include "penumbra/pismo.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "host/backend/backend.h"
#include "penumbra/error.h"
#include "pismo_pack.h"
#include "pismo_rays.h"
#include "visibility_output.h"

namespace penumbra {
namespace {

const std::string kPismoOp = "pismo";

// Pixel and depth indices are int in the kernel.
constexpr std::size_t kMaxIndex = (std::size_t(1) << 31) - 1;

void require_maps(bool condition, const std::string& message) { require(condition, kPismoOp, "maps", message); }

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
    return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

void check_mesh(const std::vector<std::array<double, 3>>& vertices, const std::vector<std::array<int, 3>>& triangles)
{
    require_maps(!vertices.empty() && !triangles.empty(), "the light mesh is empty (" +
                                                              std::to_string(vertices.size()) + " vertices, " +
                                                              std::to_string(triangles.size()) + " triangles)");
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        for (int k : triangles[t])
            require_maps(k >= 0 && std::size_t(k) < vertices.size(),
                         "triangle " + std::to_string(t) + " names vertex " + std::to_string(k) + " of " +
                             std::to_string(vertices.size()));
        require_maps(detail::pismo_triangle_area(vertices, triangles[t]) > 0,
                     "triangle " + std::to_string(t) + " has no area; drop it from the mesh");
    }
}

void check_maps(const std::vector<std::array<double, 3>>& vertices, const std::vector<LayeredDepthMap>& maps)
{
    require_maps(maps.size() == vertices.size(), "the mesh has " + std::to_string(vertices.size()) +
                                                     " vertices but there are " + std::to_string(maps.size()) +
                                                     " maps; give one map per vertex, in vertex order");
    const int w = maps.front().width(), h = maps.front().height();
    require_maps(w >= 1 && h >= 1, "map 0 has no pixels (" + std::to_string(w) + "x" + std::to_string(h) + ")");
    std::size_t depths = 0;
    for (std::size_t j = 0; j < maps.size(); ++j) {
        const LayeredDepthMap& m = maps[j];
        require_maps(m.width() == w && m.height() == h, "map " + std::to_string(j) + " is " +
                                                            std::to_string(m.width()) + "x" +
                                                            std::to_string(m.height()) + ", map 0 " +
                                                            std::to_string(w) + "x" + std::to_string(h) +
                                                            "; render every map at one size");
        const double away = distance(m.camera().position, vertices[j]);
        require_maps(away <= 1e-6 * std::max(1.0, distance(vertices[j], {0, 0, 0})),
                     "the camera of map " + std::to_string(j) + " lies " + std::to_string(away) +
                         " from its vertex; render each map from its own vertex");
        depths += m.depths().size();
    }
    require_maps(std::size_t(w) * std::size_t(h) * maps.size() <= kMaxIndex && depths <= kMaxIndex,
                 "the maps hold " + std::to_string(depths) + " depths in " +
                     std::to_string(std::size_t(w) * std::size_t(h) * maps.size()) +
                     " pixels; the kernel indexes fewer than 2^31: use smaller maps or a coarser light mesh");
}

void check_receivers(const Image& receivers, const Image& out)
{
    const int channels = receivers.channels();
    require((channels == 3 || channels == 6 || channels == 7) && !receivers.empty(), kPismoOp, "receivers",
            "the receivers need channels x, y, z, world positions, and optionally then the normal's x, y, z and "
            "then the surface id (got " +
                std::to_string(receivers.channels()) +
                " channels, " + std::to_string(receivers.width()) + "x" + std::to_string(receivers.height()) + ")");
    require(out.channels() == 1 && out.width() == receivers.width() && out.height() == receivers.height(), kPismoOp,
            "out",
            "the output must be a 1-channel image of the receivers' size (" + std::to_string(receivers.width()) + "x" +
                std::to_string(receivers.height()) + ")");
}

// A 7th plane holds the receivers' surface ids: -1 (unknown) or an integer
// that a float holds exactly. Any other value would match no layer's id and
// silently shade the receiver as if every layer were another surface.
void check_receiver_ids(const Image& receivers)
{
    if (receivers.channels() != 7) return;
    for (int y = 0; y < receivers.height(); ++y)
        for (int x = 0; x < receivers.width(); ++x) {
            const float id = receivers.at(6, x, y);
            if (id == -1.0f || (id >= 0.0f && id <= float(kPismoMaxSurfaceId) && id == std::floor(id))) continue;
            throw Error(ErrorCategory::InvalidData, kPismoOp, "receivers",
                        "the surface id at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is " +
                            std::to_string(id) + "; an id is -1 (unknown) or an integer in [0, " +
                            std::to_string(kPismoMaxSurfaceId) + "]",
                        BadPixel{6, x, y, id});
        }
}

// Surface ids, when given: one list a map, one id a layer, each in range; not
// with the maximum-depth maps.
void check_surface_ids(const std::vector<LayeredDepthMap>& maps, PismoDepths depths,
                       const std::vector<std::vector<std::int32_t>>& ids)
{
    if (ids.empty()) return;
    const auto refuse_unless = [](bool condition, const std::string& message) {
        require(condition, kPismoOp, "surface-ids", message);
    };
    refuse_unless(depths == PismoDepths::Layered,
                  "the maximum-depth maps keep one depth a pixel, no surface's crossing: give no surface ids");
    refuse_unless(ids.size() == maps.size(), "there are " + std::to_string(ids.size()) + " lists of surface ids for " +
                                                 std::to_string(maps.size()) + " maps; give one a map, or none");
    for (std::size_t j = 0; j < ids.size(); ++j) {
        refuse_unless(ids[j].size() == maps[j].depths().size(),
                      "map " + std::to_string(j) + " has " + std::to_string(maps[j].depths().size()) +
                          " layers but " + std::to_string(ids[j].size()) + " surface ids; give one id a layer");
        for (std::size_t l = 0; l < ids[j].size(); ++l)
            refuse_unless(ids[j][l] >= 0 && ids[j][l] <= kPismoMaxSurfaceId,
                          "map " + std::to_string(j) + ", layer " + std::to_string(l) + ": surface id " +
                              std::to_string(ids[j][l]) + " is outside [0, " + std::to_string(kPismoMaxSurfaceId) + "]");
    }
}

// Rows y0 .. y0 + rows - 1 of the receivers' planes (positions, and normals if given).
Image receiver_rows(const Image& receivers, int y0, int rows)
{
    Image chunk(receivers.width(), rows, receivers.channels(), Image::Uninitialized{});
    for (int c = 0; c < receivers.channels(); ++c)
        for (int y = 0; y < rows; ++y)
            std::memcpy(chunk.row(c, y), receivers.row(c, y0 + y), sizeof(float) * std::size_t(receivers.width()));
    return chunk;
}

// What the two passes share: the maps, the ray table and the Params.
struct Prepared {
    const detail::PismoArrays& maps;
    detail::PismoRayTable rays;
    PismoParams params{};
};

Prepared prepare(const PismoMaps& maps, detail::PismoRayTable rays, float bias_texels, int receiver_channels)
{
    const bool normals = receiver_channels >= 6;
    Prepared s{*maps.arrays(), std::move(rays), PismoParams{}};
    s.params.map_width = s.maps.width;
    s.params.map_height = s.maps.height;
    s.params.maps = int(maps.vertices().size());
    s.params.triangles = int(s.rays.triangles.size() / PN_PISMO_TRIANGLE_UINTS);
    s.params.bias_texels = bias_texels;
    s.params.normals = normals ? 1 : 0;
    s.params.max_slope = kPismoMaxSlopeTexels;
    s.params.surface_ids = receiver_channels == 7 && maps.has_surface_ids() ? 1 : 0;
    s.params.other_bias_texels = kPismoOtherSurfaceBiasTexels;
    return s;
}

// One chunk of receiver rows: the estimates, then the rays, into `shaded`.
void shade_chunk(detail::BackendImpl& backend, const Prepared& s, const Image& chunk, Image& shaded, int* bad_rows)
{
    Image estimates(chunk.width(), chunk.height() * s.params.maps, 1, Image::Uninitialized{});
    PismoParams p = s.params;
    p.receivers = detail::dims_of(chunk);
    p.out = detail::dims_of(estimates);
    const detail::PismoLayers& bled = s.maps.bled;
    p.last_depth = int(std::max<std::size_t>(bled.depth_count, 1) - 1);
    detail::receiver_lookup<detail::KernelId::pismo_estimates>(
        backend, detail::LookupSource({std::span(bled.offsets), std::span(bled.depths), std::span(s.maps.cameras)}),
        chunk, p, estimates, bad_rows);
    p.out = detail::dims_of(shaded);
    p.estimates = detail::dims_of(estimates);
    const detail::PismoLayers& test = s.maps.test;
    p.last_depth = int(std::max<std::size_t>(test.depth_count, 1) - 1);
    const std::span<const float> estimate_values(estimates.plane(0), estimates.plane_pitch());
    detail::receiver_lookup<detail::KernelId::pismo_visibility>(
        backend,
        detail::LookupSource({std::span(test.offsets), std::span(test.depths), std::span(s.maps.test_ids),
                              std::span(s.maps.cameras),
                              std::span(s.rays.triangles), std::span(s.rays.rays), estimate_values}),
        chunk, p, shaded, bad_rows);
}

}  // namespace

PismoMaps::PismoMaps(std::vector<std::array<double, 3>> vertices, std::vector<std::array<int, 3>> triangles,
                     const std::vector<LayeredDepthMap>& maps, PismoDepths depths,
                     const std::vector<std::vector<std::int32_t>>& surface_ids)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)), depths_(depths),
      has_surface_ids_(!surface_ids.empty())
{
    check_mesh(vertices_, triangles_);
    check_maps(vertices_, maps);
    check_surface_ids(maps, depths, surface_ids);
    auto arrays = std::make_shared<detail::PismoArrays>();
    arrays->width = maps.front().width();
    arrays->height = maps.front().height();
    // One map at a time, so that no more than one derived map is alive beside the arrays.
    for (const LayeredDepthMap& m : maps) {
        const LayeredDepthMap deepest = depths == PismoDepths::MaximumDepth ? maximum_depth_map(m) : LayeredDepthMap();
        const LayeredDepthMap& test = depths == PismoDepths::MaximumDepth ? deepest : m;
        const LayeredDepthMap bled = bleed_empty_pixels(test);
        require_maps(arrays->bled.depths.size() + bled.depths().size() <= kMaxIndex,
                     "the bled maps hold more than 2^31 depths, which the kernel cannot index: use smaller maps");
        detail::append_layers(arrays->test, test);
        detail::append_layers(arrays->bled, bled);
        detail::append_camera(*arrays, test);
    }
    detail::close_layers(arrays->test);
    detail::close_layers(arrays->bled);
    for (const std::vector<std::int32_t>& ids : surface_ids) arrays->test_ids.insert(arrays->test_ids.end(), ids.begin(), ids.end());
    if (arrays->test_ids.empty()) arrays->test_ids.push_back(-1.0f);  // the kernel's stand-in element
    arrays->test_ids.shrink_to_fit();
    arrays_ = std::move(arrays);
}

namespace {

std::vector<LayeredDepthMap> unpack_all(const detail::PismoArrays* arrays, detail::PismoLayers detail::PismoArrays::*set,
                                        std::size_t count)
{
    std::vector<LayeredDepthMap> out;
    for (std::size_t j = 0; arrays && j < count; ++j) out.push_back(detail::unpack_map(*arrays, arrays->*set, int(j)));
    return out;
}

}  // namespace

std::vector<LayeredDepthMap> PismoMaps::test_maps() const
{
    return unpack_all(arrays_.get(), &detail::PismoArrays::test, vertices_.size());
}

std::vector<LayeredDepthMap> PismoMaps::bled_maps() const
{
    return unpack_all(arrays_.get(), &detail::PismoArrays::bled, vertices_.size());
}

std::size_t PismoMaps::bytes() const noexcept
{
    if (!arrays_) return 0;
    std::size_t total = 0;
    for (const auto* layers : {&arrays_->test, &arrays_->bled})
        total += 4 * (layers->offsets.size() + layers->depths.size());
    return total;
}

void detail::pismo_shade_rays(Context& context, const PismoMaps& maps, PismoRayTable rays, float bias_texels,
                              const Image& receivers, Image& out, std::size_t estimate_bytes)
{
    require_maps(!maps.empty(), "no maps: build PismoMaps from a light mesh and its vertices' layered maps first");
    check_receivers(receivers, out);
    check_receiver_ids(receivers);
    const Prepared s = prepare(maps, std::move(rays), bias_texels, receivers.channels());
    const std::size_t row_bytes = sizeof(float) * std::size_t(receivers.width()) * std::size_t(s.params.maps);
    const int rows = int(std::clamp<std::size_t>(estimate_bytes / row_bytes, 1, std::size_t(receivers.height())));
    for (int y0 = 0; y0 < receivers.height(); y0 += rows) {
        const int n = std::min(rows, receivers.height() - y0);
        const Image chunk = receiver_rows(receivers, y0, n);
        Image shaded(receivers.width(), n, 1, Image::Uninitialized{});
        std::vector<int> bad_rows(std::size_t(n), 0);
        shade_chunk(context.impl(), s, chunk, shaded, bad_rows.data());
        // The report names the pixel in the caller's rows, on the planes read.
        if (std::find(bad_rows.begin(), bad_rows.end(), 1) != bad_rows.end())
            require_finite(receiver_rows(receivers, 0, receivers.height()), kPismoOp, "the receivers image",
                           "receivers");
        for (int y = 0; y < n; ++y)
            std::memcpy(out.row(0, y0 + y), shaded.row(0, y), sizeof(float) * std::size_t(receivers.width()));
    }
}

void pismo_shade(Context& context, const PismoMaps& maps, const Image& receivers, const PismoOptions& o, Image& out)
{
    check(kPismoRaysRange, o.rays, kPismoOp);
    check(kPismoBiasRange, o.bias_texels, kPismoOp);
    detail::pismo_shade_rays(context, maps, detail::pismo_ray_table(maps.vertices(), maps.triangles(), o.rays),
                             o.bias_texels, receivers, out);
}

PN_ALLOCATING_VISIBILITY(pismo_shade, PismoMaps, PismoOptions)

}  // namespace penumbra
