// EXR plausibility and completeness checks (exr_validate.h), on the OpenEXR
// core (C) API, which reads a chunk's table entry and decompresses it without
// touching a frame buffer: the C++ InputFile of OpenEXR 3.1 zero-pads a chunk
// that decompresses short and hands the caller whatever its buffer held.
#include "exr_validate.h"

#include <OpenEXR/openexr.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <mutex>
#include <string>

#include "penumbra/error.h"

namespace penumbra::detail {
namespace {

std::string in_quotes(const std::string& text) { return "'" + text + "'"; }

// The core library reports through a callback; keep the first message.
struct Reading {
    const InputFile* file;
    std::mutex mutex;
    std::string first_error;
};

void record_error(exr_const_context_t ctxt, exr_result_t, const char* message)
{
    void* user = nullptr;
    if (exr_get_user_data(ctxt, &user) != EXR_ERR_SUCCESS || !user) return;
    auto* reading = static_cast<Reading*>(user);
    const std::lock_guard lock(reading->mutex);
    if (reading->first_error.empty() && message) reading->first_error = message;
}

int64_t read_bytes(exr_const_context_t, void* user, void* buffer, uint64_t size, uint64_t offset,
                   exr_stream_error_func_ptr_t)
{
    const InputFile& file = *static_cast<Reading*>(user)->file;
    if (offset >= file.size()) return 0;
    const uint64_t count = std::min<uint64_t>(size, file.size() - offset);
    return file.read_at(offset, buffer, std::size_t(count)) ? int64_t(count) : -1;
}

int64_t file_size(exr_const_context_t, void* user) { return int64_t(static_cast<Reading*>(user)->file->size()); }

class CoreContext {
public:
    CoreContext(Reading& reading, std::string_view operation) : reading_(reading), operation_(operation)
    {
        exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
        init.error_handler_fn = record_error;
        init.read_fn = read_bytes;
        init.size_fn = file_size;
        init.user_data = &reading;
        check(exr_start_read(&ctxt_, reading.file->path().c_str(), &init), "its header cannot be read");
    }
    ~CoreContext() { exr_finish(&ctxt_); }
    CoreContext(const CoreContext&) = delete;
    CoreContext& operator=(const CoreContext&) = delete;

    exr_const_context_t get() const { return ctxt_; }

    void check(exr_result_t result, const std::string& what) const
    {
        if (result == EXR_ERR_SUCCESS) return;
        std::string detail;
        {
            const std::lock_guard lock(reading_.mutex);
            detail = reading_.first_error;
        }
        if (detail.empty()) detail = exr_get_default_error_message(result);
        throw Error(ErrorCategory::Io, operation_,
                    in_quotes(reading_.file->path()) + " is corrupt or truncated: " + what + " (" + detail +
                        "); re-create the file");
    }

private:
    Reading& reading_;
    std::string_view operation_;
    exr_context_t ctxt_ = nullptr;
};

std::uint64_t bytes_per_pixel(const CoreContext& core)
{
    const exr_attr_chlist_t* channels = nullptr;
    core.check(exr_get_channels(core.get(), 0, &channels), "its channel list cannot be read");
    std::uint64_t bytes = 0;
    for (int c = 0; c < channels->num_channels; ++c)
        bytes += channels->entries[c].pixel_type == EXR_PIXEL_HALF ? 2 : 4;
    return bytes;
}

// Decompresses one chunk and discards the result: the core library fails when
// the chunk's table entry is missing or points outside the file, or when the
// data decompresses to a size other than the chunk's pixels need.
void check_chunk(const CoreContext& core, const exr_chunk_info_t& chunk, const std::string& where)
{
    exr_decode_pipeline_t decode = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_result_t result = exr_decoding_initialize(core.get(), 0, &chunk, &decode);
    // No channel has a destination, so the default routines read and decompress only.
    if (result == EXR_ERR_SUCCESS) result = exr_decoding_choose_default_routines(core.get(), 0, &decode);
    if (result == EXR_ERR_SUCCESS) result = exr_decoding_run(core.get(), 0, &decode);
    exr_decoding_destroy(core.get(), &decode);
    // OpenEXR 3.1's core has no DWA decoder: the chunk's table entry and header were read, which is what it can check.
    if (result == EXR_ERR_FEATURE_NOT_IMPLEMENTED) return;
    core.check(result, where + " cannot be decoded");
}

void check_scanline_chunks(const CoreContext& core, const exr_attr_box2i_t& window)
{
    int32_t lines = 0;
    core.check(exr_get_scanlines_per_chunk(core.get(), 0, &lines), "its chunk layout cannot be read");
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    const std::int64_t chunks = (height + lines - 1) / lines;
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, chunks), [&](const tbb::blocked_range<std::int64_t>& r) {
        for (std::int64_t i = r.begin(); i < r.end(); ++i) {
            const int y = int(window.min.y + i * lines);
            exr_chunk_info_t chunk{};
            const std::string where = "the scanlines from y = " + std::to_string(y);
            core.check(exr_read_scanline_chunk_info(core.get(), 0, y, &chunk), where + " are missing");
            check_chunk(core, chunk, where);
        }
    });
}

