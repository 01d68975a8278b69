// Reading deep shadow maps from OpenEXR deep images (penumbra/deep_exr.h).
//
// Order of work, so that nothing is allocated on a file's word alone:
//  1. the header walk of the flat reader (check_attribute_sizes) and, with the
//     core library, the data window against ExrReadLimits, the chunk table
//     against the file's size, and every chunk's table entry: present, inside
//     the file, and claiming no more decoded bytes than its stored bytes can
//     expand to in the file's compression (exr_max_expansion);
//  2. OpenEXR's C++ reader reads the sample counts (one uint per pixel, within
//     max_pixels); each chunk's counts times the bytes of a sample must equal
//     the decoded size that chunk declares, so the total samples are bounded by
//     the file's size before the sample arrays are allocated;
//  3. the samples are read in bands of rows (a row of tiles), then checked and
//     turned into vertices pixel by pixel (deep_exr_samples.cpp).
#include "penumbra/deep_exr.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineInputFile.h>
#include <OpenEXR/ImfDeepTiledInputFile.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfVersion.h>

#include <algorithm>
#include <array>
#include <memory>
#include <mutex>
#include <vector>

#include "deep_exr_samples.h"
#include "exr_core.h"
#include "exr_streams.h"
#include "exr_validate.h"
#include "quoted.h"

