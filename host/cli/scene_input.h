// Resolves a scene argument: a built-in name (`penumbra render-scene contact`)
// or a JSON scene file (anything ending in .json, or an existing path).
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

#include "penumbra/reference/scene.h"

namespace penumbra::cli {

// Anything that is not a built-in name is read as a file, so that a symbolic-link
// loop or an over-long name gets load_scene's one-line error naming the path.
inline reference::Scene resolve_scene(const std::string& name_or_path)
{
    const std::filesystem::path path(name_or_path);
    std::error_code error;
    const bool exists = std::filesystem::exists(std::filesystem::symlink_status(path, error));
    if (path.extension() == ".json" || exists || (error && error != std::errc::no_such_file_or_directory))
        return reference::load_scene(path);
    return reference::builtin_scene(name_or_path);
}

}  // namespace penumbra::cli
