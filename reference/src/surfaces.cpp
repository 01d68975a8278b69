// What a ray meets in a scene: its primitives, then its hair's capsules.
#include "penumbra/reference/scene.h"

namespace penumbra::reference {

double opacity_of(const Primitive& primitive)
{
    return std::visit([](const auto& p) { return p.opacity; }, primitive);
}

std::vector<Primitive> scene_surfaces(const Scene& scene)
{
    std::vector<Primitive> surfaces = scene.primitives;
    for (const Hair& hair : scene.hair)
        for (const Capsule& capsule : hair_strands(hair)) surfaces.push_back(capsule);
    return surfaces;
}

}  // namespace penumbra::reference