namespace penumbra {
namespace {

constexpr std::string_view kAdvice = "; the file may be truncated or corrupt, re-create it";
using detail::kScanlineBand;

using detail::in_quotes;

[[noreturn]] void refuse(const detail::DeepFileKind& kind, const std::string& path, const std::string& what)
{
    throw Error(ErrorCategory::Io, kind.operation, in_quotes(path) + " " + what);
}

// One chunk's pixels (relative to the data window) and the decoded bytes it declares.
struct ChunkClaim {
    int x0, y0, width, height;
    std::uint64_t unpacked;
};

// What the core library's reading of the header and chunk table establishes.
struct DeepLayout {
    bool tiled = false;
    int width = 0, height = 0;
    std::uint64_t bytes_per_sample = 0;  // every channel of the file, as stored
    bool has_zback = false, has_a = false, has_t = false, has_ids = false;
    std::vector<ChunkClaim> chunks;
};

bool is_deep(exr_storage_t storage)
{
    return storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED;
}

// The kind's channel of ids: full resolution and UINT, so that every id is
// exact (a float holds integers only to 2^24, a half to 2^11).
void inspect_id_channel(const exr_attr_chlist_entry_t& e, const detail::DeepFileKind& kind, const std::string& path)
{
    const std::string name(kind.id_channel);
    if (e.x_sampling != 1 || e.y_sampling != 1)
        refuse(kind, path, "has a subsampled channel " + in_quotes(name) + "; its ids are one a sample");
    if (e.pixel_type != EXR_PIXEL_UINT)
        refuse(kind, path, "stores channel " + in_quotes(name) + " as " +
                               (e.pixel_type == EXR_PIXEL_HALF ? "HALF" : "FLOAT") +
                               "; its ids are UINT, exact integers (" + std::string(kind.writer) + " writes them so)");
}

// The channels the kind of file needs, their types, and the bytes of one sample.
void inspect_channels(const detail::CoreContext& core, const detail::DeepFileKind& kind, const std::string& path,
                      DeepLayout& layout)
{
    const exr_attr_chlist_t* channels = nullptr;
    core.check(exr_get_channels(core.get(), 0, &channels), "its channel list cannot be read");
    bool has_z = false;
    for (int c = 0; c < channels->num_channels; ++c) {
        const exr_attr_chlist_entry_t& e = channels->entries[c];
        layout.bytes_per_sample += e.pixel_type == EXR_PIXEL_HALF ? 2 : 4;
        const std::string name(e.name.str, std::size_t(e.name.length));
        if (!kind.id_channel.empty() && name == kind.id_channel) {
            inspect_id_channel(e, kind, path);
            layout.has_ids = true;
            continue;
        }
        const bool ours = name == "Z" || name == "ZBack" || name == "A" || name == kDeepTransmittanceChannel;
        if (!ours) continue;
        if (e.x_sampling != 1 || e.y_sampling != 1)
            refuse(kind, path,
                   "has a subsampled channel " + in_quotes(name) + "; a deep map's channels are full resolution");
        if (e.pixel_type == EXR_PIXEL_UINT)
            refuse(kind, path,
                   "stores channel " + in_quotes(name) + " as UINT; depths and opacities are FLOAT (or HALF)");
        has_z |= name == "Z", layout.has_a |= name == "A" && kind.needs_opacity;
        layout.has_zback |= name == "ZBack", layout.has_t |= name == kDeepTransmittanceChannel;
    }
    if (!has_z || (kind.needs_opacity && !layout.has_a))
        refuse(kind, path, std::string("has no ") + (has_z ? "A" : "Z") + " channel; " + std::string(kind.what) +
                               (kind.needs_opacity ? " needs Z (depth) and A (opacity) per sample, "
                                                     "as OpenEXR's \"Interpreting Deep Pixels\" defines them"
                                                   : " needs Z (depth) per sample"));
}

// Every chunk's table entry, its decoded size bounded by its stored size.
void inspect_chunks(const detail::CoreContext& core, const exr_attr_box2i_t& window, exr_compression_t compression,
                    DeepLayout& layout)
{
    const double expansion = detail::exr_max_expansion(compression);
    std::mutex mutex;
    detail::for_each_chunk(core, layout.tiled, window,
                           [&](const exr_chunk_info_t& chunk, int x0, int y0, const std::string& where) {
        if (double(chunk.unpacked_size) > double(chunk.packed_size) * expansion + 64.0)
            core.refuse(where + " claims " + std::to_string(chunk.unpacked_size) + " bytes of samples from " +
                        std::to_string(chunk.packed_size) + " stored bytes, more than its compression can expand to");
        const std::lock_guard lock(mutex);
        layout.chunks.push_back({x0, y0, chunk.width, chunk.height, chunk.unpacked_size});
    });
}

DeepLayout inspect_deep(const InputFile& file, const ExrReadLimits& limits, const detail::DeepFileKind& kind)
{
    const std::string& path = file.path();
    char magic[4] = {};
    if (!file.read_at(0, magic, sizeof magic) || !Imf::isImfMagic(magic))
        refuse(kind, path, "is not an OpenEXR file (it lacks the EXR magic number)");
    detail::check_attribute_sizes(file, kind.operation);
    detail::Reading reading{&file, {}, {}};
    const detail::CoreContext core(reading, kind.operation);
    detail::require_readers_agree(core, kind.operation);
    exr_storage_t storage{};
    exr_attr_box2i_t window{};
    exr_compression_t compression{};
    core.check(exr_get_storage(core.get(), 0, &storage), "its storage type cannot be read");
    if (!is_deep(storage))
        refuse(kind, path, "is a flat (not deep) image; " + std::string(kind.what) +
                               " is a deep scanline or deep tiled OpenEXR file (" + std::string(kind.writer) +
                               " writes one)");
    core.check(exr_get_data_window(core.get(), 0, &window), "its data window cannot be read");
    core.check(exr_get_compression(core.get(), 0, &compression), "its compression cannot be read");
    DeepLayout layout;
    layout.tiled = storage == EXR_STORAGE_DEEP_TILED;
    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0 || width > INT32_MAX || height > INT32_MAX)
        refuse(kind, path, "has an empty or impossible data window; re-export it with at least one pixel");
    layout.width = int(width), layout.height = int(height);
    detail::check_declared_sizes(core, window, limits, layout.tiled);
    inspect_channels(core, kind, path, layout);
    inspect_chunks(core, window, compression, layout);
    return layout;
}

// Each chunk's declared decoded size must be exactly its samples' bytes: then
// the counts (already bounded per chunk by its stored size) bound the arrays.
std::uint64_t checked_sample_total(const DeepLayout& layout, const std::vector<unsigned>& counts,
                                   const detail::DeepFileKind& kind, const std::string& path)
{
    std::uint64_t total = 0;
    for (const ChunkClaim& c : layout.chunks) {
        std::uint64_t samples = 0;
        for (int y = c.y0; y < std::min(layout.height, c.y0 + c.height); ++y)
            for (int x = c.x0; x < std::min(layout.width, c.x0 + c.width); ++x)
                samples += counts[std::size_t(y) * std::size_t(layout.width) + std::size_t(x)];
        if (samples * layout.bytes_per_sample != c.unpacked)
            refuse(kind, path, "is corrupt: the chunk at pixel (" + std::to_string(c.x0) + ", " + std::to_string(c.y0) +
                             ") counts " + std::to_string(samples) + " samples but declares " +
                             std::to_string(c.unpacked) + " bytes of them; re-create the file");
        total += samples;
    }
    return total;
}

// The C++ reader of either layout behind one interface: counts, then bands.
class DeepReader {
public:
    DeepReader(const InputFile& file, bool tiled) : stream_(file)
    {
        if (tiled)
            tiled_ = std::make_unique<Imf::DeepTiledInputFile>(stream_);
        else
            scanline_ = std::make_unique<Imf::DeepScanLineInputFile>(stream_);
    }
    const Imf::Header& header() const { return tiled_ ? tiled_->header() : scanline_->header(); }
    const Imath::Box2i& window() const { return header().dataWindow(); }
    int band_height() const { return tiled_ ? int(tiled_->tileYSize()) : kScanlineBand; }

