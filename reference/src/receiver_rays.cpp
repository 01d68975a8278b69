// Where a receiver's shadow rays start and what they may cross: the
// receiver's own surface exactly where the receivers name it, the normal lift
// otherwise (penumbra/reference/ground_truth.h). Shared by the area-light
// truth (light_sampling.cpp) and the sun's (cascades.cpp).
#include <cmath>

#include "penumbra/reference/ground_truth.h"

namespace penumbra::reference {

ReceiverRays::ReceiverRays(Vec3 position, Vec3 normal, int own_surface)
    : origin(own_surface >= 0 ? position : position + normal * (kNormalOffset * (1 + max_abs_component(position)))),
      normal(normal),
      own_surface(own_surface)
{
}

double ReceiverRays::transmittance(const PreparedScene& prepared, Vec3 direction, double t_max) const
{
    if (own_surface >= 0 && dot(direction, normal) <= 0) return 0;  // into the solid the point lies on
    return prepared.transmittance({origin, direction}, 0.0, t_max, own_surface);
}

std::vector<bool> opaque_surfaces(const Scene& scene)
{
    std::vector<bool> opaque;
    for (const Primitive& surface : scene_surfaces(scene)) opaque.push_back(opacity_of(surface) == 1);
    return opaque;
}

int receiver_own_surface(const Receivers& r, const std::vector<bool>& opaque, int x, int y)
{
    if (r.surface.width() != r.hit.width() || r.surface.height() != r.hit.height() || r.surface.channels() != 1)
        return -1;
    const float id = r.surface.at(0, x, y);
    if (!(id >= 0 && id < float(opaque.size())) || id != std::floor(id)) return -1;
    return opaque[std::size_t(id)] ? int(id) : -1;
}

}  // namespace penumbra::reference
