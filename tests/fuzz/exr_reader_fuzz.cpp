// libFuzzer target: the EXR reader (host/src/exr_io.cpp, image.cpp).
//
// Oracle: every input either reads or throws penumbra::Error. Anything else is a
// finding: a sanitizer report, a signal, another exception escaping (an Iex or
// std::bad_alloc one included: exr_io.h promises none escapes), or an allocation
// above libFuzzer's -malloc_limit_mb (a tiny file must not claim gigabytes).
// Pixels left unread (issue 11, defect 10) are invisible to ASan: the
// regression tests in tests/ check those.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_input_file.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string& path = penumbra::fuzz::input_as_file(data, size, ".exr");
    try {
        std::vector<std::string> channels = penumbra::exr_channel_names(path);
        // Read at most four channels: enough for every layout penumbra writes
        // (Z; u, v, z; four moments) while bounding the work per input.
        if (channels.size() > 4) channels.resize(4);
        if (channels.empty()) return 0;
        penumbra::Image image = penumbra::read_exr(path, channels);
        (void)image;
    } catch (const penumbra::Error&) {
        // A refused file: the expected outcome for almost every mutated input.
    }
    return 0;
}
