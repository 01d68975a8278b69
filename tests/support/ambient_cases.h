// Rigs and receivers shared by the ambient tests and bench/ambient_error_table.cpp:
// the four rigs of the error table, a dense sphere of normals, and the
// float64 volume factor written from docs/ambient.md's formulas (independent
// of the kernel's text).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "penumbra/ambient.h"
#include "penumbra/image.h"

namespace penumbra::testing {

struct NamedRig {
    std::string name;
    AmbientRig rig;
};

inline AmbientLight white(AmbientVector d, double intensity) { return {d, {1, 1, 1}, intensity}; }

// One light along +Y; the six-axis rig (Toy Story 3's basic rig); the same
// with a negative light from below (the notes' "negative light"); a strong
// sun over a weak six-axis fill. Intensities are relative to the strongest
// light, the unit of the error table.
inline std::vector<NamedRig> error_table_rigs()
{
    const AmbientRig one{{white({0, 1, 0}, 1.0)}};
    const AmbientRig six{{{{1, 0, 0}, {1.0, 0.9, 0.8}, 0.6}, white({-1, 0, 0}, 0.4), {{0, 1, 0}, {0.7, 0.8, 1.0}, 1.0},
                          white({0, -1, 0}, 0.3), white({0, 0, 1}, 0.5), white({0, 0, -1}, 0.5)}};
    const AmbientRig negative{{white({1, 0, 0}, 0.5), white({-1, 0, 0}, 0.5), white({0, 1, 0}, 1.0),
                               white({0, -1, 0}, -0.4), white({0, 0, 1}, 0.5), white({0, 0, -1}, 0.5)}};
    const AmbientRig sun{{{{0.3, 1.0, 0.2}, {1.0, 0.95, 0.8}, 1.0}, white({1, 0, 0}, 0.025), white({-1, 0, 0}, 0.025),
                          white({0, 1, 0}, 0.0375), white({0, -1, 0}, 0.0125), white({0, 0, 1}, 0.025),
                          white({0, 0, -1}, 0.025)}};
    return {{"one light", one}, {"six-axis", six}, {"negative light", negative}, {"strong sun", sun}};
}

// `count` unit normals spread evenly over the sphere (a Fibonacci lattice:
// equal areas), as a width x ceil(count / width) image; the padding repeats +Z.
inline Image sphere_of_normals(int count, int width)
{
    const int height = (count + width - 1) / width;
    Image n(width, height, 3);
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < width * height; ++i) {
        const double z = i < count ? 1.0 - 2.0 * (i + 0.5) / count : 1.0;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = golden * i;
        n.at(0, i % width, i / width) = float(r * std::cos(phi));
        n.at(1, i % width, i / width) = float(r * std::sin(phi));
        n.at(2, i % width, i / width) = float(z);
    }
    return n;
}

inline AmbientVector normal_at(const Image& n, int x, int y) { return {n.at(0, x, y), n.at(1, x, y), n.at(2, x, y)}; }

// The volume's factor in float64: q = R^T (p - c) / (half size x bias); a
// box maps q onto the sphere (Nowell's cube-to-sphere map) inside the cube;
// f = clamp((1 - |q|) / (1 - delay), 0, 1); volumes combine by max.
inline double expected_factor(const AmbientVolume& v, AmbientVector p)
{
    const double o[3] = {p.x - v.center.x, p.y - v.center.y, p.z - v.center.z};
    const AmbientVector axes[3] = {v.axis_x, v.axis_y, v.axis_z};
    const double h[3] = {v.half_size.x, v.half_size.y, v.half_size.z};
    double q[3];
    for (int k = 0; k < 3; ++k) q[k] = (axes[k].x * o[0] + axes[k].y * o[1] + axes[k].z * o[2]) / (h[k] * v.scale_bias);
    double d = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    if (v.shape == AmbientVolume::Shape::Box) {
        if (std::abs(q[0]) > 1 || std::abs(q[1]) > 1 || std::abs(q[2]) > 1) return 0.0;
        double s2 = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double a = q[(k + 1) % 3] * q[(k + 1) % 3], b = q[(k + 2) % 3] * q[(k + 2) % 3];
            s2 += q[k] * q[k] * (1.0 - a / 2.0 - b / 2.0 + a * b / 3.0);
        }
        d = std::sqrt(s2);
    }
    return std::clamp((1.0 - d) / (1.0 - v.falloff_delay), 0.0, 1.0);
}

inline double expected_factor(const std::vector<AmbientVolume>& volumes, AmbientVector p)
{
    double f = 0.0;
    for (const AmbientVolume& v : volumes) f = std::max(f, expected_factor(v, p));
    return f;
}

}  // namespace penumbra::testing
