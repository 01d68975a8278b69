// OpenEXR reading and writing, and the atomic replace that write_png shares.
#include "penumbra/exr_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfVersion.h>

#include <Imath/ImathBox.h>

#include <tbb/info.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <system_error>
#include <utility>

#include "exr_streams.h"
#include "exr_validate.h"
#include "penumbra/error.h"
#include "penumbra/input_file.h"
#include "penumbra/output_files.h"
#include "quoted.h"

namespace penumbra {
namespace {

using detail::CheckedOutputStream;
using detail::DescriptorInputStream;
using detail::translating_exr_exceptions;
using detail::use_hardware_threads_for_exr;

namespace fs = std::filesystem;

constexpr std::string_view kReadAdvice = "; the file may be truncated or corrupt, re-create it";
constexpr std::string_view kWriteAdvice = "; check free disk space and write permission";

using detail::in_quotes;

[[noreturn]] void throw_io(std::string_view operation, const std::string& message)
{
    throw Error(ErrorCategory::Io, operation, message);
}

std::string joined(const std::vector<std::string>& names)
{
    if (names.empty()) return "(none)";
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + in_quotes(name);
    return text;
}

// ---------------------------------------------------------------- arguments

void require_distinct_names(const std::vector<std::string>& channels, std::string_view operation)
{
    require(!channels.empty(), operation, "no channel names given; name at least one channel");
    std::set<std::string> seen;
    for (const std::string& name : channels) {
        require(!name.empty(), operation, "a channel name is empty; EXR channels need a name");
        require(seen.insert(name).second, operation,
                "channel " + in_quotes(name) + " is named twice; name each channel once");
    }
}

// ---------------------------------------------------------------- reading

// An EXR opened for reading: the file, the stream over it and OpenEXR's reader.
struct OpenExr {
    InputFile file;
    std::unique_ptr<DescriptorInputStream> stream;
    std::unique_ptr<Imf::InputFile> reader;
};

// What the file system can tell is checked before OpenEXR sees the file, so that
// a wrong path, a FIFO or a file of another format gets a message that says just
// that; and the header's claims before OpenEXR's reader sizes its tables by them.
OpenExr open_exr(const std::string& path, std::string_view operation, const ExrReadLimits& limits,
                 detail::ChunkCheck chunks)
{
    OpenExr exr{open_input_file(path, operation), nullptr, nullptr};
    char magic[4] = {};
    if (!exr.file.read_at(0, magic, sizeof magic) || !Imf::isImfMagic(magic))
        throw_io(operation, in_quotes(path) + " is not an OpenEXR file (it lacks the EXR magic number); "
                                           "convert it to .exr first");
    detail::validate_exr(exr.file, limits, operation, chunks);
    exr.stream = std::make_unique<DescriptorInputStream>(exr.file);
    translating_exr_exceptions(operation, path, kReadAdvice,
                               [&] { exr.reader = std::make_unique<Imf::InputFile>(*exr.stream); });
    return exr;
}

std::vector<std::string> channel_names(const Imf::Header& header)
{
    std::vector<std::string> names;
    for (auto channel = header.channels().begin(); channel != header.channels().end(); ++channel)
        names.emplace_back(channel.name());
    return names;
}

void require_channels_present(const Imf::Header& header, const std::vector<std::string>& channels,
                              const std::string& path, std::string_view operation)
{
    for (const std::string& name : channels) {
        const Imf::Channel* channel = header.channels().findChannel(name);
        if (!channel)
            throw_io(operation, in_quotes(path) + " has no channel " + in_quotes(name) + "; its channels are " +
                                    joined(channel_names(header)));
        // Reading a subsampled channel into a full-resolution plane would need
        // an upsampling policy; refusing is clearer than inventing one.
        if (channel->xSampling != 1 || channel->ySampling != 1)
            throw_io(operation,
                     "channel " + in_quotes(name) + " of " + in_quotes(path) + " is subsampled (" +
                         std::to_string(channel->xSampling) + "x" + std::to_string(channel->ySampling) +
                         "); only full-resolution channels can be read, re-export it unsubsampled");
    }
}

struct Extent {
    int width = 0, height = 0;
};

// 64-bit arithmetic: a window spanning INT_MIN..INT_MAX is 2^32 pixels wide.
Extent data_window_extent(const Imath::Box2i& window, const std::string& path, std::string_view operation)
{
    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    std::ostringstream corners;
    corners << '(' << window.min.x << ", " << window.min.y << ")..(" << window.max.x << ", " << window.max.y
            << ')';
    if (width <= 0 || height <= 0)
        throw_io(operation, in_quotes(path) + " has an empty data window " + corners.str() +
                                ": it holds no pixels; re-export it with at least one pixel");
    if (width > INT_MAX || height > INT_MAX)
        throw_io(operation, in_quotes(path) + " has a data window too large to read " + corners.str());
    return {int(width), int(height)};
}

// ---------------------------------------------------------------- both ways

// One FLOAT slice per plane. Slice::Make subtracts the data window origin from
// the plane pointer (in 64-bit arithmetic), because OpenEXR addresses pixels by
// their absolute coordinates: pixel (min.x, min.y) lands at plane(c)[0].
// Slice::Make takes a const pointer for both directions; when reading, `image`
// refers to a non-const Image that OpenEXR fills.
Imf::FrameBuffer frame_buffer_over(const Image& image, const std::vector<std::string>& channels,
                                   const Imath::Box2i& window)
{
    Imf::FrameBuffer frame;
    const std::size_t row_bytes = std::size_t(image.pitch()) * sizeof(float);
    for (std::size_t c = 0; c < channels.size(); ++c)
        frame.insert(channels[c],
                     Imf::Slice::Make(Imf::FLOAT, image.plane(int(c)), window, sizeof(float), row_bytes));
    return frame;
}

// ---------------------------------------------------------------- writing

Imf::Header float_header(const Image& image, const std::vector<std::string>& channels)
{
    const Imath::Box2i window({0, 0}, {image.width() - 1, image.height() - 1});
    Imf::Header header(window, window, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, Imf::ZIP_COMPRESSION);
    for (const std::string& name : channels) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    return header;
}

void write_exr_pixels(const std::string& temporary_path, const Image& image,
                      const std::vector<std::string>& channels)
{
    use_hardware_threads_for_exr();
    const Imf::Header header = float_header(image, channels);
    CheckedOutputStream stream(temporary_path);
    {
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frame_buffer_over(image, channels, header.dataWindow()));
        file.writePixels(image.height());
    }  // the destructor writes the scanline offset table
    stream.close();
}

}  // namespace

