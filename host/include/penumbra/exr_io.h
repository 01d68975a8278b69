// OpenEXR files to and from planar Images.
//
// EXR is the library's interchange format for shadow maps, receivers, ground
// truth and filtered results: lossless, float, any number of named channels.
// Only the pixels inside a file's data window are read; the display window and
// all other attributes are ignored. The image returned by read_exr has the data
// window's size, and its pixel (0, 0) is the data window's top-left corner, even
// when that corner is not at the origin.
//
// Every failure throws penumbra::Error: a file that is missing, unreadable, not
// EXR, truncated, lacks a channel or holds no pixels is ErrorCategory::Io (the
// message names the file and, where it matters, the channel); a mistake in the
// arguments themselves (no channels named, a name twice, a channel count that does
// not match the image) is ErrorCategory::InvalidArgument. No OpenEXR (Iex)
// exception escapes.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/output_files.h"

namespace penumbra {

// Limits read_exr applies before it allocates anything (docs/robustness.md).
// The default admits a 16384^2 plane, the largest map penumbra itself writes
// (1 GiB per float channel); larger files need a larger limit, on purpose.
struct ExrReadLimits {
    std::uint64_t max_pixels = std::uint64_t(1) << 28;  // width x height of the data window
};

// Names of the channels of an EXR file, in the file's (alphabetical) order.
// The header's claims are checked against `limits` as for read_exr.
std::vector<std::string> exr_channel_names(const std::string& path, const ExrReadLimits& limits = {});

// Reads `channels`, in that order, into the planes of a new Image (plane i holds
// channels[i]). The file may store a channel as FLOAT, HALF or UINT: OpenEXR
// converts HALF and UINT to float while reading (UINT values above 2^24 lose
// precision). Channels stored at reduced resolution (x/y sampling other than 1)
// are refused rather than silently upsampled. Scanline and tiled single-part
// files are read; of a multi-part file only the first part is.
//
// Before allocating, the data window is checked against limits.max_pixels and
// against what the file's size can hold in its compression; every chunk is
// checked to be present and to decompress in full (a header that claims more
// than the file holds is refused, never read from uninitialised memory). The
// path must name a regular file (a FIFO or device is refused without blocking).
Image read_exr(const std::string& path, const std::vector<std::string>& channels, const ExrReadLimits& limits = {});

// Writes plane i of `image` as 32-bit FLOAT channel channels[i], data window and
// display window both (0, 0)..(width-1, height-1). ZIP compression: it is
// lossless, so a write followed by a read is bit-exact, it is the compression
// every EXR reader supports, and depth and moment maps shrink well under it.
//
// The write is atomic: pixels go to a temporary file in the target's directory,
// which replaces the target only once it is complete. A failed write leaves no
// partial file behind and an existing target as it was.
void write_exr(const std::string& path, const Image& image, const std::vector<std::string>& channels);

// As write_exr, into `output`, which publishes it with its other files at once.
void stage_exr(OutputFiles& output, const std::string& path, const Image& image,
               const std::vector<std::string>& channels);

namespace detail {

// Shared by write_exr and write_png (png_io.cpp); an implementation detail, not
// API. An OutputFiles of one file (penumbra/output_files.h): `write_temporary`
// gets a name that opens an unnamed temporary beside `path`, which replaces
// `path` once flushed. If anything throws, nothing is left behind and an Error
// (Io, naming `operation` and `path`) or the writer's own exception propagates.
void write_file_atomically(const std::string& path, std::string_view operation,
                           const std::function<void(const std::string& temporary_path)>& write_temporary);

}  // namespace detail

}  // namespace penumbra
