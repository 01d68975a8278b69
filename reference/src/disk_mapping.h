// The area-preserving map of the unit square onto the unit disk, shared by
// the light samples (light_sampling.cpp) and the cosine-weighted AO rays
// (obscurance_truth.cpp). Private to reference/src.
#pragma once

#include <cmath>
#include <numbers>

#include "penumbra/reference/geometry.h"

namespace penumbra::reference {

// Shirley and Chiu 1997: squares around the centre of [-1, 1]^2 go to circles,
// preserving area, so equal strata of the square are equal areas of the disk.
inline Vec3 concentric_disk(double a, double b)
{
    const double x = 2 * a - 1, y = 2 * b - 1;
    if (x == 0 && y == 0) return {};
    constexpr double quarter_pi = std::numbers::pi / 4;
    if (std::fabs(x) > std::fabs(y)) {
        const double phi = quarter_pi * (y / x);
        return {x * std::cos(phi), x * std::sin(phi), 0};
    }
    const double phi = 2 * quarter_pi - quarter_pi * (x / y);
    return {y * std::cos(phi), y * std::sin(phi), 0};
}

}  // namespace penumbra::reference
