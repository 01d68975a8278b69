// The two readings of an EXR header (exr_validate.h, require_readers_agree).
//
// Every size check before OpenEXR's C++ reader runs (the pixel limit, the
// decoded size a file can hold, the tile bounds) is made on the core (C)
// library's reading of the header. The C++ reader then sizes its line buffers
// and compressors by its own reading. The two are not the same parser: where an
// attribute is damaged, the core library falls back to a default or skips it
// (it is not run in strict mode, which refuses files real writers produce),
// while the C++ reader may keep what it read. A fuzzed 4 KB file passed the
// core-side checks and then made the C++ reader's ZIP compressor ask for over
// 1 GiB (CI's fuzz stage, stop 32). So the fields that size its buffers must
// read the same both ways, or the file is refused before the C++ reader exists.
#include "exr_validate.h"
#include "exr_core.h"
#include "exr_streams.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfTileDescription.h>
#include <OpenEXR/ImfVersion.h>

#include <string>

namespace penumbra::detail {
namespace {

// The C++ reader's view of the first part's header, read as InputFile and
// MultiPartInputFile read it: magic and version, then the attributes.
Imf::Header cpp_header(const InputFile& file, std::string_view operation, int& version)
{
    return translating_exr_exceptions(operation, file.path(), "; the file is corrupt, re-create it", [&] {
        DescriptorInputStream stream(file);
        char magic[4];
        stream.read(magic, sizeof magic);
        stream.read(reinterpret_cast<char*>(&version), sizeof version);
        Imf::Header header;
        header.readFrom(stream, version);
        return header;
    });
}

// The first field the two readings disagree on, or "" when they agree.
std::string first_disagreement(const CoreContext& core, const Imf::Header& header, int version)
{
    exr_storage_t storage{};
    exr_attr_box2i_t window{};
    exr_compression_t compression{};
    const exr_attr_chlist_t* channels = nullptr;
    core.check(exr_get_storage(core.get(), 0, &storage), "its storage type cannot be read");
    core.check(exr_get_data_window(core.get(), 0, &window), "its data window cannot be read");
    core.check(exr_get_compression(core.get(), 0, &compression), "its compression cannot be read");
    core.check(exr_get_channels(core.get(), 0, &channels), "its channel list cannot be read");

    const bool deep = storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED;
    const bool tiled = storage == EXR_STORAGE_TILED || storage == EXR_STORAGE_DEEP_TILED;
    // A single-part flat file is tiled by its version field (InputFile trusts
    // it over the type attribute); a deep or multi-part one by its type.
    const bool typed = deep || Imf::isMultiPart(version);
    const bool cpp_tiled = typed ? header.hasType() && Imf::isTiled(header.type()) : Imf::isTiled(version);
    if (tiled != cpp_tiled) return "whether it is tiled";
    const Imath::Box2i& box = header.dataWindow();
    if (box.min.x != window.min.x || box.min.y != window.min.y || box.max.x != window.max.x ||
        box.max.y != window.max.y)
        return "its data window";
    if (int(header.compression()) != int(compression)) return "its compression";
    int count = 0;
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c) ++count;
    if (count != channels->num_channels) return "its number of channels";
    for (int i = 0; i < channels->num_channels; ++i) {
        const exr_attr_chlist_entry_t& entry = channels->entries[i];
        const Imf::Channel* channel = header.channels().findChannel(std::string(entry.name.str, entry.name.length));
        if (!channel || int(channel->type) != int(entry.pixel_type) || channel->xSampling != entry.x_sampling ||
            channel->ySampling != entry.y_sampling)
            return "its channel list";
    }
    if (tiled) {
        const CoreTiles core_tiles = tile_descriptor(core);
        if (!header.hasTileDescription()) return "its tile description";
        const Imf::TileDescription& tiles = header.tileDescription();
        if (tiles.xSize != core_tiles.width || tiles.ySize != core_tiles.height ||
            int(tiles.mode) != int(core_tiles.levels) || int(tiles.roundingMode) != int(core_tiles.rounding))
            return "its tile description";
    }
    return "";
}

}  // namespace

void require_readers_agree(const CoreContext& core, std::string_view operation)
{
    int version = 0;
    const Imf::Header header = cpp_header(core.file(), operation, version);
    const std::string field = first_disagreement(core, header, version);
    if (!field.empty())
        core.refuse("OpenEXR's two header parsers read " + field +
                    " differently (a damaged attribute one of them skips)");
}

}  // namespace penumbra::detail
