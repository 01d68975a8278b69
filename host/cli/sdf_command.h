// penumbra sdf-shade and sdf-bake (host/cli/sdf_command.cpp): SDF soft
// shadows from a scene or a distance-grid file, and grid files from scenes.
#pragma once

#include <string>
#include <vector>

namespace penumbra::cli {

int sdf_shade_command(const std::vector<std::string>& args);
int sdf_bake_command(const std::vector<std::string>& args);

}  // namespace penumbra::cli
