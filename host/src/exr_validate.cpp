// EXR plausibility and completeness checks (exr_validate.h), on the OpenEXR
// core (C) API, which reads a chunk's table entry and decompresses it without
// touching a frame buffer: the C++ InputFile of OpenEXR 3.1 zero-pads a chunk
// that decompresses short and hands the caller whatever its buffer held.
#include "exr_validate.h"
#include "exr_core.h"
#include "exr_zip_inflate.h"

#include <OpenEXR/openexr.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <set>
#include <string>

#include "penumbra/error.h"
#include "quoted.h"

namespace penumbra::detail {
namespace {

// A name read from a damaged header, fit for a one-line message.
std::string printable(std::string text)
{
    for (char& c : text)
        if (c < 0x20 || c > 0x7e) c = '?';
    return text;
}

std::uint64_t bytes_per_pixel(const CoreContext& core)
{
    const exr_attr_chlist_t* channels = nullptr;
    core.check(exr_get_channels(core.get(), 0, &channels), "its channel list cannot be read");
    std::uint64_t bytes = 0;
    for (int c = 0; c < channels->num_channels; ++c)
        bytes += channels->entries[c].pixel_type == EXR_PIXEL_HALF ? 2 : 4;
    return bytes;
}

// Reads and decompresses one chunk, unpacking the channels `destination` gives
// a pointer for; the core library fails when the data decompresses to any size
// but the one the chunk's pixels need.
template <class Destination>
exr_result_t decode_chunk(const CoreContext& core, const exr_chunk_info_t& chunk, Destination&& destination)
{
    exr_decode_pipeline_t decode{};  // all zero, as EXR_DECODE_PIPELINE_INITIALIZER
    exr_result_t result = exr_decoding_initialize(core.get(), 0, &chunk, &decode);
    if (result == EXR_ERR_SUCCESS) {
        for (int c = 0; c < decode.channel_count; ++c) destination(decode.channels[c]);
        result = exr_decoding_choose_default_routines(core.get(), 0, &decode);
    }
    exr_compression_t compression{};
    if (result == EXR_ERR_SUCCESS) result = exr_get_compression(core.get(), 0, &compression);
    if (result == EXR_ERR_SUCCESS) inflate_zip_with_libdeflate(decode, compression);
    if (result == EXR_ERR_SUCCESS) result = exr_decoding_run(core.get(), 0, &decode);
    exr_decoding_destroy(core.get(), &decode);
    return result;
}

struct Layout {
    exr_storage_t storage{};
    exr_attr_box2i_t window{};
    exr_compression_t compression{};
};

Layout layout_of(const CoreContext& core, const InputFile& file, std::string_view operation)
{
    Layout l;
    core.check(exr_get_storage(core.get(), 0, &l.storage), "its storage type cannot be read");
    core.check(exr_get_data_window(core.get(), 0, &l.window), "its data window cannot be read");
    core.check(exr_get_compression(core.get(), 0, &l.compression), "its compression cannot be read");
    if (l.storage != EXR_STORAGE_SCANLINE && l.storage != EXR_STORAGE_TILED)
        throw Error(ErrorCategory::Io, operation,
                    in_quotes(file.path()) + " holds deep data; only flat scanline or tiled images can be read");
    return l;
}

// OpenEXR 3.1's core library has no DWA decoder.
bool core_decodes(exr_compression_t compression)
{
    return compression != EXR_COMPRESSION_DWAA && compression != EXR_COMPRESSION_DWAB;
}

}  // namespace

// Decoded bytes per stored byte, at most. NONE stores pixels as they are. RLE
// (OpenEXR's ImfRle: a signed count byte and a value byte for a run of at most
// 127 bytes) reaches 63.5. ZIP and ZIPS are zlib's deflate, whose maximum is
// 1032 (zlib's "technical details": 258-byte matches coded in 2 bits, plus
// framing). PXR24 stores 32-bit floats as 24 bits before deflate: 1032 * 4 / 3
// = 1376. B44/B44A code a 4x4 block of halves (32 bytes) in 14 bytes, or 3
// when flat, and store other channels as they are: 32 / 3 < 11, so 64. PIZ
// (wavelet, then Huffman with run codes of at most 255 values in a code of at
// least 9 bits) stays below 16 * 255 / 9 < 512: 4096. DWAA/DWAB nest RLE,
// Huffman and deflate and have no small bound; 65536 is a stated policy, far
// above what real content reaches (a constant 8192^2 float image: about 5000),
// so that a small file cannot make OpenEXR's decoders size gigabytes. Every
// chunk is still decoded and checked in full.
double exr_max_expansion(int compression)
{
    switch (compression) {
    case EXR_COMPRESSION_NONE: return 1.0;
    case EXR_COMPRESSION_RLE: return 63.5;
    case EXR_COMPRESSION_ZIPS:
    case EXR_COMPRESSION_ZIP: return 1032.0;
    case EXR_COMPRESSION_PXR24: return 1376.0;
    case EXR_COMPRESSION_B44:
    case EXR_COMPRESSION_B44A: return 64.0;
    case EXR_COMPRESSION_PIZ: return 4096.0;
    default: return 65536.0;  // DWAA, DWAB, and codes OpenEXR 3.1 does not know
    }
}

// The value size OpenEXR 3.1's C++ reader consumes for an attribute of a fixed-
// size type whatever size the file declares (Imf*Attribute::readValueFrom), or
// 0 for types whose reader honours the declared size (string, stringvector,
// floatvector, unknown types) or walks the content (chlist, preview).
std::int64_t fixed_value_size(const std::string& type)
{
    static const std::pair<const char*, std::int64_t> sizes[] = {
        {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"double", 8},
        {"envmap", 1}, {"float", 4}, {"int", 4}, {"keycode", 28}, {"lineOrder", 1}, {"m33f", 36},
        {"m33d", 72}, {"m44f", 64}, {"m44d", 128}, {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},
        {"v2i", 8}, {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12}, {"v3d", 24}, {"deepImageState", 1}};
    for (const auto& [name, size] : sizes)
        if (type == name) return size;
    return 0;
}

// The header is a list of attributes (name, type name, a little-endian int32
// size, then the value), closed by an empty name; a multi-part file has one such
// list per part and an empty list after the last (the OpenEXR file layout,
// "Header"). OpenEXR 3.1's C++ reader allocates a value at the size the file
// claims before reading it (1.6 GB from a 469-byte file, found by
// tests/fuzz/exr_reader_fuzz), sizes a preview image by its own width and
// height, and reads fixed-size types and channel lists by their content, not by
// the declared size. So the walk below reads the header as that reader does and
// refuses any value that claims more bytes than follow it, or whose declared
// size is not what the reader will consume (no genuine file has either). It
// also refuses an attribute named twice in one part: the C++ reader lets the
// later value win, and validate_exr checks the core library's reading, so a
// second dataWindow made the two disagree (a 7x3 window checked, a 3604489x3
// one allocated: 1.6 GB of DWA line buffers from 2 KB, exr_reader_fuzz).
void check_attribute_sizes(const InputFile& file, std::string_view operation)
{
    std::uint8_t version[4] = {};
    if (!file.read_at(4, version, sizeof version))
        throw Error(ErrorCategory::Io, operation, in_quotes(file.path()) + " is truncated inside its header");
    const bool multipart = (version[1] & 0x10) != 0;  // bit 12 of the version field
    const std::size_t max_name = (version[1] & 0x04) ? 255 : 31;  // bit 10: long names
    const auto corrupt = [&](const std::string& what) {
        throw Error(ErrorCategory::Io, operation,
                    in_quotes(file.path()) + " is corrupt or truncated: " + what + "; re-create the file");
    };
    const auto left = [&](std::uint64_t at) { return file.size() - std::min(at, file.size()); };
    // A name as Imf's Xdr::read reads it: up to max_name + 1 bytes, stopping after a null.
    const auto read_name = [&](std::uint64_t& at) {
        char buffer[256] = {};
        const std::size_t count = std::size_t(std::min<std::uint64_t>(max_name + 1, left(at)));
        if (count == 0 || !file.read_at(at, buffer, count)) corrupt("its header ends early");
        const std::size_t length = std::string_view(buffer, count).find('\0');
        if (length == std::string_view::npos) corrupt("a header name is longer than " + std::to_string(max_name) + " characters");
        at += length + 1;
        return std::string(buffer, length);
    };
    const auto read_int = [&](std::uint64_t at) {
        std::uint8_t b[4] = {};
        if (!file.read_at(at, b, sizeof b)) corrupt("its header ends early");
        return std::int64_t(std::int32_t(std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
                                         std::uint32_t(b[3]) << 24));
    };
    // The bytes a channel list's reader consumes: names with 16 bytes each, then an empty name.
    const auto chlist_bytes = [&](std::uint64_t at) {
        const std::uint64_t start = at;
        for (int c = 0; c <= (1 << 16) && !read_name(at).empty(); ++c) at += 16;
        return std::int64_t(at - start);
    };
    constexpr int kMaxParts = 1 << 16, kMaxAttributes = 1 << 16;
    std::uint64_t at = 8;
    for (int part = 0; part < kMaxParts; ++part) {
        int attributes = 0;
        std::set<std::string> names;
        for (std::string name = read_name(at); !name.empty(); name = read_name(at)) {
            if (++attributes > kMaxAttributes) corrupt("its header has more than 65536 attributes");
            if (!names.insert(name).second) corrupt("its header names the attribute '" + printable(name) + "' twice");
            const std::string type = read_name(at);
            const std::int64_t size = read_int(at);
            at += 4;
            const std::string what = "its header attribute '" + printable(name) + "' (" + printable(type) + ")";
            if (size < 0 || std::uint64_t(size) > left(at))
                corrupt(what + " claims " + std::to_string(size) + " bytes, more than the " + std::to_string(left(at)) +
                        " that follow it");
            std::int64_t consumed = fixed_value_size(type);
            if (type == "chlist") consumed = chlist_bytes(at);
            if (type == "preview") {  // unsigned width and height, then 4 bytes per pixel
                const auto w = std::uint64_t(std::uint32_t(read_int(at))), h = std::uint64_t(std::uint32_t(read_int(at + 4)));
                consumed = (w >> 20 || h >> 20) ? -1 : std::int64_t(8 + 4 * w * h);
            }
            if (consumed != 0 && consumed != size)
                corrupt(what + " declares " + std::to_string(size) + " bytes but its value takes " + std::to_string(consumed));
            at += std::uint64_t(size);
        }
        if (!multipart || attributes == 0) return;  // a single part, or the empty list after the last part
    }
    corrupt("it claims more than 65536 parts");
}

void validate_exr(const InputFile& file, const ExrReadLimits& limits, std::string_view operation, ChunkCheck chunks)
{
    check_attribute_sizes(file, operation);
    Reading reading{&file, {}, {}};
    const CoreContext core(reading, operation);
    const Layout l = layout_of(core, file, operation);
    require_readers_agree(core, operation);
    const exr_attr_box2i_t& window = l.window;

    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0) return;  // read_exr names an empty window itself
    const std::string size_text = std::to_string(width) + "x" + std::to_string(height);
    check_declared_sizes(core, window, limits, l.storage == EXR_STORAGE_TILED);
    // Its scanline reader sizes each line buffer for a whole chunk of lines
    // (up to 256 for DWAB), however few lines the image has: count those rows.
    std::int64_t rows = height;
    if (l.storage == EXR_STORAGE_SCANLINE) {
        int32_t lines = 1;
        core.check(exr_get_scanlines_per_chunk(core.get(), 0, &lines), "its chunk layout cannot be read");
        if (lines > 0) rows = (height + lines - 1) / lines * lines;
    }
    const double decoded = double(width) * double(rows) * double(bytes_per_pixel(core));
    const double bound = double(file.size()) * exr_max_expansion(l.compression);
    if (decoded > bound)
        throw Error(ErrorCategory::Io, operation,
                    in_quotes(file.path()) + " declares a " + size_text + " data window (" +
                        std::to_string(std::uint64_t(decoded)) + " bytes decoded) that its " +
                        std::to_string(file.size()) + " bytes cannot hold in this compression; "
                        "the header is corrupt or the file truncated");
    if (chunks == ChunkCheck::Skip) return;
    // Decompress and discard; without a decoder (DWA), the table entries are what can be checked.
    const bool tiled = l.storage == EXR_STORAGE_TILED;
    for_each_chunk(core, tiled, window, [&](const exr_chunk_info_t& chunk, int, int, const std::string& where) {
        if (core_decodes(l.compression))
            core.check(decode_chunk(core, chunk, [](exr_coding_channel_info_t&) {}), where + " cannot be decoded");
    });
}

