// The deep-shadow scenes: shadows that are fractions, which a single depth per
// texel cannot hold (Lokovic and Veach 2000). Each is lit by a point light, so
// its truth is the exact transmittance per receiver, the quantity a deep
// shadow map estimates. docs/reference.md describes them.
#include "scene_parts.h"

namespace penumbra::reference {

// Thin occluders: a head of opaque strands 0.8 mm thick (about a seventh of a
// texel at the 1024^2 design size, where a texel is 5.8 mm at the head) on a
// sphere resting on the ground. Their shadow on the ground and on the scalp is
// grey only on average over a texel: per point it is lit or not.
Scene hair_scene()
{
    Scene scene;
    scene.name = "hair";
    scene.description =
        "Thin occluders: 4000 opaque strands (0.8 mm thick, a seventh of a texel at 1024^2; 6 capsules each, "
        "0.35 m long) on the top of a sphere resting on the ground, under a point light.";
    const Sphere head{{0, 0.5, 0}, 0.5};
    scene.primitives = {ground(), head};
    scene.hair = {Hair{.center = head.center,
                       .scalp_radius = head.radius,
                       .axis = {0, 1, 0},
                       .cap_degrees = 75,
                       .strands = 4000,
                       .segments = 6,
                       .length = 0.35,
                       .radius = 0.0004,
                       .droop = 1.2,
                       .curl = 0.15,
                       .seed = 14}};
    scene.light = point_light({-2.0, 4.5, 1.0}, {0.3, 0.3, -0.2});
    scene.light_camera = perspective(1, 10, 62);
    scene.view = ViewCamera{{1.6, 3.1, 2.0}, {0.0, 0.1, -0.2}, {0, 1, 0}, 42};
    scene.map_size = 1024;
    return scene;
}

// Participating media: a box of fog whose extinction rises linearly along its
// own x (0.17 to 1.6 per metre), holding an opaque sphere. Its shadow on the
// ground darkens smoothly across the box, with the sphere's hard one inside.
Scene fog_scene()
{
    Scene scene;
    scene.name = "fog";
    scene.description =
        "Participating media: a 2.4 x 1.2 x 2 m box of fog 0.5 m above the ground whose extinction rises "
        "linearly across it (0.9 per metre at its centre, gradient 0.5 per metre^2 along x), an opaque sphere "
        "inside, under a point light.";
    Medium fog;
    fog.region = Box{{0, 1.1, 0}, {2.4, 1.2, 2.0}, {0, 20, 0}};
    fog.extinction = 0.9;
    fog.gradient = {0.5, 0, 0};
    scene.primitives = {ground(), Sphere{{0.2, 1.1, 0.1}, 0.35}};
    scene.media = {fog};
    scene.light = point_light({-1.5, 5.5, 1.0}, {0.4, 0, -0.1});
    scene.light_camera = perspective(1, 12, 70);
    scene.view = ViewCamera{{2.4, 4.4, 2.8}, {0.4, 0.3, -0.2}, {0, 1, 0}, 45};
    scene.map_size = 1024;
    return scene;
}

// Semi-transparent layers: three 2 cm sheets of opacity 0.3, 0.5 and 0.7 at
// heights 0.6, 1.2 and 1.8, offset and turned, so the ground holds every
// product of their transmittances (0.7, 0.5, 0.3, 0.35, 0.21, 0.15, 0.105).
Scene layers_scene()
{
    Scene scene;
    scene.name = "layers";
    scene.description =
        "Semi-transparent layers: three 1.4 m square sheets (opacity 0.3, 0.5, 0.7) at heights 0.6, 1.2 and "
        "1.8 over the ground, offset and turned so their shadows overlap in every combination, under a point "
        "light.";
    scene.primitives = {
        ground(),
        Box{{-0.3, 0.6, -0.2}, {1.4, 0.02, 1.4}, {0, 10, 0}, 0.3},
        Box{{0.2, 1.2, 0.15}, {1.4, 0.02, 1.4}, {0, 25, 0}, 0.5},
        Box{{0.5, 1.8, -0.1}, {1.4, 0.02, 1.4}, {0, 40, 0}, 0.7},
    };
    scene.light = point_light({-1.0, 6.0, 1.2}, {0.3, 0, 0});
    scene.light_camera = perspective(1, 12, 70);
    scene.view = ViewCamera{{2.2, 4.6, 3.0}, {0.4, 0.4, 0}, {0, 1, 0}, 45};
    scene.map_size = 1024;
    return scene;
}

}  // namespace penumbra::reference
