// The ambient readers that scene_json.cpp shares with ambient_json.cpp (a
// scene's optional "ambient" field); private to reference/src.
#pragma once

#include <string>
#include <vector>

#include "json_reader.h"
#include "penumbra/ambient.h"
#include "penumbra/reference/ambient_json.h"

namespace penumbra::reference {

// {"lights": [...]} at `at`.
AmbientRig read_rig(const Reader& r, const json& j, const std::string& at);
// An array of volumes at `path`.
std::vector<AmbientVolume> read_volumes(const Reader& r, const json& volumes, const std::string& path);
// A scene's "ambient": {"rig": RIG, "dark_rig": RIG (optional), "volumes": [...] (optional)}.
SceneAmbient read_scene_ambient(const Reader& r, const json& j, const std::string& at);
json scene_ambient_to_json(const SceneAmbient& ambient);

}  // namespace penumbra::reference
