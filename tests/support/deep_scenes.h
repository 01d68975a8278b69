// Small scenes with closed-form deep shadow maps: an orthographic light 5 m
// above the ground looking straight down (near 1, far 6, an 8 m square), so
// every light ray is vertical with unit direction, a world point at height y
// has depth d = 5 - y and z = (d - 1) / 5, and u = 1/2 + x / 8 (one pixel of
// an 8 x 8 map is one metre). Written as JSON, as a user's scene would be.
// Also the comparison of two maps that the deep-map tests share.
#pragma once

#include <string>

#include "penumbra/deep_shadow_map.h"
#include "penumbra/reference/scene.h"

namespace penumbra::testing {

inline constexpr double kOverheadNear = 1, kOverheadFar = 6, kOverheadHeight = 5;

// z of a world height under the overhead light.
inline double overhead_z(double height) { return (kOverheadHeight - height - kOverheadNear) / (kOverheadFar - kOverheadNear); }

// The depth d of a z under the overhead light.
inline double overhead_depth(double z) { return kOverheadNear + z * (kOverheadFar - kOverheadNear); }

// The scene's JSON around `primitives` and `media` (JSON array bodies);
// a ground plane comes first.
inline std::string overhead_json(const std::string& primitives, const std::string& media = "")
{
    return R"({"name": "overhead",
  "light": {"shape": "rectangle", "center": [0, 5, 0], "normal": [0, -1, 0], "size": [1, 1]},
  "light_camera": {"projection": "orthographic", "near": 1, "far": 6, "extent": 8},
  "view": {"position": [3, 4, 4], "target": [0, 0, 0], "fov_degrees": 45},
  "primitives": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]})" +
           (primitives.empty() ? "" : ", " + primitives) + "]" + (media.empty() ? "" : ", \"media\": [" + media + "]") +
           "}";
}

// A 2 cm sheet of `opacity` whose top face is at height y, covering x < x_max
// (and the whole frustum otherwise).
inline std::string sheet_json(double top, double opacity, double x_max = 20)
{
    const double x_min = -20;
    return R"({"type": "box", "center": [)" + std::to_string((x_min + x_max) / 2) + ", " + std::to_string(top - 0.01) +
           R"(, 0], "size": [)" + std::to_string(x_max - x_min) + R"(, 0.02, 40], "opacity": )" +
           std::to_string(opacity) + "}";
}

inline reference::Scene overhead_scene(const std::string& primitives, const std::string& media = "")
{
    return reference::scene_from_json(overhead_json(primitives, media), "overhead");
}

// Bit for bit: the size, every offset, depth and transmittance.
inline bool same_deep_map(const DeepShadowMap& a, const DeepShadowMap& b)
{
    return a.width() == b.width() && a.height() == b.height() && a.offsets() == b.offsets() &&
           a.depths() == b.depths() && a.transmittances() == b.transmittances();
}

}  // namespace penumbra::testing
