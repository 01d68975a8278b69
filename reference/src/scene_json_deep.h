// The JSON of what deep shadows need beyond opaque primitives: media and hair
// (scene_json_deep.cpp), and the shape reader and writer they share with the
// primitives (scene_json.cpp). Private to reference/src.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "json_reader.h"
#include "penumbra/reference/scene.h"

namespace penumbra::reference {

// A primitive's shape fields ("type" and its own), with `extra` keys allowed
// beside them; the opacity stays at its default.
Primitive read_shape(const Reader& r, const json& j, const std::string& at, std::initializer_list<std::string_view> extra);
json shape_to_json(const Primitive& primitive);

// The optional top-level "media" and "hair" arrays (empty when absent).
std::vector<Medium> read_media(const Reader& r, const json& root);
std::vector<Hair> read_hair(const Reader& r, const json& root);
json media_to_json(const std::vector<Medium>& media);
json hair_to_json(const std::vector<Hair>& hair);

}  // namespace penumbra::reference
