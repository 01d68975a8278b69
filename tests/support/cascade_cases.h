// Scenes and inputs of the cascaded-shadow tests and benchmarks
// (docs/cascades.md): the built-in scenes with directional lights and the
// courtyard, whose pillar stands nearer the sun than the first cascade's near
// plane (the pancaking case), rendered once per process.
#pragma once

#include <map>
#include <string>
#include <utility>

#include "penumbra/cascades.h"
#include "penumbra/reference/cascades.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"

namespace penumbra::testing {

// A viewer standing in a yard, the sun low behind them: the pillar behind
// the viewer (8 m tall) throws its shadow across the ground in view, while
// its top lies far nearer the sun than the first split's corners.
inline reference::Scene courtyard_scene()
{
    using namespace reference;
    Scene scene;
    scene.name = "courtyard";
    scene.description = "Pancaking: an 8 m pillar behind the viewer shadows the ground in view; the sun is low.";
    scene.primitives = {Plane{{0, 0, 0}, {0, 1, 0}}, Box{{0.8, 4, 3}, {0.6, 8, 0.6}, {0, 0, 0}},
                        Sphere{{-1, 0.5, -4}, 0.5}, Box{{1.5, 0.4, -7}, {0.8, 0.8, 0.8}, {0, 30, 0}}};
    scene.light = AreaLight{LightShape::Point, {0, 20, 10}, normalize(Vec3{0, -20, -14}), {0, 1, 0}, 0, 0};
    scene.light_camera = LightCamera{Projection::Perspective, 1, 60, 90, 10};
    scene.view = ViewCamera{{0, 1.7, 0}, {0, 0.6, -8}, {0, 1, 0}, 60};
    scene.directional_lights = {{normalize(Vec3{0.1, -0.55, -1}), {0, 1, 0}}};
    return scene;
}

inline reference::Scene cascade_scene(const std::string& name)
{
    return name == "courtyard" ? courtyard_scene() : reference::builtin_scene(name);
}

struct CascadeCase {
    reference::Receivers receivers;
    Image rx;     // reference::cascade_receivers
    Image truth;  // reference::directional_truth
    CascadeShadows shadows;
};

// The shadowed range of a scene's cascades: the courtyard's ground runs to
// the horizon, so its cascades end at 40 m (the notes stretch theirs over
// 300 m of a town); the others' from the closest to the farthest surface seen.
inline reference::CascadeSetup scene_setup(const std::string& scene_name, reference::CascadeSetup setup)
{
    if (scene_name == "courtyard" && setup.far == 0) setup.near = 0.5, setup.far = 40;
    return setup;
}

// scene, light, frame width x height, setup: rendered once and kept.
inline const CascadeCase& cascade_case(const std::string& scene_name, int light, int width, int height,
                                       const reference::CascadeSetup& setup = {})
{
    using Key = std::tuple<std::string, int, int, int, int, int, int>;
    static std::map<Key, CascadeCase> cases;
    const Key key{scene_name, light, width, height, setup.count, setup.map_size, int(setup.near_plane)};
    auto found = cases.find(key);
    if (found != cases.end()) return found->second;
    const reference::Scene scene = cascade_scene(scene_name);
    CascadeCase c;
    c.receivers = reference::render_receivers(scene, width, height);
    c.rx = reference::cascade_receivers(c.receivers);
    c.truth = reference::directional_truth(scene, light, c.receivers);
    c.shadows = reference::render_cascades(scene, light, c.receivers, scene_setup(scene_name, setup));
    return cases.emplace(key, std::move(c)).first->second;
}

// The shadows with only cascade c (its frame and its rows of the maps).
inline CascadeShadows single_cascade(const CascadeShadows& s, int c)
{
    CascadeShadows one = s;
    const int size = s.maps.width(), rows = s.maps.height() / int(s.cascades.size());
    one.cascades = {s.cascades[std::size_t(c)]};
    one.maps = Image(size, rows, 1);
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < size; ++x) one.maps.at(0, x, y) = s.maps.at(0, x, c * rows + y);
    return one;
}

}  // namespace penumbra::testing
