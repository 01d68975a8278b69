// The I/O of `penumbra shade` done with OpenEXR alone, for cli_io_bench: the
// floor the tool's wall time is measured against (issue 10, item 10).
#pragma once

#include <string>
#include <vector>

namespace penumbra::bench {

// Float planes, one after another, each width x height with no row padding.
struct FloatPlanes {
    int width = 0, height = 0;
    std::vector<float> pixels;
};

// Reads `channels` of a scanline or tiled EXR with Imf::InputFile::readPixels,
// on OpenEXR's global thread pool as the caller sized it.
FloatPlanes read_exr_planes(const std::string& path, const std::vector<std::string>& channels);

// Writes plane 0 as float channel `channel`, ZIP-compressed, increasing Y: the
// header write_exr makes (keep in sync with float_header in host/src/exr_io.cpp).
void write_exr_plane(const std::string& path, const FloatPlanes& image, const std::string& channel);

}  // namespace penumbra::bench
