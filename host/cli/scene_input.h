// Resolves a scene argument: a built-in name (`penumbra render-scene contact`)
// or a JSON scene file (anything ending in .json, or an existing path).
#pragma once

#include <filesystem>
#include <string>

#include "penumbra/reference_scene.h"

namespace penumbra::cli {

inline reference::Scene resolve_scene(const std::string& name_or_path)
{
    const std::filesystem::path path(name_or_path);
    if (path.extension() == ".json" || std::filesystem::exists(path)) return reference::load_scene(path);
    return reference::builtin_scene(name_or_path);
}

}  // namespace penumbra::cli