    void read_counts(const Imf::DeepFrameBuffer& frame)
    {
        if (tiled_) {
            tiled_->setFrameBuffer(frame);
            tiled_->readPixelSampleCounts(0, tiled_->numXTiles() - 1, 0, tiled_->numYTiles() - 1);
        } else {
            scanline_->setFrameBuffer(frame);
            scanline_->readPixelSampleCounts(window().min.y, window().max.y);
        }
    }
    // Band b: rows [b * band_height, ...) of the data window. OpenEXR forgets
    // the counts when given a new frame buffer, so they are read again first.
    void read_band(const Imf::DeepFrameBuffer& frame, int band, int rows)
    {
        if (tiled_) {
            tiled_->setFrameBuffer(frame);
            tiled_->readPixelSampleCounts(0, tiled_->numXTiles() - 1, band, band);
            tiled_->readTiles(0, tiled_->numXTiles() - 1, band, band);
        } else {
            scanline_->setFrameBuffer(frame);
            const int y0 = window().min.y + band * kScanlineBand;
            scanline_->readPixelSampleCounts(y0, y0 + rows - 1);
            scanline_->readPixels(y0, y0 + rows - 1);
        }
    }

private:
    detail::DescriptorInputStream stream_;
    std::unique_ptr<Imf::DeepScanLineInputFile> scanline_;
    std::unique_ptr<Imf::DeepTiledInputFile> tiled_;
};

// A slice whose element (x, y) in absolute coordinates is base[(y - y0) * width + (x - x0)].
template <class T>
char* shifted(T* base, const Imath::Box2i& window, int y0, int width)
{
    const std::ptrdiff_t shift = std::ptrdiff_t(y0) * width + window.min.x;
    return reinterpret_cast<char*>(base - shift);
}

}  // namespace