bool decode_exr(const InputFile& file, const std::vector<std::string>& channels, Image& image,
                std::string_view operation)
{
    Reading reading{&file, {}, {}};
    const CoreContext core(reading, operation);
    const Layout l = layout_of(core, file, operation);
    if (!core_decodes(l.compression)) return false;
    const std::size_t row_bytes = std::size_t(image.pitch()) * sizeof(float);
    for_each_chunk(core, l.storage == EXR_STORAGE_TILED, l.window, [&](const exr_chunk_info_t& chunk, int x0, int y0,
                                                  const std::string& where) {
        // The chunk's pixels land at their place in the data window, as floats.
        if (x0 + chunk.width > image.width() || y0 + chunk.height > image.height())
            core.check(EXR_ERR_CORRUPT_CHUNK, where + " lies outside the data window");
        const std::size_t offset = std::size_t(y0) * std::size_t(image.pitch()) + std::size_t(x0);
        const exr_result_t result = decode_chunk(core, chunk, [&](exr_coding_channel_info_t& channel) {
            const auto it = std::find(channels.begin(), channels.end(), channel.channel_name);
            if (it == channels.end()) return;
            channel.decode_to_ptr = reinterpret_cast<uint8_t*>(image.plane(int(it - channels.begin())) + offset);
            channel.user_pixel_stride = sizeof(float);
            channel.user_line_stride = int32_t(row_bytes);
            channel.user_bytes_per_element = sizeof(float);
            channel.user_data_type = EXR_PIXEL_FLOAT;
        });
        core.check(result, where + " cannot be decoded");
    });
    return true;
}

}  // namespace penumbra::detail
