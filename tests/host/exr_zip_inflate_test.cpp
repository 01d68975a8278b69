// read_exr's ZIP and ZIPS chunks go through libdeflate (host/src/exr_zip_inflate.cpp):
// the pixels must be those OpenEXR's own writer stored, for compressible data,
// for random bits (chunks the writer stores raw) and for odd widths; a chunk
// whose deflate stream is damaged is Error(Io), never wrong pixels.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/exr_io.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

fs::path scratch_path(const std::string& name)
{
    const fs::path dir = fs::temp_directory_path() / ("penumbra-zip-inflate-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

// Writes one float channel "Z" with OpenEXR's writer.
void write_plane(const fs::path& file, Imf::Compression compression, int width, int height,
                 const std::vector<float>& pixels)
{
    const Imath::Box2i window({0, 0}, {width - 1, height - 1});
    Imf::Header header(window, window);
    header.compression() = compression;
    header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile out(file.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(pixels.data())), 4,
                                 4 * std::size_t(width)));
    out.setFrameBuffer(frame);
    out.writePixels(height);
}

std::vector<float> test_pixels(int width, int height, bool random_bits)
{
    std::mt19937 rng(std::uint32_t(width * 131 + height));
    std::vector<float> pixels(std::size_t(width) * height);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        if (!random_bits) {
            pixels[i] = float(i % 97) * 0.01f;
            continue;
        }
        std::uint32_t bits = rng() & 0x3fffffffu;  // finite: exponent below 0xff
        std::memcpy(&pixels[i], &bits, 4);
    }
    return pixels;
}

TEST(ExrZipInflate, ReadsWhatOpenExrWrote)
{
    for (const Imf::Compression c : {Imf::ZIP_COMPRESSION, Imf::ZIPS_COMPRESSION})
        for (const bool random_bits : {false, true})
            for (const auto& [width, height] : {std::pair{1, 1}, {7, 3}, {17, 40}, {333, 35}}) {
                const std::vector<float> pixels = test_pixels(width, height, random_bits);
                const fs::path file = scratch_path("plane.exr");
                write_plane(file, c, width, height, pixels);
                const Image image = read_exr(file.string(), {"Z"});
                ASSERT_EQ(image.width(), width);
                ASSERT_EQ(image.height(), height);
                for (int y = 0; y < height; ++y)
                    for (int x = 0; x < width; ++x)
                        ASSERT_EQ(image.at(0, x, y), pixels[std::size_t(y) * width + x])
                            << "compression " << int(c) << (random_bits ? " random" : " smooth") << " " << width
                            << "x" << height << " at " << x << "," << y;
                fs::remove(file);
            }
}

TEST(ExrZipInflate, ADamagedStreamIsAnIoError)
{
    const int width = 64, height = 16;  // one ZIP chunk of 16 lines
    const fs::path file = scratch_path("damaged.exr");
    write_plane(file, Imf::ZIP_COMPRESSION, width, height, test_pixels(width, height, false));
    std::vector<char> bytes(fs::file_size(file));
    std::ifstream(file, std::ios::binary).read(bytes.data(), std::streamsize(bytes.size()));
    // The chunk is the file's tail; damage the middle of its deflate stream.
    for (std::size_t i = bytes.size() - 24; i < bytes.size() - 16; ++i) bytes[i] = char(bytes[i] ^ 0x5a);
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
    try {
        read_exr(file.string(), {"Z"});
        FAIL() << "a damaged deflate stream was read";
    } catch (const Error& e) {
        EXPECT_EQ(e.category(), ErrorCategory::Io) << e.what();
    }
    fs::remove(file);
}

}  // namespace
}  // namespace penumbra
