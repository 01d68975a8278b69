// The built-in reference scenes, each named for the failure it provokes.
// docs/reference.md describes them; the numbers below are their parameters.
// Every scene keeps what its view camera sees inside the light's frustum
// (tests/reference/reference_scene_test.cpp checks the valid fraction).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "penumbra/error.h"
#include "penumbra/reference/scene.h"
#include "scene_parts.h"

namespace penumbra::reference {
namespace {

// Contact hardening: a unit sphere resting on the ground and a capsule lying
// with one end on the ground and the other against the sphere. Shadows start
// hard where the occluders touch the ground and soften with distance.
Scene contact_scene()
{
    Scene scene;
    scene.name = "contact";
    scene.description =
        "Contact hardening: a sphere (r = 1) resting on the ground and a capsule (r = 0.15) leaning "
        "on it. Penumbrae grow from zero at the contacts; blocker-search methods must follow.";
    const Sphere sphere{{0, 1, 0}, 1.0};
    const double capsule_radius = 0.15;
    const Vec3 foot{2.6, capsule_radius, 0.6};
    // The upper end touches the sphere: its centre sits at distance r_sphere + r_capsule
    // from the sphere's centre, on a ray chosen so the capsule leans away from it.
    const Vec3 top = sphere.center + normalize(Vec3{1, 0.55, 0.3}) * (sphere.radius + capsule_radius);
    scene.primitives = {ground(), sphere, Capsule{foot, top, capsule_radius}};
    scene.light = square_light({-2.5, 9, -1.5}, {1.2, 0, 0.8}, 1.5);
    scene.light_camera = perspective(0.5, 24, 80);
    scene.view = ViewCamera{{3.1, 4.0, 3.9}, {0.9, 0.2, 0.7}, {0, 1, 0}, 45};
    scene.map_size = 1024;
    // Cascades (docs/cascades.md): a sun from about the area light's side and
    // a character light from the other, low enough to cross the first.
    scene.directional_lights = {{{0.45, -1, 0.3}, {0, 0, -1}}, {{-0.8, -1, 0.25}, {0, 0, -1}}};
    return scene;
}

// Light leaking: two thin square slabs stacked at different heights, offset
// so their shadows overlap in part. Where the receiver lies under both, the
// depth distribution in a filter footprint is bimodal and moment methods leak.
Scene overlap_scene()
{
    Scene scene;
    scene.name = "overlap";
    scene.description =
        "Light leaking: two 1.6 m square slabs at heights 0.8 and 2.4 over the ground, offset so "
        "their shadows overlap; a low box near the lower slab adds a third depth layer.";
    scene.primitives = {
        ground(),
        Box{{0, 0.8, 0}, {1.6, 0.05, 1.6}, {0, 0, 0}},
        Box{{0.9, 2.4, 0.6}, {1.6, 0.05, 1.6}, {0, 15, 0}},
        Box{{-0.9, 0.2, 0.9}, {0.4, 0.4, 0.4}, {0, 30, 0}},
    };
    scene.light = square_light({-0.8, 8, -0.6}, {0.3, 0, 0.3}, 1.2);
    scene.light_camera = perspective(0.5, 14, 60);
    scene.view = ViewCamera{{2.6, 5.0, 3.2}, {0.5, 0.4, 0.5}, {0, 1, 0}, 45};
    scene.map_size = 1024;
    return scene;
}

// High-frequency occluders: a picket fence of slats 12 mm wide every 50 mm,
// lit from behind and above, so its shadow is a dense stripe pattern. At the
// 1024 map a slat covers about 2 texels: filters alias or blur it away.
Scene fence_scene()
{
    Scene scene;
    scene.name = "fence";
    scene.description =
        "High-frequency occluders: 41 pickets 12 mm wide every 50 mm (about 2 texels wide at 1024^2) "
        "and two rails, lit from behind; stripes sharp at the fence, blurred away from it.";
    scene.primitives.push_back(ground());
    const double slat_width = 0.012, spacing = 0.05;
    for (int i = -20; i <= 20; ++i)
        scene.primitives.push_back(Box{{i * spacing, 0.6, 0}, {slat_width, 1.2, 0.012}, {0, 0, 0}});
    for (double height : {0.3, 1.0})  // rails touching the pickets' backs
        scene.primitives.push_back(Box{{0, height, -0.016}, {2.1, 0.05, 0.02}, {0, 0, 0}});
    scene.light = square_light({0.4, 6, -6}, {0, 0, 1.2}, 0.6);
    scene.light_camera = perspective(1, 16, 40);
    scene.view = ViewCamera{{1.0, 3.2, 3.0}, {0, 0.3, 0.6}, {0, 1, 0}, 38};
    scene.map_size = 1024;
    return scene;
}

// Acne and bias: the light grazes the ground (about 6 degrees of elevation),
// so the ground is almost parallel to the light's rays and its depth changes
// by many texels' worth across one texel.
Scene grazing_scene()
{
    Scene scene;
    scene.name = "grazing";
    scene.description =
        "Acne and bias: a light about 6 degrees above the horizon, so the ground receiver is almost "
        "parallel to the light direction; a post, a sphere and a low wall cast long shadows.";
    scene.primitives = {
        ground(),
        Box{{-1.5, 0.5, 0.3}, {0.2, 1.0, 0.2}, {0, 0, 0}},
        Sphere{{-2.5, 0.4, -0.9}, 0.4},
        Box{{-0.5, 0.15, -1.2}, {0.1, 0.3, 1.4}, {0, 10, 0}},
    };
    scene.light = square_light({-12, 1.3, 0}, {0, 0, 0}, 0.5);
    scene.light_camera = perspective(2, 26, 50);
    scene.view = ViewCamera{{0.5, 7.5, 4}, {-0.8, 0, -0.1}, {0, 1, 0}, 40};
    scene.map_size = 1024;
    return scene;
}

// A deterministic pseudo-random value in [0, 1) per integer (no std::
// distributions: their output differs between standard libraries).
double hash_unit(int i)
{
    std::uint32_t h = std::uint32_t(i) * 2654435761u;
    h ^= h >> 16;
    h *= 2246822519u;
    h ^= h >> 13;
    return double(h) / 4294967296.0;
}

// Precision: a 200 m city block of boxes of varied heights and thin poles
// under a high sun-like light. Meant for a 16384^2 map (1.7 cm texels, the
// 0.3 m poles about 17 texels wide), where depth and texture coordinates need
// every bit of a float and summed-area tables lose theirs; at 256^2 the
// blocks are still several texels wide.
Scene large_scene()
{
    Scene scene;
    scene.name = "large";
    scene.description =
        "Precision: a 200 m block of 8 x 8 buildings (2-24 m tall) and 16 poles (r = 0.15 m) under "
        "a high light 300 m away; meant for a 16384^2 shadow map, renderable at any size.";
    scene.primitives.push_back(ground());
    const int blocks = 8;
    const double pitch = 25;
    for (int j = 0; j < blocks; ++j)
        for (int i = 0; i < blocks; ++i) {
            const int k = j * blocks + i;
            const double height = 2 + 22 * hash_unit(k);
            const double side = 8 + 8 * hash_unit(k + 1000);
            const Vec3 center{(i - (blocks - 1) / 2.0) * pitch, height / 2, (j - (blocks - 1) / 2.0) * pitch};
            scene.primitives.push_back(Box{center, {side, height, side}, {0, 40 * hash_unit(k + 2000), 0}});
        }
    for (int k = 0; k < 16; ++k) {
        const double x = (k % 4 - 1.5) * 2 * pitch + pitch / 2, z = (k / 4 - 1.5) * 2 * pitch + pitch / 2;
        scene.primitives.push_back(Capsule{{x, 0.15, z}, {x, 6, z}, 0.15});
    }
    scene.light = square_light({-60, 300, -40}, {0, 0, 0}, 8);
    scene.light_camera = perspective(10, 400, 50);
    scene.view = ViewCamera{{50, 170, 110}, {0, 0, 5}, {0, 1, 0}, 45};
    scene.map_size = 16384;
    // The city under a sun (cascaded shadow maps, docs/cascades.md).
    scene.directional_lights = {{{0.25, -1, 0.15}, {0, 0, -1}}};
    return scene;
}

struct Entry {
    const char* name;
    Scene (*make)();
    SceneSet set;
};

constexpr Entry kScenes[] = {
    {"contact", contact_scene, SceneSet::Opaque}, {"overlap", overlap_scene, SceneSet::Opaque},
    {"fence", fence_scene, SceneSet::Opaque},     {"grazing", grazing_scene, SceneSet::Opaque},
    {"large", large_scene, SceneSet::Opaque},     {"hair", hair_scene, SceneSet::Deep},
    {"fog", fog_scene, SceneSet::Deep},           {"layers", layers_scene, SceneSet::Deep},
};

}  // namespace

std::vector<std::string> builtin_scene_names(SceneSet set)
{
    std::vector<std::string> names;
    for (const Entry& entry : kScenes)
        if (set == SceneSet::All || entry.set == set) names.emplace_back(entry.name);
    return names;
}

Scene builtin_scene(std::string_view name)
{
    for (const Entry& entry : kScenes)
        if (name == entry.name) return entry.make();
    std::string valid;
    for (const Entry& entry : kScenes) valid += (valid.empty() ? "" : ", ") + std::string(entry.name);
    throw Error(ErrorCategory::InvalidArgument, "builtin_scene",
                "unknown scene \"" + std::string(name) + "\"; the built-in scenes are " + valid);
}

}  // namespace penumbra::reference
