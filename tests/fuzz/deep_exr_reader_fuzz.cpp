// libFuzzer target: the deep shadow map reader (host/src/deep_exr_read.cpp,
// deep_exr_samples.cpp), docs/deep_shadow_maps.md "Bad input", and on the
// same bytes the layered depth map reader that shares its checks
// (host/src/layered_exr.cpp, Pismo's map files, with their surface ids).
//
// Oracle: every input either reads, into a map whose invariants hold, or
// throws penumbra::Error. Anything else is a finding: a sanitizer report, a
// signal, another exception escaping (Iex or std::bad_alloc included), or an
// allocation above libFuzzer's -malloc_limit_mb.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "fuzz_input_file.h"
#include "penumbra/deep_exr.h"
#include "penumbra/error.h"
#include "penumbra/layered_exr.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string& path = penumbra::fuzz::input_as_file(data, size, ".exr");
    try {
        const penumbra::DeepShadowMap map = penumbra::read_deep_exr(path);
        // The reader promises a valid map: every pixel's function evaluates.
        for (int y = 0; y < map.height(); ++y)
            for (int x = 0; x < map.width(); ++x) {
                const float v = map.visibility(x, y, 1e30f);
                if (!(v >= 0.0f && v <= 1.0f)) std::abort();
            }
    } catch (const penumbra::Error&) {
        // A refused file: the expected outcome for almost every mutated input.
    }
    try {
        // An accepted layered map holds its invariants (its constructor checked
        // them); every pixel's layers are in range of the depth array; its
        // surface ids, when the file has them, are one a layer and >= 0.
        std::vector<std::int32_t> ids;
        const penumbra::LayeredDepthMap map = penumbra::read_layered_exr(path, {}, &ids);
        std::size_t layers = 0;
        for (int y = 0; y < map.height(); ++y)
            for (int x = 0; x < map.width(); ++x) layers += map.layers(x, y).size();
        if (layers != map.depths().size()) std::abort();
        if (!ids.empty() && ids.size() != layers) std::abort();
        for (std::int32_t id : ids)
            if (id < 0) std::abort();
    } catch (const penumbra::Error&) {
        // Refused, as almost every mutated input is.
    }
    return 0;
}
