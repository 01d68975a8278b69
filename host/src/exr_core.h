// The OpenEXR core (C) library over a file penumbra opened itself, shared by
// the flat checks (exr_validate.cpp) and the deep reader (deep_exr_read.cpp).
#pragma once

#include <OpenEXR/openexr.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>

#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/input_file.h"

namespace penumbra::detail {

// The core library reports through a callback; keep the first message.
struct Reading {
    const InputFile* file;
    std::mutex mutex;
    std::string first_error;
};

class CoreContext {
public:
    // Reads the header through `reading.file` (never by path); Error(Io) if it cannot.
    CoreContext(Reading& reading, std::string_view operation);
    ~CoreContext() { exr_finish(&ctxt_); }
    CoreContext(const CoreContext&) = delete;
    CoreContext& operator=(const CoreContext&) = delete;

    exr_const_context_t get() const { return ctxt_; }
    const InputFile& file() const { return *reading_.file; }
    std::string_view operation() const { return operation_; }

    // A layout the core library accepted but that no reader can walk.
    [[noreturn]] void refuse(const std::string& what) const;
    // Error(Io) naming the file, `what` and the core library's first message, unless success.
    void check(exr_result_t result, const std::string& what) const;

private:
    Reading& reading_;
    std::string_view operation_;
    exr_context_t ctxt_ = nullptr;
};

// The first part's tile description as the core library read it.
struct CoreTiles {
    uint32_t width = 0, height = 0;
    exr_tile_level_mode_t levels{};
    exr_tile_round_mode_t rounding{};
};
CoreTiles tile_descriptor(const CoreContext& core);

// Error(Io) naming the file unless the data window holds at most
// limits.max_pixels pixels and the file can hold the chunk offset table the
// header implies (8 bytes a chunk), and, for a tiled file, its tiles are not
// larger than the image (plus room): OpenEXR's C++ readers allocate by both.
void check_declared_sizes(const CoreContext& core, const exr_attr_box2i_t& window, const ExrReadLimits& limits,
                          bool tiled);

// Runs `body(chunk, x0, y0, where)` for every chunk (scanline block, or tile of
// level 0, the level read_exr reads; flat or deep), in parallel, after reading its table
// entry; (x0, y0) is the chunk's first pixel relative to the data window. (In
// OpenEXR 3.1's core, a tile's start_x/start_y are tile indices, a scanline
// block's are pixel coordinates.)
template <class Body>
void for_each_chunk(const CoreContext& core, bool tiled, const exr_attr_box2i_t& window, Body&& body)
{
    if (!tiled) {
        int32_t lines = 0;
        core.check(exr_get_scanlines_per_chunk(core.get(), 0, &lines), "its chunk layout cannot be read");
        // 0 for a scanline file whose header also holds a `tiles` attribute (found by exr_reader_fuzz).
        if (lines <= 0) core.refuse("it claims " + std::to_string(lines) + " scanlines per chunk");
        const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
        const std::int64_t chunks = (height + lines - 1) / lines;
        tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, chunks), [&](const tbb::blocked_range<std::int64_t>& r) {
            for (std::int64_t i = r.begin(); i < r.end(); ++i) {
                const int y = int(window.min.y + i * lines);
                exr_chunk_info_t chunk{};
                const std::string where = "the scanlines from y = " + std::to_string(y);
                core.check(exr_read_scanline_chunk_info(core.get(), 0, y, &chunk), where + " are missing");
                body(chunk, 0, int(i * lines), where);
            }
        });
        return;
    }
    int32_t tile_w = 0, tile_h = 0, level_w = 0, level_h = 0;
    core.check(exr_get_tile_sizes(core.get(), 0, 0, 0, &tile_w, &tile_h), "its tile size cannot be read");
    core.check(exr_get_level_sizes(core.get(), 0, 0, 0, &level_w, &level_h), "its level size cannot be read");
    if (tile_w <= 0 || tile_h <= 0 || level_w < 0 || level_h < 0)
        core.refuse("it claims tiles of " + std::to_string(tile_w) + "x" + std::to_string(tile_h));
    const int across = (level_w + tile_w - 1) / tile_w, down = (level_h + tile_h - 1) / tile_h;
    tbb::parallel_for(tbb::blocked_range<int>(0, down), [&](const tbb::blocked_range<int>& rows) {
        for (int ty = rows.begin(); ty < rows.end(); ++ty)
            for (int tx = 0; tx < across; ++tx) {
                exr_chunk_info_t chunk{};
                const std::string where = "tile (" + std::to_string(tx) + ", " + std::to_string(ty) + ")";
                core.check(exr_read_tile_chunk_info(core.get(), 0, tx, ty, 0, 0, &chunk), where + " is missing");
                body(chunk, tx * tile_w, ty * tile_h, where);
            }
    });
}

}  // namespace penumbra::detail
