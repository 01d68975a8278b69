// The demo's pictures. Visibility in grey, signed error (estimate minus
// truth) in colormap_error's white-centred map (blue: too dark, red: too
// bright, saturating at kDemoErrorScale), and in both the receivers that face
// away from the light in one colour neither map uses (green): they get no
// direct light in any renderer and are not scored, and black there would
// read as shadow.
#pragma once

#include <string>

#include "penumbra/image.h"

namespace penumbra::cli {

constexpr float kDemoErrorScale = 0.5f;
inline constexpr const char* kDemoBackFaceColour = "#2e8b57";  // the same green, for the report's key

// `valid`: the receivers' mask (a surface there); `scored`: valid and facing the light.
void write_visibility_png(const std::string& path, const Image& visibility, const Image& valid, const Image& scored);
void write_error_png(const std::string& path, const Image& estimate, const Image& truth, const Image& valid,
                     const Image& scored);
// The error colours from -kDemoErrorScale (left) to +kDemoErrorScale (right).
void write_error_scale_png(const std::string& path);

}  // namespace penumbra::cli
