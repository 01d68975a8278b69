// libFuzzer target: the scene JSON reader (host/src/reference_scene_json.cpp
// and the validation behind it, reference_scene_validate.cpp).
//
// Oracle: every input either gives a Scene or throws penumbra::Error; a scene
// that was accepted must also survive a write and a re-read (scene_to_json then
// scene_from_json), since `render-scene` and the demo round-trip scenes that
// way. Anything else -- a sanitizer report, a signal, another exception (a
// nlohmann::json one included) -- is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "penumbra/error.h"
#include "penumbra/reference/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        penumbra::reference::Scene scene = penumbra::reference::scene_from_json(text, "fuzz");
        penumbra::reference::scene_from_json(penumbra::reference::scene_to_json(scene), "fuzz round trip");
    } catch (const penumbra::Error&) {
        // A refused scene: the expected outcome for almost every mutated input.
    }
    return 0;
}
