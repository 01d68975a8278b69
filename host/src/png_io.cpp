// PNG container written by hand (PNG specification, ISO/IEC 15948:2004): the
// signature, then IHDR, IDAT and IEND chunks, each as length, type, data and a
// CRC-32 of type and data. zlib supplies the deflate stream (compress2 makes the
// zlib-wrapped stream PNG wants) and the CRC. Only 8-bit grey and RGB, not
// interlaced: all a preview needs.
#include "penumbra/png_io.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <system_error>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/exr_io.h"  // detail::write_file_atomically

namespace penumbra {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr std::array<std::uint8_t, 8> kSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr std::uint8_t kColourTypeGrey = 0, kColourTypeRgb = 2;
constexpr std::uint8_t kFilterNone = 0;
// PNG allows chunks of up to 2^31-1 bytes and decoders concatenate consecutive
// IDAT chunks, so splitting the stream keeps any image size legal.
constexpr std::size_t kMaxIdatChunk = std::size_t(1) << 20;

// ---------------------------------------------------------------- values

std::string pixel_name(int c, int x, int y)
{
    return "channel " + std::to_string(c) + " at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
           ")";
}

// NaN is refused rather than drawn: it has no place on a clamped scale, and a
// preview that hides one would hide a bug. Infinities clamp like any value.
void require_no_nan(const Image& image, std::string_view operation, const std::string& what)
{
    for (int c = 0; c < image.channels(); ++c)
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
                if (std::isnan(image.at(c, x, y)))
                    throw Error(ErrorCategory::InvalidData, operation,
                                what + " has a NaN in " + pixel_name(c, x, y) +
                                    "; fix or replace NaNs first");
}

// The sRGB transfer function (IEC 61966-2-1), linear light to encoded value.
float srgb_encode(float linear)
{
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t to_code(float value, PngTransfer transfer)
{
    float v = std::clamp(value, 0.0f, 1.0f);
    if (transfer == PngTransfer::Srgb) v = srgb_encode(v);
    return std::uint8_t(std::lround(v * 255.0f));
}

// ---------------------------------------------------------------- container

void append_u32(Bytes& out, std::uint32_t value)  // PNG integers are big-endian
{
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(value >> shift));
}

void append_chunk(Bytes& png, const char (&type)[5], const std::uint8_t* data, std::size_t size)
{
    append_u32(png, std::uint32_t(size));
    const std::size_t type_start = png.size();
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), data, data + size);
    // The CRC covers the chunk type and data, not the length.
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), png.data() + type_start, uInt(4 + size));
    append_u32(png, std::uint32_t(crc));
}

Bytes image_header(const Image& image)
{
    Bytes header;
    append_u32(header, std::uint32_t(image.width()));
    append_u32(header, std::uint32_t(image.height()));
    const std::uint8_t colour_type = image.channels() == 1 ? kColourTypeGrey : kColourTypeRgb;
    // bit depth, colour type, compression (deflate), filter method, interlace (none)
    header.insert(header.end(), {8, colour_type, 0, 0, 0});
    return header;
}

// Every row gets filter type None. The adaptive filters (Sub, Up, Paeth) would
// make smaller files, which previews of a few hundred kilobytes do not need.
Bytes filtered_scanlines(const Image& image, PngTransfer transfer)
{
    const std::size_t row_bytes = 1 + std::size_t(image.width()) * std::size_t(image.channels());
    Bytes scanlines(row_bytes * std::size_t(image.height()));
    for (int y = 0; y < image.height(); ++y) {
        std::uint8_t* out = scanlines.data() + std::size_t(y) * row_bytes;
        *out++ = kFilterNone;
        for (int x = 0; x < image.width(); ++x)
            for (int c = 0; c < image.channels(); ++c) *out++ = to_code(image.at(c, x, y), transfer);
    }
    return scanlines;
}

Bytes zlib_compressed(const Bytes& raw)
{
    uLongf size = compressBound(uLong(raw.size()));
    Bytes compressed(size);
    const int status =
        compress2(compressed.data(), &size, raw.data(), uLong(raw.size()), Z_DEFAULT_COMPRESSION);
    if (status == Z_MEM_ERROR) throw std::bad_alloc();
    // compressBound sized the buffer, so any other failure is a broken zlib.
    if (status != Z_OK)
        throw Error(ErrorCategory::Backend, "write_png",
                    "zlib compress2 failed with status " + std::to_string(status));
    compressed.resize(size);
    return compressed;
}

Bytes encode_png(const Image& image, PngTransfer transfer)
{
    Bytes png(kSignature.begin(), kSignature.end());
    const Bytes header = image_header(image);
    append_chunk(png, "IHDR", header.data(), header.size());
    const Bytes stream = zlib_compressed(filtered_scanlines(image, transfer));
    for (std::size_t start = 0; start < stream.size(); start += kMaxIdatChunk)
        append_chunk(png, "IDAT", stream.data() + start, std::min(kMaxIdatChunk, stream.size() - start));
    append_chunk(png, "IEND", nullptr, 0);
    return png;
}

// stdio rather than a stream, for an errno that says why a write failed.
void write_bytes(const std::string& path, const Bytes& bytes)
{
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) throw std::system_error(errno, std::generic_category(), "opening " + path);
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    const int write_error = errno;
    const bool closed = std::fclose(file) == 0;
    if (!written) throw std::system_error(write_error, std::generic_category(), "writing " + path);
    if (!closed) throw std::system_error(errno, std::generic_category(), "closing " + path);
}

}  // namespace

void write_png(const std::string& path, const Image& image, PngTransfer transfer)
{
    constexpr std::string_view operation = "write_png";
    const std::string what = "the image for '" + path + "'";
    require(image.channels() == 1 || image.channels() == 3, operation,
            what + " has " + std::to_string(image.channels()) +
                " channels; PNG previews take 1 (grey) or 3 (RGB), so pick the channels to show first");
    require(!image.empty(), operation,
            what + " is empty (" + std::to_string(image.width()) + "x" + std::to_string(image.height()) +
                "); a PNG needs at least one pixel");
    require_no_nan(image, operation, what);

    const Bytes png = encode_png(image, transfer);
    detail::write_file_atomically(path, operation,
                                  [&](const std::string& temporary) { write_bytes(temporary, png); });
}

Image colormap_error(const Image& signed_error, float max_abs)
{
    constexpr std::string_view operation = "colormap_error";
    require(signed_error.channels() == 1, operation,
            "the error image has " + std::to_string(signed_error.channels()) +
                " channels; pass one channel of signed error (estimate minus truth)");
    require(std::isfinite(max_abs) && max_abs > 0, operation,
            "max_abs must be finite and > 0 (got " + (std::ostringstream() << max_abs).str() +
                "); pass the error magnitude that should saturate the colours");
    require_no_nan(signed_error, operation, "the error image");

    Image heatmap(signed_error.width(), signed_error.height(), 3);
    for (int y = 0; y < heatmap.height(); ++y)
        for (int x = 0; x < heatmap.width(); ++x) {
            const float t = std::clamp(signed_error.at(0, x, y) / max_abs, -1.0f, 1.0f);
            // From white, fade the two primaries the end colour lacks: green
            // always, red towards blue (t < 0), blue towards red (t > 0).
            const float fade = 1.0f - std::abs(t);
            heatmap.at(0, x, y) = t < 0 ? fade : 1.0f;
            heatmap.at(1, x, y) = fade;
            heatmap.at(2, x, y) = t > 0 ? fade : 1.0f;
        }
    return heatmap;
}

}  // namespace penumbra
