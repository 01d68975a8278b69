// The contact band of the `contact` scene, for the figures that measure what
// happens where solids touch (soft_shadow_figures' contact hardening,
// pcf_failure_figures' peter-panning): the receivers within a few shadow-map
// texels of a contact point.
#pragma once

#include <vector>

#include "penumbra/reference.h"

namespace penumbra::bench {

namespace ref = penumbra::reference;

// World points where the scene's solids touch (builtin_scenes.cpp, contact_scene).
inline std::vector<ref::Vec3> contact_points()
{
    const ref::Vec3 sphere{0, 1, 0};
    const ref::Vec3 top = sphere + ref::normalize(ref::Vec3{1, 0.55, 0.3}) * 1.15;
    return {{0, 0, 0}, {2.6, 0, 0.6}, sphere + (top - sphere) * (1.0 / 1.15)};
}

// 1 for the valid receivers within `texels` map texels (the texel's world size
// at the contact's light depth) of a contact point.
inline Image contact_band(const ref::Scene& scene, const ref::Receivers& rx, int map_size, double texels)
{
    const ref::LightProjection projection(scene);
    Image band(rx.width(), rx.height(), 1);
    for (const ref::Vec3& c : contact_points()) {
        const double depth = projection.depth_of(projection.project(c).z);
        const double radius = texels * projection.texture_unit_length(depth) / map_size;
        for (int y = 0; y < rx.height(); ++y)
            for (int x = 0; x < rx.width(); ++x) {
                const ref::Vec3 p{rx.world_position.at(0, x, y), rx.world_position.at(1, x, y),
                                  rx.world_position.at(2, x, y)};
                if (rx.mask.at(0, x, y) > 0.5f && ref::length(p - c) <= radius) band.at(0, x, y) = 1;
            }
    }
    return band;
}

}  // namespace penumbra::bench
