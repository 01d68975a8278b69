// Checks an EXR file before OpenEXR's C++ reader allocates or decodes anything,
// and decodes its pixels with the core API, checking every chunk on the way
// (docs/robustness.md, "EXR inputs"); used by read_exr (exr_io.cpp).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "penumbra/exr_io.h"
#include "penumbra/image.h"
#include "penumbra/input_file.h"

namespace penumbra::detail {

// Throws Error(Io) naming the file unless, for the first part of `file`:
//  - the data window holds at most limits.max_pixels pixels;
//  - its decoded size (every channel of the file, not only those asked for) is
//    at most the file's size times the largest expansion its compression can
//    reach (exr_max_expansion), so that a small
//    file cannot claim a huge image;
//  - every chunk (scanline block, or tile of level 0) is present in the offset
//    table, and decompresses without error to exactly the size its header
//    implies, so that no pixel is computed from memory the file never filled.
//    (Skip: only the header's claims, for callers that read no pixels.)
//    DWAA and DWAB chunks are checked to be present only: OpenEXR 3.1's core
//    library cannot decode them, so their completeness rests on its C++ reader.
enum class ChunkCheck { DecodeEvery, Skip };
void validate_exr(const InputFile& file, const ExrReadLimits& limits, std::string_view operation,
                  ChunkCheck chunks);

// Decodes `channels` of every chunk of `file` into `image` (already sized to the
// data window; plane i receives channels[i], converted to float), each chunk
// decompressed once, chunks in parallel: the read and the completeness check of
// validate_exr in one pass. A missing chunk or one that decodes short is
// Error(Io). Returns false, having written nothing, when the core library
// cannot decode the file's compression (DWAA, DWAB): the caller then reads
// with OpenEXR's C++ library after validate_exr.
bool decode_exr(const InputFile& file, const std::vector<std::string>& channels, Image& image,
                std::string_view operation);

// Throws Error(Io) naming the file unless its header walks as OpenEXR 3.1's C++
// reader walks it: no attribute claims more bytes than follow it or a size its
// type does not take, none is named twice (exr_validate.cpp says why).
void check_attribute_sizes(const InputFile& file, std::string_view operation);

// Throws Error(Io) naming the file unless OpenEXR's C++ reader reads the first
// part's header as the core library did: storage (tiled or not), data window,
// compression, channels and tiles, the fields its buffers are sized by. Every
// size check is made on the core's reading, so a file the two read
// differently (a damaged attribute one skips) is refused
// (exr_readers_agree.cpp says why).
class CoreContext;
void require_readers_agree(const CoreContext& core, std::string_view operation);

// Decoded bytes per stored byte, at most, for an OpenEXR compression code
// (exr_compression_t); the figures, their sources and the one stated policy
// (DWA) are in exr_validate.cpp.
double exr_max_expansion(int compression);

}  // namespace penumbra::detail
