// libFuzzer target: the SDF grid reader (host/src/sdf_grid.cpp; format in
// docs/sdf.md, "Grid files").
//
// Oracle: every input either gives a DistanceGrid or throws penumbra::Error.
// An accepted grid is sampled at its corners and centre through
// DistanceGrid::at, the accessor issue 11's defect 2 crashed in, so a grid
// whose claimed size does not match its storage is caught by ASan here.
// Anything else -- a sanitizer report, a signal, another exception, an
// allocation above -malloc_limit_mb -- is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input_file.h"
#include "penumbra/error.h"
#include "penumbra/sdf.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string& path = penumbra::fuzz::input_as_file(data, size, ".pnsdf");
    try {
        penumbra::DistanceGrid grid = penumbra::read_distance_grid(path);
        volatile float sink = 0.0f;
        for (int z : {0, grid.nz() / 2, grid.nz() - 1})
            for (int y : {0, grid.ny() / 2, grid.ny() - 1})
                for (int x : {0, grid.nx() / 2, grid.nx() - 1}) sink = sink + grid.at(x, y, z);
    } catch (const penumbra::Error&) {
        // A refused file: the expected outcome for almost every mutated input.
    }
    return 0;
}
