#include "penumbra/image.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>

#include <sys/mman.h>

#include "penumbra/error.h"

namespace penumbra {

int padded_pitch(int width)
{
    // One element beyond the width is always kept: the summed-area tables use
    // the last padding element of a row as their zero column (see moment_table.h).
    return (width / kPitchQuantum + 1) * kPitchQuantum;
}

void AlignedBuffer::Free::operator()(std::byte* p) const noexcept { std::free(p); }

// Buffers of several megabytes (tables, 4096^2 images) are aligned to 2 MiB
// and offered to the kernel as transparent huge pages: a fresh 128 MiB table
// then takes 64 page faults instead of 32768 (Linux; elsewhere a no-op).
constexpr std::size_t kHugePage = std::size_t(2) << 20;

AlignedBuffer::AlignedBuffer(std::size_t bytes, Uninitialized) : size_(bytes)
{
    if (bytes == 0) return;
    const bool huge = bytes >= 4 * kHugePage;
    const std::size_t alignment = huge ? kHugePage : kAlignment;
    const std::size_t rounded = (bytes + alignment - 1) / alignment * alignment;
    auto* p = static_cast<std::byte*>(std::aligned_alloc(alignment, rounded));
    if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    if (huge) madvise(p, rounded, MADV_HUGEPAGE);
#endif
    data_.reset(p);
}

AlignedBuffer::AlignedBuffer(std::size_t bytes) : AlignedBuffer(bytes, Uninitialized{})
{
    if (bytes) std::memset(data_.get(), 0, (bytes + kAlignment - 1) / kAlignment * kAlignment);
}

AlignedBuffer::AlignedBuffer(const AlignedBuffer& other) : AlignedBuffer(other.size_)
{
    if (size_) std::memcpy(data_.get(), other.data_.get(), size_);
}

AlignedBuffer& AlignedBuffer::operator=(const AlignedBuffer& other)
{
    if (this != &other) *this = AlignedBuffer(other);
    return *this;
}

Image::Image(int width, int height, int channels) : Image(width, height, channels, Uninitialized{})
{
    // zero_padding has faulted the pages in, on every thread; the pixels now.
    if (storage_.size()) std::memset(storage_.data(), 0, storage_.size());
}

Image::Image(int width, int height, int channels, Uninitialized)
{
    require(width >= 0 && height >= 0, "Image",
            "width and height must be non-negative (got " + std::to_string(width) + "x" +
                std::to_string(height) + ")");
    require(channels >= 1 && channels <= 16, "Image",
            "channel count must be in [1, 16] (got " + std::to_string(channels) + ")");
    width_ = width;
    height_ = height;
    channels_ = channels;
    pitch_ = padded_pitch(width);
    plane_pitch_ = std::size_t(pitch_) * std::size_t(height);
    storage_ = AlignedBuffer(plane_pitch_ * std::size_t(channels) * sizeof(float), Uninitialized{});
    zero_padding();
}

Image::Image(float* pixels, int width, int height, int channels, int pitch, std::size_t plane_pitch, Borrow)
    : width_(width), height_(height), channels_(channels), pitch_(pitch), plane_pitch_(plane_pitch), borrowed_(pixels)
{
}

// A borrowed image's copy takes its pixels row by row: the caller's memory
// may end at the last pixel, and its padding is the caller's business.
Image::Image(const Image& other)
    : width_(other.width_), height_(other.height_), channels_(other.channels_), pitch_(other.pitch_),
      plane_pitch_(other.plane_pitch_),
      storage_(other.borrowed_ ? AlignedBuffer(plane_pitch_ * std::size_t(channels_) * sizeof(float))
                               : other.storage_)
{
    if (!other.borrowed_) return;
    for (int c = 0; c < channels_; ++c)
        for (int y = 0; y < height_; ++y) std::copy_n(other.row(c, y), width_, row(c, y));
}

Image& Image::operator=(const Image& other)
{
    if (this != &other) *this = Image(other);
    return *this;
}

std::size_t Image::extent() const noexcept
{
    if (empty()) return 0;
    return plane_pitch_ * std::size_t(channels_ - 1) + std::size_t(pitch_) * std::size_t(height_ - 1) +
           std::size_t(width_);
}

// No byte of an image is left indeterminate: the writer fills the pixels, this
// the columns past the width (copies and OpenCL's host buffers move them too).
// In parallel, because touching a row's end faults its fresh pages in: on one
// thread, that would serialise the cost the uninitialised storage saves.
void Image::zero_padding()
{
    const int padding = pitch_ - width_;
    const std::size_t rows = std::size_t(height_) * std::size_t(channels_);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, 256), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t row = r.begin(); row < r.end(); ++row)
            std::memset(plane(0) + row * std::size_t(pitch_) + std::size_t(width_), 0, std::size_t(padding) * sizeof(float));
    });
}

