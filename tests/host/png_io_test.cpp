// write_png and colormap_error. The PNG is decoded here independently of the
// writer: chunks walked by hand, CRCs recomputed, the IDAT stream inflated with
// zlib's uncompress and compared with the expected scanlines byte for byte.
#include "penumbra/png_io.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <vector>

#include "penumbra/error.h"
#include "support/cli.h"
#include "support/errors.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

using testing::error_from;
using testing::mentions;

Bytes bytes_of(const fs::path& path)
{
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), {}};
}

std::uint32_t big_endian_u32(const std::uint8_t* p)
{
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}

struct Chunk {
    std::string type;
    Bytes data;
    bool crc_valid = false;
};

// Walks the chunks after the signature; a malformed file yields a short list,
// which the tests' expectations on the list then report.
std::vector<Chunk> chunks_of(const Bytes& png)
{
    static const Bytes signature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    EXPECT_TRUE(png.size() >= 8 && Bytes(png.begin(), png.begin() + 8) == signature);
    std::vector<Chunk> chunks;
    std::size_t at = 8;
    while (at + 12 <= png.size()) {
        const std::uint32_t length = big_endian_u32(&png[at]);
        if (at + 12 + length > png.size()) break;
        const std::uint8_t* type = &png[at + 4];
        Chunk chunk{std::string(type, type + 4), Bytes(type + 4, type + 4 + length)};
        const uLong crc = crc32(crc32(0L, Z_NULL, 0), type, 4 + length);
        chunk.crc_valid = crc == big_endian_u32(type + 4 + length);
        chunks.push_back(std::move(chunk));
        at += 12 + length;
    }
    EXPECT_EQ(at, png.size()) << "bytes after the last whole chunk";
    return chunks;
}

Bytes inflated_idat(const std::vector<Chunk>& chunks, std::size_t expected_size)
{
    Bytes stream;
    for (const Chunk& chunk : chunks)
        if (chunk.type == "IDAT") stream.insert(stream.end(), chunk.data.begin(), chunk.data.end());
    Bytes raw(expected_size + 16);  // room to notice a stream that is too long
    uLongf size = raw.size();
    EXPECT_EQ(uncompress(raw.data(), &size, stream.data(), stream.size()), Z_OK);
    raw.resize(size);
    return raw;
}

void expect_well_formed(const std::vector<Chunk>& chunks)
{
    ASSERT_GE(chunks.size(), 3u);
    EXPECT_EQ(chunks.front().type, "IHDR");
    EXPECT_EQ(chunks.back().type, "IEND");
    EXPECT_TRUE(chunks.back().data.empty());
    for (const Chunk& chunk : chunks) EXPECT_TRUE(chunk.crc_valid) << chunk.type;
}

// A fresh scratch folder per test (support/cli.h).
class PngIoTest : public testing::CliFixture {};

TEST_F(PngIoTest, RgbImageDecodesToTheExpectedScanlines)
{
    Image image(3, 2, 3);
    Bytes expected;
    for (int y = 0; y < 2; ++y) {
        expected.push_back(0);  // filter type None
        for (int x = 0; x < 3; ++x)
            for (int c = 0; c < 3; ++c) {
                const int code = 10 + 40 * x + 100 * y + 3 * c;
                image.at(c, x, y) = float(code) / 255.0f;
                expected.push_back(std::uint8_t(code));
            }
    }
    // Out of range values clamp.
    image.at(0, 0, 0) = -0.5f;
    expected[1] = 0;
    image.at(2, 2, 1) = 7.0f;
    expected.back() = 255;

    write_png(path("rgb.png"), image, PngTransfer::None);
    const std::vector<Chunk> chunks = chunks_of(bytes_of(path("rgb.png")));
    expect_well_formed(chunks);
    EXPECT_EQ(chunks.front().data, (Bytes{0, 0, 0, 3, 0, 0, 0, 2, 8, 2, 0, 0, 0}));  // 3x2, 8-bit RGB
    EXPECT_EQ(inflated_idat(chunks, expected.size()), expected);
}

TEST_F(PngIoTest, GreyImageIsSrgbEncoded)
{
    Image image(5, 1, 1);
    const float values[] = {0.0f, 0.001f, 0.5f, 1.0f, std::numeric_limits<float>::infinity()};
    for (int x = 0; x < 5; ++x) image.at(0, x, 0) = values[x];

    write_png(path("grey.png"), image);
    const std::vector<Chunk> chunks = chunks_of(bytes_of(path("grey.png")));
    expect_well_formed(chunks);
    EXPECT_EQ(chunks.front().data, (Bytes{0, 0, 0, 5, 0, 0, 0, 1, 8, 0, 0, 0, 0}));  // 5x1, 8-bit grey
    // 0.001 is on the linear segment: 12.92 * 0.001 * 255 = 3.29; 0.5 encodes
    // to 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354, and 0.7354 * 255 = 187.5.
    EXPECT_EQ(inflated_idat(chunks, 6), (Bytes{0, 0, 3, 188, 255, 255}));
}

