// Ambient rigs and volumes as JSON (docs/ambient.md has the formats): the
// files `penumbra ambient` reads, and a scene's optional "ambient" field.
// Reading names the field of every complaint ("rig.json: lights[2].direction:
// must be an array of 3 numbers"); unknown keys are refused. Values are
// checked by the library when the rig is projected or the volumes packed
// (penumbra/ambient.h), which name lights[i] and volumes[i] too.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/ambient.h"

namespace penumbra::reference {

// A scene's ambient lighting: a light rig, optionally a dark rig and the
// volumes that blend towards it.
struct SceneAmbient {
    AmbientRig rig;
    std::optional<AmbientRig> dark_rig;
    std::vector<AmbientVolume> volumes;
};

// Error(Io) for a file that cannot be read or is not JSON; Error(InvalidArgument)
// naming the field otherwise.
AmbientRig rig_from_json(std::string_view text, std::string_view source_name = "<string>");
AmbientRig load_rig(const std::filesystem::path& path);
std::vector<AmbientVolume> volumes_from_json(std::string_view text, std::string_view source_name = "<string>");
std::vector<AmbientVolume> load_volumes(const std::filesystem::path& path);

}  // namespace penumbra::reference