// Level 0 only: that is the level read_exr reads.
void check_tile_chunks(const CoreContext& core)
{
    int32_t tile_w = 0, tile_h = 0, level_w = 0, level_h = 0;
    core.check(exr_get_tile_sizes(core.get(), 0, 0, 0, &tile_w, &tile_h), "its tile size cannot be read");
    core.check(exr_get_level_sizes(core.get(), 0, 0, 0, &level_w, &level_h), "its level size cannot be read");
    const int across = (level_w + tile_w - 1) / tile_w, down = (level_h + tile_h - 1) / tile_h;
    tbb::parallel_for(tbb::blocked_range<int>(0, down), [&](const tbb::blocked_range<int>& rows) {
        for (int ty = rows.begin(); ty < rows.end(); ++ty)
            for (int tx = 0; tx < across; ++tx) {
                exr_chunk_info_t chunk{};
                const std::string where = "tile (" + std::to_string(tx) + ", " + std::to_string(ty) + ")";
                core.check(exr_read_tile_chunk_info(core.get(), 0, tx, ty, 0, 0, &chunk), where + " is missing");
                check_chunk(core, chunk, where);
            }
    });
}

}  // namespace

// Decoded bytes per stored byte, at most, where the format bounds it. NONE
// stores pixels as they are. RLE (OpenEXR's ImfRle: a signed count byte and a
// value byte for a run of at most 127 bytes) reaches 63.5. ZIP and ZIPS are
// zlib's deflate, whose maximum is 1032 (zlib's "technical details": 258-byte
// matches coded in 2 bits, plus framing). PXR24 stores 32-bit floats as 24
// bits before deflate: 1032 * 4 / 3 = 1376. PIZ, B44/B44A and DWAA/DWAB
// (run lengths inside Huffman or DCT coding) have no small bound; for them,
// 0 means "no bound": every chunk is still decoded and checked in full.
double exr_max_expansion(int compression)
{
    switch (compression) {
    case EXR_COMPRESSION_NONE: return 1.0;
    case EXR_COMPRESSION_RLE: return 63.5;
    case EXR_COMPRESSION_ZIPS:
    case EXR_COMPRESSION_ZIP: return 1032.0;
    case EXR_COMPRESSION_PXR24: return 1376.0;
    default: return 0.0;
    }
}

void validate_exr(const InputFile& file, const ExrReadLimits& limits, std::string_view operation, ChunkCheck chunks)
{
    Reading reading{&file, {}, {}};
    const CoreContext core(reading, operation);
    exr_storage_t storage{};
    exr_attr_box2i_t window{};
    exr_compression_t compression{};
    core.check(exr_get_storage(core.get(), 0, &storage), "its storage type cannot be read");
    core.check(exr_get_data_window(core.get(), 0, &window), "its data window cannot be read");
    core.check(exr_get_compression(core.get(), 0, &compression), "its compression cannot be read");
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED)
        throw Error(ErrorCategory::Io, operation,
                    in_quotes(file.path()) + " holds deep data; only flat scanline or tiled images can be read");

    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0) return;  // read_exr names an empty window itself
    const auto pixels = std::uint64_t(width) * std::uint64_t(height);
    const std::string size_text = std::to_string(width) + "x" + std::to_string(height);
    if (pixels > limits.max_pixels)
        throw Error(ErrorCategory::Io, operation,
                    in_quotes(file.path()) + " declares a " + size_text + " data window, " + std::to_string(pixels) +
                        " pixels, more than the limit of " + std::to_string(limits.max_pixels) +
                        " (raise it with --max-pixels N / ExrReadLimits::max_pixels if the file is genuine)");
    const double decoded = double(pixels) * double(bytes_per_pixel(core));
    const double bound = double(file.size()) * exr_max_expansion(compression);
    if (bound > 0.0 && decoded > bound)
        throw Error(ErrorCategory::Io, operation,
                    in_quotes(file.path()) + " declares a " + size_text + " data window (" +
                        std::to_string(std::uint64_t(decoded)) + " bytes decoded) that its " +
                        std::to_string(file.size()) + " bytes cannot hold in this compression; "
                        "the header is corrupt or the file truncated");
    if (chunks == ChunkCheck::Skip) return;
    if (storage == EXR_STORAGE_SCANLINE) check_scanline_chunks(core, window);
    else check_tile_chunks(core);
}

}  // namespace penumbra::detail