// Noise does not compress, so 1.3 MB of it needs more than one 1 MiB IDAT chunk.
TEST_F(PngIoTest, LargeImageSpansSeveralIdatChunks)
{
    Image image(700, 600, 3);
    Bytes expected;
    std::uint32_t state = 12345;
    for (int y = 0; y < image.height(); ++y) {
        expected.push_back(0);
        for (int x = 0; x < image.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                state = state * 1664525u + 1013904223u;  // LCG (Numerical Recipes)
                const std::uint8_t code = std::uint8_t(state >> 24);
                image.at(c, x, y) = float(code) / 255.0f;
                expected.push_back(code);
            }
    }
    write_png(path("noise.png"), image, PngTransfer::None);
    const std::vector<Chunk> chunks = chunks_of(bytes_of(path("noise.png")));
    expect_well_formed(chunks);
    EXPECT_GE(std::count_if(chunks.begin(), chunks.end(), [](const Chunk& c) { return c.type == "IDAT"; }),
              2);
    EXPECT_TRUE(inflated_idat(chunks, expected.size()) == expected);
}

TEST_F(PngIoTest, HeatmapColoursAtTheEndsAndAtZero)
{
    const float max_abs = 0.25f;
    const float errors[] = {
        -max_abs, 0.0f, max_abs, -0.125f, -1.0f, 1e30f, -std::numeric_limits<float>::infinity()};
    Image error(7, 1, 1);
    for (int x = 0; x < 7; ++x) error.at(0, x, 0) = errors[x];

    const Image heatmap = colormap_error(error, max_abs);
    ASSERT_EQ(heatmap.channels(), 3);
    const float expected[7][3] = {{0, 0, 1}, {1, 1, 1}, {1, 0, 0}, {0.5f, 0.5f, 1},
                                  {0, 0, 1}, {1, 0, 0}, {0, 0, 1}};
    for (int x = 0; x < 7; ++x)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(heatmap.at(c, x, 0), expected[x][c]) << "error " << errors[x];

    write_png(path("heat.png"), heatmap, PngTransfer::None);
    const Bytes raw = inflated_idat(chunks_of(bytes_of(path("heat.png"))), 22);
    EXPECT_EQ(Bytes(raw.begin(), raw.begin() + 10), (Bytes{0, 0, 0, 255, 255, 255, 255, 255, 0, 0}));
}

TEST_F(PngIoTest, HeatmapRejectsBadArguments)
{
    const Image error(2, 2, 1);
    for (const float max_abs : {0.0f, -1.0f, std::numeric_limits<float>::infinity(), std::nanf("")}) {
        const auto failure = error_from([&] { colormap_error(error, max_abs); });
        ASSERT_TRUE(failure) << max_abs;
        EXPECT_EQ(failure->category(), ErrorCategory::InvalidArgument);
    }
    const auto three_channels = error_from([] { colormap_error(Image(2, 2, 3), 1.0f); });
    ASSERT_TRUE(three_channels);
    EXPECT_EQ(three_channels->category(), ErrorCategory::InvalidArgument);

    Image with_nan(2, 2, 1);
    with_nan.at(0, 1, 0) = std::nanf("");
    const auto nan = error_from([&] { colormap_error(with_nan, 1.0f); });
    ASSERT_TRUE(nan);
    EXPECT_EQ(nan->category(), ErrorCategory::InvalidData);
    EXPECT_TRUE(mentions(*nan, "(1, 0)")) << nan->what();
}

TEST_F(PngIoTest, UnsupportedImagesAreRefusedAndTheTargetKept)
{
    std::ofstream(path("keep.png")) << "previous contents";
    Image with_nan(2, 2, 3);
    with_nan.at(1, 0, 1) = std::nanf("");
    const std::pair<Image, ErrorCategory> cases[] = {{Image(2, 2, 2), ErrorCategory::InvalidArgument},
                                                     {Image(0, 2, 1), ErrorCategory::InvalidArgument},
                                                     {std::move(with_nan), ErrorCategory::InvalidData}};
    for (const auto& bad : cases) {  // not a structured binding: clang before 16 cannot capture one
        const auto error = error_from([&] { write_png(path("keep.png"), bad.first); });
        ASSERT_TRUE(error);
        EXPECT_EQ(error->category(), bad.second) << error->what();
        EXPECT_TRUE(mentions(*error, path("keep.png"))) << error->what();
    }
    const Bytes kept = bytes_of(path("keep.png"));
    EXPECT_EQ(std::string(kept.begin(), kept.end()), "previous contents");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(PngIoTest, WriteIntoMissingDirectoryIsAnIoError)
{
    const std::string target = path("no-such-directory/a.png");
    const auto error = error_from([&] { write_png(target, Image(2, 2, 1)); });
    ASSERT_TRUE(error);
    EXPECT_EQ(error->category(), ErrorCategory::Io);
    EXPECT_TRUE(mentions(*error, target)) << error->what();
    EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(PngIoTest, FailedRenameLeavesTargetAndNoTemporary)
{
    fs::create_directory(path("target.png"));
    const auto error = error_from([&] { write_png(path("target.png"), Image(2, 2, 1)); });
    ASSERT_TRUE(error);
    EXPECT_EQ(error->category(), ErrorCategory::Io);
    EXPECT_TRUE(fs::is_directory(path("target.png")));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace penumbra
