// Parts the built-in scenes share (builtin_scenes.cpp, deep_scenes.cpp).
// Private to reference/src.
#pragma once

#include "penumbra/reference/scene.h"

namespace penumbra::reference {

inline Plane ground() { return Plane{{0, 0, 0}, {0, 1, 0}}; }

// Aims the light (and so its camera) from `center` at `target`.
inline AreaLight square_light(Vec3 center, Vec3 target, double side)
{
    AreaLight light;
    light.shape = LightShape::Rectangle;
    light.center = center;
    light.normal = normalize(target - center);
    light.up = {0, 1, 0};  // u across, v down the map, as in a photo taken from the light
    light.width = light.height = side;
    return light;
}

inline LightCamera perspective(double near, double far, double fov_degrees)
{
    LightCamera camera;
    camera.projection = Projection::Perspective;
    camera.near = near;
    camera.far = far;
    camera.fov_degrees = fov_degrees;
    return camera;
}

// A point light (a spot: the light camera's frustum is its cone) at `center`
// aimed at `target`.
inline AreaLight point_light(Vec3 center, Vec3 target)
{
    AreaLight light = square_light(center, target, 0);
    light.shape = LightShape::Point;
    return light;
}

// The deep-shadow scenes (deep_scenes.cpp).
Scene hair_scene();
Scene fog_scene();
Scene layers_scene();

}  // namespace penumbra::reference