float* Image::plane(int c) noexcept { return base() + plane_pitch_ * std::size_t(c); }

const float* Image::plane(int c) const noexcept { return base() + plane_pitch_ * std::size_t(c); }

void Image::fill(int c, float value)
{
    for (int y = 0; y < height_; ++y) std::fill_n(row(c, y), width_, value);
}

bool channel_within(const Image& image, int c, float lo, float hi)
{
    return tbb::parallel_reduce(
        tbb::blocked_range<int>(0, image.height(), 64), true,
        [&](const tbb::blocked_range<int>& rows, bool ok) {
            const int width = image.width();
            for (int y = rows.begin(); y < rows.end() && ok; ++y) {
                const float* r = image.row(c, y);
                int outside = 0;  // branch-free so that the compiler vectorises it
                for (int x = 0; x < width; ++x) outside |= int(!(r[x] >= lo)) | int(!(r[x] <= hi));
                ok = outside == 0;
            }
            return ok;
        },
        [](bool a, bool b) { return a && b; });
}

NonFinite find_non_finite(const Image& image)
{
    bool all_finite = true;
    for (int c = 0; c < image.channels(); ++c)
        all_finite = all_finite && channel_within(image, c, -FLT_MAX, FLT_MAX);
    if (all_finite) return {};
    for (int c = 0; c < image.channels(); ++c)
        for (int y = 0; y < image.height(); ++y) {
            const float* r = image.row(c, y);
            for (int x = 0; x < image.width(); ++x)
                if (!std::isfinite(r[x])) return {true, c, x, y, r[x]};
        }
    return {};
}

void require_finite(const Image& image, const std::string& operation, const std::string& what,
                    const std::string& parameter)
{
    const NonFinite bad = find_non_finite(image);
    if (!bad.found) return;
    throw Error(ErrorCategory::InvalidData, operation, parameter,
                what + " has a non-finite value (" + std::to_string(bad.value) + ") in channel " +
                    std::to_string(bad.channel) + " at pixel (" + std::to_string(bad.x) + ", " +
                    std::to_string(bad.y) + "); replace NaN/infinite values before filtering",
                BadPixel{bad.channel, bad.x, bad.y, bad.value});
}

void require_unit_depths(const Image& depth, const std::string& operation)
{
    // One parallel, vectorised pass for the common case (NaN fails it too);
    // only a bad map pays the slow passes that find and name the first value.
    if (depth.channels() == 1 && channel_within(depth, 0, 0.0f, 1.0f)) return;
    require_finite(depth, operation, "the shadow map", "depth");
    for (int y = 0; y < depth.height(); ++y) {
        const float* row = depth.row(0, y);
        for (int x = 0; x < depth.width(); ++x)
            if (row[x] < 0.0f || row[x] > 1.0f)
                throw Error(ErrorCategory::InvalidData, operation, "depth",
                            "shadow-map depth " + std::to_string(row[x]) + " at (" + std::to_string(x) + ", " +
                                std::to_string(y) +
                                ") is outside [0, 1]; store linear light depth normalised to [0, 1]",
                            BadPixel{0, x, y, row[x]});
    }
}

}  // namespace penumbra
