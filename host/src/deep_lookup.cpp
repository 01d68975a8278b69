// Deep shadow map lookups (penumbra/deep_lookup.h): the options checked, the
// map's three arrays as the generic lookup's source (detail::SourceArray),
// the kernel's Params (kernels/dsm_lookup.h).
#include "penumbra/deep_lookup.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>

#include "checked_lookup.h"
#include "host/backend/backend.h"
#include "penumbra/error.h"
#include "visibility_output.h"

namespace penumbra {
namespace {

const std::string kDsmOp = "dsm";

// The kernel's bisection adds a step to an index below the vertex count;
// both stay below 2^31 (signed gather indices) under this bound.
constexpr std::size_t kMaxLookupVertices = std::size_t(1) << 30;

// The largest power of two at most the longest pixel's vertex count (0 for
// a map of empty pixels): the bisection's first step.
int search_top(const DeepShadowMap& map)
{
    const std::vector<std::uint32_t>& offsets = map.offsets();
    std::uint32_t longest = 0;
    for (std::size_t p = 0; p + 1 < offsets.size(); ++p) longest = std::max(longest, offsets[p + 1] - offsets[p]);
    return int(std::bit_floor(longest));
}

// The kernel reads index 0 of each array even where no pixel has a vertex
// (a masked lane still gathers); a map with none gets one stand-in each.
constexpr float kNoDepth[1] = {0.0f}, kNoTransmittance[1] = {1.0f};

detail::LookupSource source_of(const DeepShadowMap& map)
{
    const bool empty = map.vertex_count() == 0;
    const std::span<const float> depths = empty ? std::span<const float>(kNoDepth) : std::span(map.depths());
    const std::span<const float> transmittances =
        empty ? std::span<const float>(kNoTransmittance) : std::span(map.transmittances());
    return detail::LookupSource({std::span(map.offsets()), depths, transmittances});
}

DsmParams params_of(const DeepShadowMap& map, const Image& receivers, const DeepLookupOptions& o, const Image& out)
{
    DsmParams p{};
    p.map = pn_dims{map.width(), map.height(), map.width(), map.width() * map.height()};
    p.receivers = detail::dims_of(receivers);
    p.out = detail::dims_of(out);
    p.filter = o.filter == DeepFilter::Tent ? PN_DSM_TENT : PN_DSM_BOX;
    p.radius = o.radius;
    p.search = o.search == DeepSearch::Linear ? PN_DSM_LINEAR : PN_DSM_BINARY;
    p.search_top = search_top(map);
    p.vertices = int(map.vertex_count());
    p.last_vertex = std::max(p.vertices - 1, 0);
    p.bias = o.bias;
    return p;
}

}  // namespace

void deep_lookup(Context& context, const DeepShadowMap& map, const Image& receivers, const DeepLookupOptions& o,
                 Image& out)
{
    check(kDeepRadiusRange, o.radius, kDsmOp);
    check(kDepthBiasRange, o.bias, kDsmOp);
    require(map.width() >= 1 && map.height() >= 1, kDsmOp, "deep-map", "the deep shadow map is empty (0 pixels)");
    require(std::size_t(map.width()) * std::size_t(map.height()) < kMaxLookupVertices, kDsmOp, "deep-map",
            "a lookup indexes fewer than 2^30 pixels; use a smaller map");
    require(map.vertex_count() < kMaxLookupVertices, kDsmOp, "deep-map",
            "the map holds " + std::to_string(map.vertex_count()) +
                " vertices; a lookup indexes fewer than 2^30 (compress it with a larger tolerance, or split it)");
    require(receivers.channels() >= 3 && !receivers.empty(), kDsmOp, "receivers",
            "the receivers need channels u, v, z (got " + std::to_string(receivers.channels()) + " channels, " +
                std::to_string(receivers.width()) + "x" + std::to_string(receivers.height()) + ")");
    require(out.channels() == 1 && out.width() == receivers.width() && out.height() == receivers.height(), kDsmOp,
            "the output must be a 1-channel image of the receivers' size (" + std::to_string(receivers.width()) +
                "x" + std::to_string(receivers.height()) + ")");
    const DsmParams p = params_of(map, receivers, o, out);
    const detail::LookupSource source = source_of(map);
    detail::checked_lookup(kDsmOp, receivers, [&](int* bad_rows) {
        detail::receiver_lookup<detail::KernelId::dsm_lookup>(context.impl(), source, receivers, p, out, bad_rows);
    });
}

PN_ALLOCATING_VISIBILITY(deep_lookup, DeepShadowMap, DeepLookupOptions)

}  // namespace penumbra