namespace detail {

DeepSamples read_deep_samples(const std::string& path, const ExrReadLimits& limits, const DeepFileKind& kind,
                              const std::function<void(const Imf::Header&)>& header)
{
    const InputFile file = open_input_file(path, kind.operation);
    const DeepLayout layout = inspect_deep(file, limits, kind);
    const int width = layout.width, height = layout.height;
    DeepSamples samples;
    samples.width = width, samples.height = height;
    translating_exr_exceptions(kind.operation, path, kAdvice, [&] {
        use_hardware_threads_for_exr();
        DeepReader reader(file, layout.tiled);
        if (header) header(reader.header());
        const Imath::Box2i window = reader.window();
        samples.counts.assign(std::size_t(width) * std::size_t(height), 0);
        Imf::DeepFrameBuffer counts_frame;
        const Imf::Slice count_slice(Imf::UINT, shifted(samples.counts.data(), window, window.min.y, width),
                                     sizeof(unsigned), sizeof(unsigned) * std::size_t(width));
        counts_frame.insertSampleCountSlice(count_slice);
        reader.read_counts(counts_frame);
        const std::uint64_t total = checked_sample_total(layout, samples.counts, kind, path);
        samples.allocate(total, layout.has_zback, layout.has_a, layout.has_t);
        if (layout.has_ids) samples.ids.assign(total, 0), samples.has_ids = true;

        const int band_rows = reader.band_height();
        std::array<std::vector<float*>, 4> pointers;
        std::vector<std::uint32_t*> id_pointers;
        for (int band = 0; band * band_rows < height; ++band) {
            const int y0 = band * band_rows, rows = std::min(band_rows, height - y0);
            Imf::DeepFrameBuffer frame;
            frame.insertSampleCountSlice(count_slice);
            const std::size_t first = std::size_t(y0) * std::size_t(width), pixels = std::size_t(rows) * width;
            for (int c = 0; c < 4; ++c) {
                if (!samples.has[c]) continue;  // not in the file (or, A, not read)
                pointers[std::size_t(c)].resize(pixels);
                for (std::size_t p = 0; p < pixels; ++p)
                    pointers[std::size_t(c)][p] = samples.channel(c).data() + samples.first[first + p];
                frame.insert(DeepSamples::kNames[c],
                             Imf::DeepSlice(Imf::FLOAT, shifted(pointers[std::size_t(c)].data(), window,
                                                                window.min.y + y0, width),
                                            sizeof(float*), sizeof(float*) * std::size_t(width), sizeof(float)));
            }
            if (samples.has_ids) {
                id_pointers.resize(pixels);
                for (std::size_t p = 0; p < pixels; ++p) id_pointers[p] = samples.ids.data() + samples.first[first + p];
                frame.insert(std::string(kind.id_channel),
                             Imf::DeepSlice(Imf::UINT, shifted(id_pointers.data(), window, window.min.y + y0, width),
                                            sizeof(std::uint32_t*), sizeof(std::uint32_t*) * std::size_t(width),
                                            sizeof(std::uint32_t)));
            }
            const std::vector<unsigned> counted(samples.counts.begin() + std::ptrdiff_t(first),
                                                samples.counts.begin() + std::ptrdiff_t(first + pixels));
            reader.read_band(frame, band, rows);
            // The arrays were sized by the counts checked; a file that changed
            // since (it is read twice) must not be read into them.
            if (!std::equal(counted.begin(), counted.end(), samples.counts.begin() + std::ptrdiff_t(first)))
                refuse(kind, path, "changed while it was read; read it again");
        }
        samples.origin_x = window.min.x, samples.origin_y = window.min.y;
    });
    return samples;
}

}  // namespace detail

DeepShadowMap read_deep_exr(const std::string& path, const ExrReadLimits& limits)
{
    static constexpr detail::DeepFileKind kDeepShadowMap{"read_deep_exr", "a deep shadow map", "penumbra dsm-build",
                                                         true};
    const detail::DeepSamples samples = detail::read_deep_samples(path, limits, kDeepShadowMap);
    return detail::deep_map_from_samples(samples, samples.width, samples.height, path);
}

}  // namespace penumbra