namespace detail {

void use_hardware_threads_for_exr()
{
    static std::once_flag once;
    std::call_once(once, [] { Imf::setGlobalThreadCount(std::max(1, tbb::info::default_concurrency())); });
}

void write_file_atomically(const std::string& path, std::string_view operation,
                           const std::function<void(const std::string& temporary_path)>& write_temporary)
{
    require_safe_outputs({path}, {}, operation);
    OutputFiles output{std::string(operation)};
    output.stage(path, write_temporary);
    output.publish();
}

}  // namespace detail

std::vector<std::string> exr_channel_names(const std::string& path, const ExrReadLimits& limits)
{
    const OpenExr exr = open_exr(path, "exr_channel_names", limits, detail::ChunkCheck::Skip);
    return channel_names(exr.reader->header());
}

Image read_exr(const std::string& path, const std::vector<std::string>& channels, const ExrReadLimits& limits)
{
    constexpr std::string_view operation = "read_exr";
    require_distinct_names(channels, operation);
    const OpenExr exr = open_exr(path, operation, limits, detail::ChunkCheck::Skip);
    Imf::InputFile* file = exr.reader.get();
    require_channels_present(file->header(), channels, path, operation);
    const Imath::Box2i window = file->header().dataWindow();
    const Extent extent = data_window_extent(window, path, operation);
    if (!file->isComplete())
        throw_io(operation, in_quotes(path) +
                                " is incomplete: its table of chunk offsets lacks some scanlines or tiles" +
                                std::string(kReadAdvice));

    // Uninitialised: every pixel is decoded or the read throws (decode_exr
    // finds every chunk, and Imf's readPixels every scanline or tile).
    Image image(extent.width, extent.height, int(channels.size()), Image::Uninitialized{});
    // One pass decodes and checks every chunk; for DWA, which the core library
    // cannot decode, check the chunks' table entries, then read with Imf.
    if (detail::decode_exr(exr.file, channels, image, operation)) return image;
    detail::validate_exr(exr.file, limits, operation, detail::ChunkCheck::DecodeEvery);
    use_hardware_threads_for_exr();
    translating_exr_exceptions(operation, path, kReadAdvice, [&] {
        file->setFrameBuffer(frame_buffer_over(image, channels, window));
        file->readPixels(window.min.y, window.max.y);
    });
    return image;
}

void write_exr(const std::string& path, const Image& image, const std::vector<std::string>& channels)
{
    constexpr std::string_view operation = "write_exr";
    OutputFiles output{std::string(operation)};
    stage_exr(output, path, image, channels);
    output.publish();
}

void stage_exr(OutputFiles& output, const std::string& path, const Image& image,
               const std::vector<std::string>& channels)
{
    constexpr std::string_view operation = "write_exr";
    require_distinct_names(channels, operation);
    require(int(channels.size()) == image.channels(), operation,
            "the image has " + std::to_string(image.channels()) + " channels but " +
                std::to_string(channels.size()) + (channels.size() == 1 ? " name was" : " names were") +
                " given for " + in_quotes(path) + "; give one name per channel");
    require(!image.empty(), operation,
            "the image for " + in_quotes(path) + " is empty (" + std::to_string(image.width()) + "x" +
                std::to_string(image.height()) + "); an EXR file needs at least one pixel");
    require_safe_outputs({path}, {}, operation);
    output.stage(path, [&](const std::string& temporary) {
        translating_exr_exceptions(operation, path, kWriteAdvice,
                                   [&] { write_exr_pixels(temporary, image, channels); });
    });
}

}  // namespace penumbra
