// Views of a caller's memory: a renderer's depth buffer, G-buffer or mask
// (pointer, size, row pitch in bytes), read and written where it lies.
//
// The kernels read planar float rows with a pitch (DESIGN.md, "Data"; pn_dims,
// kernels/params.h): a view laid out so, at any pitch, is read in place. A
// view the kernels cannot read as it is (channels interleaved, 16-bit depth,
// a pitch or pointer that is no whole number of floats) costs one copy into a
// planar float Image, on input, and one copy back, on output
// (docs/integration.md has the table). InputImage and OutputImage make that
// choice for every operation that takes views (Method::prepare_view and
// shade_view, penumbra/methods.h; the view cross_bilateral,
// penumbra/bilateral.h) and for a caller who wants a view in any other
// Image-taking operation.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "penumbra/image.h"

namespace penumbra {

enum class PixelType {
    Float32,
    UInt16,  // unsigned normalised: value / 65535 (a D16 depth buffer); inputs only
};

enum class ChannelLayout {
    Planar,       // channel c of pixel (x, y) at data + c plane_pitch + y row_pitch + x size
    Interleaved,  // at data + y row_pitch + (x channels + c) size
};

// What the caller's memory holds: `row_pitch` bytes between the starts of two
// rows, and for planar views `plane_pitch` bytes between the starts of two
// planes (0: height x row_pitch). Nothing past the last pixel of the last row
// is read or written. The memory must outlive the call (and a PreparedMap
// made from it, which refers to it).
struct ImageView {
    const void* data = nullptr;
    int width = 0, height = 0, channels = 1;
    std::size_t row_pitch = 0;
    std::size_t plane_pitch = 0;
    ChannelLayout layout = ChannelLayout::Planar;
    PixelType type = PixelType::Float32;

    ImageView() = default;
    ImageView(const Image& image);  // NOLINT: an Image is a view of itself, read in place
};

// An output: float32 only (visibility and blurred masks are floats).
struct MutableImageView {
    void* data = nullptr;
    int width = 0, height = 0, channels = 1;
    std::size_t row_pitch = 0;
    std::size_t plane_pitch = 0;
    ChannelLayout layout = ChannelLayout::Planar;

    MutableImageView() = default;
    MutableImageView(Image& image);  // NOLINT: written in place
};

// True when the kernels read (or write) the view where it lies: float32,
// planar or one channel, pointer and pitches whole floats, pitches within the
// kernels' int range.
bool in_place(const ImageView& view);
bool in_place(const MutableImageView& view);

// An input view as the Image the operations read: the caller's memory itself
// when in_place(view), else one planar float copy (16-bit values / 65535).
// Throws Error(InvalidArgument, `operation`, `parameter`) for a null pointer,
// a zero or negative size, a channel count outside [1, 16], a row pitch
// shorter than a row or a plane pitch shorter than a plane.
class InputImage {
public:
    InputImage(const ImageView& view, std::string_view operation, std::string_view parameter);
    const Image& image() const noexcept { return image_; }
    bool copied() const noexcept { return !image_.borrowed(); }

private:
    Image image_;
};

// An output view as the Image an operation writes: the caller's memory
// itself when in_place(view), else a planar image that commit() copies into
// the view (nothing reaches the view before commit()). The same checks as
// InputImage; the operation checks the size against its inputs.
class OutputImage {
public:
    OutputImage(const MutableImageView& view, std::string_view operation, std::string_view parameter);
    Image& image() noexcept { return image_; }
    bool copied() const noexcept { return !image_.borrowed(); }
    void commit() const;

private:
    MutableImageView view_;
    Image image_;
};

// Throws Error(InvalidArgument, `operation`, `output_parameter`) when the
// bytes of `output` overlap those of `input`: the kernels read their inputs
// while they write, so an operation cannot run in place.
void require_disjoint(const ImageView& input, const MutableImageView& output, std::string_view operation,
                      std::string_view output_parameter);

}  // namespace penumbra
