// Views of a caller's memory (penumbra/image_view.h): checks, the in-place
// test, and the one copy in or out for a layout the kernels cannot read.
#include "penumbra/image_view.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <climits>
#include <cstdint>
#include <cstring>

#include "penumbra/error.h"

namespace penumbra {
namespace {

// The geometry both view types share, with the pitches resolved (0: tight).
struct Geometry {
    std::uintptr_t address;
    int width, height, channels;
    std::size_t element, row_pitch, plane_pitch;
    ChannelLayout layout;

    bool interleaved() const { return layout == ChannelLayout::Interleaved && channels > 1; }
    std::size_t row_bytes() const
    {
        return std::size_t(width) * element * (interleaved() ? std::size_t(channels) : 1);
    }
    std::size_t plane_bytes() const { return std::size_t(height - 1) * row_pitch + row_bytes(); }
    // Bytes from the first pixel to just past the last.
    std::size_t span() const
    {
        return interleaved() ? plane_bytes() : std::size_t(channels - 1) * plane_pitch + plane_bytes();
    }
    std::size_t offset(int c, int x, int y) const
    {
        const std::size_t row = std::size_t(y) * row_pitch;
        if (interleaved()) return row + (std::size_t(x) * std::size_t(channels) + std::size_t(c)) * element;
        return std::size_t(c) * plane_pitch + row + std::size_t(x) * element;
    }
};

template <class View>
Geometry geometry(const View& v, std::size_t element)
{
    Geometry g{reinterpret_cast<std::uintptr_t>(v.data), v.width, v.height, v.channels, element,
               v.row_pitch, v.plane_pitch, v.layout};
    if (g.row_pitch == 0 && g.width > 0) g.row_pitch = g.row_bytes();
    if (g.plane_pitch == 0) g.plane_pitch = g.row_pitch * std::size_t(g.height > 0 ? g.height : 0);
    return g;
}

std::size_t element_size(PixelType type) { return type == PixelType::UInt16 ? 2 : 4; }

Geometry checked(const Geometry& g, std::string_view op, std::string_view parameter)
{
    const auto fail = [&](const std::string& message) {
        throw Error(ErrorCategory::InvalidArgument, op, parameter, message);
    };
    const std::string name = "the view '" + std::string(parameter) + "'";
    if (g.width <= 0 || g.height <= 0)
        fail(name + " is " + std::to_string(g.width) + "x" + std::to_string(g.height) +
             "; a view holds at least one pixel");
    // After the size: an empty Image's view has no pixels and no pointer.
    if (g.address == 0) fail(name + " has a null data pointer; pass the address of its first pixel");
    if (g.channels < 1 || g.channels > 16)
        fail(name + " has " + std::to_string(g.channels) + " channels; give 1 to 16");
    if (g.row_pitch < g.row_bytes())
        fail(name + "'s row pitch of " + std::to_string(g.row_pitch) + " bytes is shorter than a row (" +
             std::to_string(g.row_bytes()) + " bytes); give the bytes between the starts of two rows, or 0 for packed rows");
    if (!g.interleaved() && g.channels > 1 && g.plane_pitch < g.plane_bytes())
        fail(name + "'s plane pitch of " + std::to_string(g.plane_pitch) + " bytes is shorter than a plane (" +
             std::to_string(g.plane_bytes()) + " bytes); give the bytes between the starts of two planes, or 0");
    return g;
}

bool in_place(const Geometry& g)
{
    const auto whole_floats = [](std::size_t bytes) { return bytes % 4 == 0 && bytes / 4 <= std::size_t(INT_MAX); };
    return g.element == 4 && !g.interleaved() && g.address % 4 == 0 && whole_floats(g.row_pitch) &&
           whole_floats(g.plane_pitch);
}

// A borrowed Image's arguments from an in-place geometry.
struct Borrowed {
    float* pixels;
    int pitch;
    std::size_t plane_pitch;
};
Borrowed borrowed(const Geometry& g)
{
    return {reinterpret_cast<float*>(g.address), int(g.row_pitch / 4), g.plane_pitch / 4};
}

// Bytes between two pixels of one channel.
std::size_t pixel_step(const Geometry& g)
{
    return g.interleaved() ? std::size_t(g.channels) * g.element : g.element;
}

// One row of one channel into planar floats. A fixed-size memcpy is one
// load, at any alignment; the loops are per element type so that each is
// a plain strided loop (a per-element offset and type branch made a 1080p
// 3-channel copy 3 to 4 times slower: 60-85 ms against 16-22 ms, one run of
// five each at load 8-9 on the shared 2-core Xeon).
void read_row(const std::byte* first, std::size_t step, std::size_t element, int width, float* row)
{
    if (element == 2) {
        for (int x = 0; x < width; ++x) {
            std::uint16_t v;
            std::memcpy(&v, first + std::size_t(x) * step, 2);
            row[x] = float(v) / 65535.0f;  // correctly rounded: the contract (image_view.h)
        }
        return;
    }
    for (int x = 0; x < width; ++x) std::memcpy(row + x, first + std::size_t(x) * step, 4);
}

// Row by row in parallel: a 1080p copy is a pass over tens of megabytes.
template <class PerRow>
void for_rows(const Image& image, PerRow per_row)
{
    const int rows = image.height() * image.channels();
    tbb::parallel_for(tbb::blocked_range<int>(0, rows, 64), [&](const tbb::blocked_range<int>& r) {
        for (int i = r.begin(); i < r.end(); ++i) per_row(i / image.height(), i % image.height());
    });
}

}  // namespace

ImageView::ImageView(const Image& image)
    : data(image.plane(0)), width(image.width()), height(image.height()), channels(image.channels()),
      row_pitch(std::size_t(image.pitch()) * 4), plane_pitch(image.plane_pitch() * 4)
{
}

MutableImageView::MutableImageView(Image& image)
    : data(image.plane(0)), width(image.width()), height(image.height()), channels(image.channels()),
      row_pitch(std::size_t(image.pitch()) * 4), plane_pitch(image.plane_pitch() * 4)
{
}

bool in_place(const ImageView& view) { return in_place(geometry(view, element_size(view.type))); }
bool in_place(const MutableImageView& view) { return in_place(geometry(view, 4)); }

InputImage::InputImage(const ImageView& view, std::string_view operation, std::string_view parameter)
{
    const Geometry g = checked(geometry(view, element_size(view.type)), operation, parameter);
    if (in_place(g)) {
        const Borrowed b = borrowed(g);
        image_ = Image(b.pixels, g.width, g.height, g.channels, b.pitch, b.plane_pitch, Image::Borrow{});
        return;
    }
    image_ = Image(g.width, g.height, g.channels, Image::Uninitialized{});
    const auto* base = static_cast<const std::byte*>(view.data);
    const std::size_t step = pixel_step(g);
    for_rows(image_, [&](int c, int y) { read_row(base + g.offset(c, 0, y), step, g.element, g.width, image_.row(c, y)); });
}

OutputImage::OutputImage(const MutableImageView& view, std::string_view operation, std::string_view parameter)
    : view_(view)
{
    const Geometry g = checked(geometry(view, 4), operation, parameter);
    if (in_place(g)) {
        const Borrowed b = borrowed(g);
        image_ = Image(b.pixels, g.width, g.height, g.channels, b.pitch, b.plane_pitch, Image::Borrow{});
        return;
    }
    image_ = Image(g.width, g.height, g.channels, Image::Uninitialized{});
}

void OutputImage::commit() const
{
    if (image_.borrowed()) return;
    const Geometry g = geometry(view_, 4);
    auto* base = static_cast<std::byte*>(view_.data);
    const std::size_t step = pixel_step(g);
    for_rows(image_, [&](int c, int y) {
        const float* row = image_.row(c, y);
        std::byte* first = base + g.offset(c, 0, y);
        for (int x = 0; x < g.width; ++x) std::memcpy(first + std::size_t(x) * step, row + x, 4);
    });
}

void require_disjoint(const ImageView& input, const MutableImageView& output, std::string_view operation,
                      std::string_view output_parameter)
{
    const Geometry in = geometry(input, element_size(input.type)), out = geometry(output, 4);
    const bool overlap = in.address < out.address + out.span() && out.address < in.address + in.span();
    require(!overlap, operation, output_parameter,
            "the output view '" + std::string(output_parameter) +
                "' overlaps an input's memory; the operation cannot run in place: write into another buffer");
}

}  // namespace penumbra
