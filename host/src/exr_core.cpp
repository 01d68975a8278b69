// The OpenEXR core library over an InputFile (exr_core.h).
#include "exr_core.h"
#include "quoted.h"

#include <algorithm>

namespace penumbra::detail {
namespace {

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

}  // namespace

CoreContext::CoreContext(Reading& reading, std::string_view operation) : reading_(reading), operation_(operation)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = record_error;
    init.read_fn = read_bytes;
    init.size_fn = file_size;
    init.user_data = &reading;
    check(exr_start_read(&ctxt_, reading.file->path().c_str(), &init), "its header cannot be read");
}

void CoreContext::refuse(const std::string& what) const
{
    throw Error(ErrorCategory::Io, operation_,
                in_quotes(reading_.file->path()) + " is corrupt: " + what + "; re-create the file");
}

void CoreContext::check(exr_result_t result, const std::string& what) const
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

CoreTiles tile_descriptor(const CoreContext& core)
{
    CoreTiles tiles;
    core.check(exr_get_tile_descriptor(core.get(), 0, &tiles.width, &tiles.height, &tiles.levels, &tiles.rounding),
               "its tile description cannot be read");
    return tiles;
}

void check_declared_sizes(const CoreContext& core, const exr_attr_box2i_t& window, const ExrReadLimits& limits,
                          bool tiled)
{
    const InputFile& file = core.file();
    const std::string_view operation = core.operation();
    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    const auto pixels = std::uint64_t(width) * std::uint64_t(height);
    const std::string size_text = std::to_string(width) + "x" + std::to_string(height);
    if (pixels > limits.max_pixels)
        throw Error(ErrorCategory::Io, operation,
                    in_quotes(file.path()) + " declares a " + size_text + " data window, " + std::to_string(pixels) +
                        " pixels, more than the limit of " + std::to_string(limits.max_pixels) +
                        " (raise it with --max-pixels N / ExrReadLimits::max_pixels if the file is genuine)");
    // OpenEXR's C++ reader allocates the chunk offset table (8 bytes a chunk,
    // every tile of every level) from the header; a file holds at least that.
    int32_t chunk_count = 0;
    core.check(exr_get_chunk_count(core.get(), 0, &chunk_count), "its chunk count cannot be read");
    if (chunk_count < 0 || std::uint64_t(chunk_count) * 8 > file.size())
        throw Error(ErrorCategory::Io, operation,
                    in_quotes(file.path()) + " declares " + std::to_string(chunk_count) + " chunks, whose offset table alone its " +
                        std::to_string(file.size()) + " bytes cannot hold; the header is corrupt or the file truncated");
    // Its tiled reader also keeps a buffer of a row of tiles (the window's width
    // times the tile height) and one tile: bound both by the image itself, plus
    // room for tiles larger than a small image.
    if (tiled) {
        const CoreTiles tiles = tile_descriptor(core);
        const uint32_t tile_w = tiles.width, tile_h = tiles.height;
        const std::uint64_t room = pixels + (std::uint64_t(1) << 22);
        if (std::uint64_t(tile_w) * tile_h > room || std::uint64_t(width) * tile_h > room ||
            std::uint64_t(tile_w) * std::uint64_t(height) > room)
            throw Error(ErrorCategory::Io, operation,
                        in_quotes(file.path()) + " declares " + std::to_string(tile_w) + "x" + std::to_string(tile_h) +
                            " tiles for a " + size_text + " image; the header is corrupt");
    }
}

}  // namespace penumbra::detail
