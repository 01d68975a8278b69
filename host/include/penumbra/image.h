// Planar float images with a padded row pitch.
//
// Layout (DESIGN.md, "Data"): one plane per channel, planes one after another;
// each row starts on a 64-byte boundary (the row pitch is a multiple of 16
// floats), so that a SIMD strip load never straddles a cache line more than it
// must and a kernel never needs to read past a row's end: the padding is there
// but kernels mask instead of relying on it. Pixel (x, y) of channel c is
// plane(c)[y * pitch() + x].
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace penumbra {

inline constexpr std::size_t kAlignment = 64;        // bytes: one cache line, one AVX-512 register
inline constexpr int kPitchQuantum = kAlignment / 4;  // 4-byte elements per alignment unit

// Rounds a row length in 4-byte elements up to a whole number of cache lines.
int padded_pitch(int width);

// An owned, 64-byte aligned, zero-initialised block of bytes.
class AlignedBuffer {
public:
    AlignedBuffer() = default;
    explicit AlignedBuffer(std::size_t bytes);
    // Not zero-filled: for storage a kernel writes in full. Zero-filling a
    // fresh 128 MiB table serially cost more than building it (its page
    // faults then all land on one thread; left to the kernel, they spread).
    struct Uninitialized {};
    AlignedBuffer(std::size_t bytes, Uninitialized);
    // Copies are deep: images are values.
    AlignedBuffer(const AlignedBuffer& other);
    AlignedBuffer& operator=(const AlignedBuffer& other);
    AlignedBuffer(AlignedBuffer&&) noexcept = default;
    AlignedBuffer& operator=(AlignedBuffer&&) noexcept = default;

    std::byte* data() noexcept { return data_.get(); }
    const std::byte* data() const noexcept { return data_.get(); }
    std::size_t size() const noexcept { return size_; }

private:
    struct Free {
        void operator()(std::byte* p) const noexcept;
    };
    std::unique_ptr<std::byte, Free> data_;
    std::size_t size_ = 0;
};

class Image {
public:
    Image() = default;
    // Zero-filled image. Throws Error(InvalidArgument) for negative sizes or a
    // channel count outside [1, 16].
    Image(int width, int height, int channels);
    // The same, but only the row padding is zeroed: for an image a kernel or a
    // decoder writes in full (every pixel of every channel) before anyone reads
    // it. Zero-filling first cost a pass over the pages (issue 10: 22% of a
    // `shade` run went to zeroing fresh pages, then once more to the kernel's
    // writes); left to the writer, the first touch is the only one.
    using Uninitialized = AlignedBuffer::Uninitialized;
    Image(int width, int height, int channels, Uninitialized);
    // Copies are deep and own their pixels, a borrowed image's too (with the
    // same pitches).
    Image(const Image& other);
    Image& operator=(const Image& other);
    Image(Image&&) noexcept = default;
    Image& operator=(Image&&) noexcept = default;

    int width() const noexcept { return width_; }
    int height() const noexcept { return height_; }
    int channels() const noexcept { return channels_; }
    bool empty() const noexcept { return width_ == 0 || height_ == 0; }
    // Elements (not bytes) between the starts of two rows, and of two planes.
    int pitch() const noexcept { return pitch_; }
    std::size_t plane_pitch() const noexcept { return plane_pitch_; }
    // Elements from plane(0) to just past the last pixel of the last plane:
    // what a backend may wrap or copy (a borrowed image's memory may end there).
    std::size_t extent() const noexcept;
    // True when the pixels are a caller's memory (penumbra/image_view.h).
    bool borrowed() const noexcept { return borrowed_ != nullptr; }

    float* plane(int c) noexcept;
    const float* plane(int c) const noexcept;
    float* row(int c, int y) noexcept { return plane(c) + std::size_t(y) * pitch_; }
    const float* row(int c, int y) const noexcept { return plane(c) + std::size_t(y) * pitch_; }
    float& at(int c, int x, int y) noexcept { return row(c, y)[x]; }
    float at(int c, int x, int y) const noexcept { return row(c, y)[x]; }

    void fill(int c, float value);

private:
    friend class InputImage;
    friend class OutputImage;
    // Borrows `pixels`: planes `plane_pitch` elements apart, rows `pitch` apart
    // (the views' checks ran before).
    struct Borrow {};
    Image(float* pixels, int width, int height, int channels, int pitch, std::size_t plane_pitch, Borrow);

    void zero_padding();
    float* base() noexcept { return borrowed_ ? borrowed_ : reinterpret_cast<float*>(storage_.data()); }
    const float* base() const noexcept
    {
        return borrowed_ ? borrowed_ : reinterpret_cast<const float*>(storage_.data());
    }

    int width_ = 0, height_ = 0, channels_ = 0, pitch_ = 0;
    std::size_t plane_pitch_ = 0;
    AlignedBuffer storage_;
    float* borrowed_ = nullptr;  // the caller's pixels, when borrowed; storage_ is then empty
};

// True if every pixel of channel c lies in [lo, hi]; NaN never does. A fast,
// vectorised and parallel pass, so that validation costs little next to the
// kernels it guards.
bool channel_within(const Image& image, int c, float lo, float hi);

// Where the first non-finite value of an image is, for error messages.
struct NonFinite {
    bool found = false;
    int channel = 0, x = 0, y = 0;
    float value = 0;
};
NonFinite find_non_finite(const Image& image);

// Throws Error(InvalidData) naming `what` (e.g. "shadow map") and the first
// offending pixel if any value is NaN or infinite; the error's parameter() is
// `parameter` and its pixel() the value.
void require_finite(const Image& image, const std::string& operation, const std::string& what,
                    const std::string& parameter = {});
// The same for a depth map (parameter "depth"), and then for the first depth
// outside [0, 1]. For the report after a kernel flagged a row: it scans.
void require_unit_depths(const Image& depth, const std::string& operation);

}  // namespace penumbra
