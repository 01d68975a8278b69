// libFuzzer target: the ambient rig and volume JSON readers
// (reference/src/ambient_json.cpp), the files `penumbra ambient` reads.
//
// Oracle: every input, read as a rig and as a volume list, either gives one
// or throws penumbra::Error. Anything else -- a sanitizer report, a signal,
// another exception (a nlohmann::json one included) -- is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "penumbra/error.h"
#include "penumbra/reference/ambient_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        (void)penumbra::reference::rig_from_json(text, "fuzz");
    } catch (const penumbra::Error&) {
    }
    try {
        (void)penumbra::reference::volumes_from_json(text, "fuzz");
    } catch (const penumbra::Error&) {
    }
    return 0;
}
