// read_exr / write_exr / exr_channel_names: bit-exact round trips, channel order,
// data windows off the origin, HALF conversion, and every failure a user can
// provoke, each of which must be a penumbra::Error naming the file.
#include "penumbra/exr_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include <Imath/ImathBox.h>
#include <Imath/half.h>

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>

#include "penumbra/error.h"
#include "support/cli.h"
#include "support/errors.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

using testing::error_from;
using testing::expect_error;

std::string contents_of(const fs::path& path)
{
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), {}};
}

void write_text(const fs::path& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

std::vector<std::string> entries_of(const fs::path& directory)
{
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(directory))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Distinct in every channel and pixel, with the awkward values a lossy path or
// a conversion would change: -0, a denormal, the largest float, infinity.
Image distinct_image(int width, int height, int channels)
{
    Image image(width, height, channels);
    for (int c = 0; c < channels; ++c)
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                image.at(c, x, y) = (c % 2 ? -0.1f : 0.1f) * float(1 + x + width * y + 100 * c);
    image.at(0, 0, 0) = -0.0f;
    image.at(0, width - 1, height - 1) = std::numeric_limits<float>::max();
    if (channels > 1) {
        image.at(1, 0, 0) = 1e-40f;
        image.at(1, 1, 0) = std::numeric_limits<float>::infinity();
    }
    return image;
}

// Bit patterns, so that -0 and 0 differ and a value that only rounds equal fails.
void expect_plane_bits_equal(const Image& actual, int actual_c, const Image& expected, int expected_c)
{
    ASSERT_EQ(actual.width(), expected.width());
    ASSERT_EQ(actual.height(), expected.height());
    for (int y = 0; y < expected.height(); ++y)
        for (int x = 0; x < expected.width(); ++x)
            EXPECT_EQ(std::bit_cast<std::uint32_t>(actual.at(actual_c, x, y)),
                      std::bit_cast<std::uint32_t>(expected.at(expected_c, x, y)))
                << "at (" << x << ", " << y << ")";
}

// A fresh scratch folder per test (support/cli.h).
class ExrIoTest : public testing::CliFixture {};

TEST_F(ExrIoTest, RoundTripIsBitExact)
{
    const Image original = distinct_image(7, 3, 2);
    write_exr(path("a.exr"), original, {"depth", "moment2"});
    const Image read = read_exr(path("a.exr"), {"depth", "moment2"});

    ASSERT_EQ(read.channels(), 2);
    expect_plane_bits_equal(read, 0, original, 0);
    expect_plane_bits_equal(read, 1, original, 1);
}

TEST_F(ExrIoTest, ChannelOrderIsTheRequestedOrder)
{
    // Written in non-alphabetical order; EXR stores channels sorted by name.
    const Image original = distinct_image(7, 3, 2);
    write_exr(path("a.exr"), original, {"moment2", "depth"});

    EXPECT_EQ(exr_channel_names(path("a.exr")), (std::vector<std::string>{"depth", "moment2"}));
    const Image swapped = read_exr(path("a.exr"), {"depth", "moment2"});
    expect_plane_bits_equal(swapped, 0, original, 1);
    expect_plane_bits_equal(swapped, 1, original, 0);
    const Image single = read_exr(path("a.exr"), {"moment2"});
    ASSERT_EQ(single.channels(), 1);
    expect_plane_bits_equal(single, 0, original, 0);
}

TEST_F(ExrIoTest, OverwritesAnExistingFile)
{
    write_exr(path("a.exr"), distinct_image(7, 3, 2), {"a", "b"});
    const Image second = distinct_image(2, 5, 1);
    write_exr(path("a.exr"), second, {"c"});

    EXPECT_EQ(exr_channel_names(path("a.exr")), (std::vector<std::string>{"c"}));
    expect_plane_bits_equal(read_exr(path("a.exr"), {"c"}), 0, second, 0);
    EXPECT_EQ(entries_of(dir_), (std::vector<std::string>{"a.exr"}));  // no temporary left
}

// Written with the OpenEXR API directly: a data window whose corner is not the
// origin (negative y, too) and a HALF channel that must come back as float.
void write_offset_window_file(const std::string& path, const Imath::Box2i& window)
{
    float depth[4][4];
    Imath::half coverage[4][4];
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const int absolute_x = window.min.x + x, absolute_y = window.min.y + y;
            depth[y][x] = float(100 * absolute_y + absolute_x);
            coverage[y][x] = Imath::half(0.25f * float(x + 4 * y));  // exact in half
        }
    Imf::Header header(Imath::Box2i({0, 0}, {19, 19}), window);
    header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    header.channels().insert("coverage", Imf::Channel(Imf::HALF));
    Imf::FrameBuffer frame;
    frame.insert("Z", Imf::Slice::Make(Imf::FLOAT, &depth[0][0], window));
    frame.insert("coverage", Imf::Slice::Make(Imf::HALF, &coverage[0][0], window));
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(4);
}

TEST_F(ExrIoTest, ReadsADataWindowAwayFromTheOrigin)
{
    const Imath::Box2i window({5, -2}, {8, 1});
    write_offset_window_file(path("offset.exr"), window);

    const Image image = read_exr(path("offset.exr"), {"Z", "coverage"});
    ASSERT_EQ(image.width(), 4);
    ASSERT_EQ(image.height(), 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            EXPECT_EQ(image.at(0, x, y), float(100 * (window.min.y + y) + window.min.x + x))
                << x << ", " << y;
            EXPECT_EQ(image.at(1, x, y), 0.25f * float(x + 4 * y)) << x << ", " << y;
        }
}

TEST_F(ExrIoTest, MissingFileIsAnIoErrorNamingIt)
{
    for (const auto& read : {+[](const std::string& p) { read_exr(p, {"Z"}); },
                             +[](const std::string& p) { exr_channel_names(p); }}) {
        expect_error([&] { read(path("absent.exr")); }, ErrorCategory::Io, {path("absent.exr"), "does not exist"});
    }
}

TEST_F(ExrIoTest, TextFileIsNotAnExr)
{
    write_text(path("notes.exr"), "this is not an image\n");
    expect_error([&] { read_exr(path("notes.exr"), {"Z"}); }, ErrorCategory::Io,
                 {path("notes.exr"), "not an OpenEXR file"});
}

TEST_F(ExrIoTest, DirectoryIsNotAnExr)
{
    expect_error([&] { exr_channel_names(dir_.string()); }, ErrorCategory::Io, {"is a directory"});
}

TEST_F(ExrIoTest, UnreadableFileIsAnIoError)
{
    if (::geteuid() == 0) GTEST_SKIP() << "root reads files regardless of their permissions";
    write_exr(path("locked.exr"), distinct_image(2, 2, 1), {"Z"});
    fs::permissions(path("locked.exr"), fs::perms::none);
    expect_error([&] { read_exr(path("locked.exr"), {"Z"}); }, ErrorCategory::Io, {"permissions"});
}

// OpenEXR's own exceptions (Iex::BaseExc) must arrive translated.
TEST_F(ExrIoTest, TruncatedFileIsAnIoErrorNotAnIexException)
{
    write_exr(path("cut.exr"), distinct_image(64, 64, 2), {"a", "b"});
    fs::resize_file(path("cut.exr"), fs::file_size(path("cut.exr")) / 2);
    expect_error([&] { read_exr(path("cut.exr"), {"a", "b"}); }, ErrorCategory::Io, {path("cut.exr")});
}

TEST_F(ExrIoTest, MissingChannelIsNamedWithTheChannelsThatExist)
{
    write_exr(path("a.exr"), distinct_image(3, 3, 2), {"depth", "moment2"});
    expect_error([&] { read_exr(path("a.exr"), {"depth", "moment4"}); }, ErrorCategory::Io,
                 {path("a.exr"), "'moment4'", "'depth', 'moment2'"});
}

// OpenEXR's writer refuses an empty data window, so one is made by editing the
// header of a valid file: xMax = xMin - 1 leaves zero columns.
TEST_F(ExrIoTest, EmptyDataWindowIsAnIoError)
{
    write_exr(path("empty.exr"), distinct_image(1, 1, 1), {"Z"});
    std::string bytes = contents_of(path("empty.exr"));
    const std::string attribute("dataWindow\0box2i\0", 17);
    const std::size_t at = bytes.find(attribute);
    ASSERT_NE(at, std::string::npos);
    const std::size_t x_max = at + attribute.size() + 4 + 8;  // past the size; xMin, yMin, then xMax
    const std::int32_t minus_one = -1;                        // EXR is little-endian, as is x86
    std::memcpy(&bytes[x_max], &minus_one, 4);
    write_text(path("empty.exr"), bytes);

    expect_error([&] { read_exr(path("empty.exr"), {"Z"}); }, ErrorCategory::Io, {path("empty.exr"), "data window"});
}

TEST_F(ExrIoTest, BadChannelListsAreInvalidArguments)
{
    write_exr(path("a.exr"), distinct_image(3, 3, 2), {"a", "b"});
    for (const std::vector<std::string>& channels : {std::vector<std::string>{}, {"a", "a"}, {"a", ""}}) {
        const auto error = error_from([&] { read_exr(path("a.exr"), channels); });
        ASSERT_TRUE(error);
        EXPECT_EQ(error->category(), ErrorCategory::InvalidArgument) << error->what();
    }
}

TEST_F(ExrIoTest, ChannelCountMismatchLeavesTheExistingTargetUntouched)
{
    write_text(path("keep.exr"), "previous contents");
    expect_error([&] { write_exr(path("keep.exr"), distinct_image(3, 3, 2), {"depth"}); },
                 ErrorCategory::InvalidArgument, {"2 channels but 1 name was given"});
    EXPECT_EQ(contents_of(path("keep.exr")), "previous contents");
    EXPECT_EQ(entries_of(dir_), (std::vector<std::string>{"keep.exr"}));
}

TEST_F(ExrIoTest, EmptyImageIsNotWritten)
{
    const auto error = error_from([&] { write_exr(path("empty.exr"), Image(0, 4, 1), {"Z"}); });
    ASSERT_TRUE(error);
    EXPECT_EQ(error->category(), ErrorCategory::InvalidArgument);
    EXPECT_TRUE(entries_of(dir_).empty());
}

TEST_F(ExrIoTest, WriteIntoMissingDirectoryCreatesNothing)
{
    const std::string target = path("no-such-directory/a.exr");
    expect_error([&] { write_exr(target, distinct_image(3, 3, 1), {"Z"}); }, ErrorCategory::Io,
                 {target, "does not exist"});
    EXPECT_TRUE(entries_of(dir_).empty());
}

// The pixels reach the temporary file, but rename(2) cannot put a file over a
// directory: the target must survive and the temporary must be gone.
TEST_F(ExrIoTest, FailedRenameLeavesTargetAndNoTemporary)
{
    fs::create_directory(path("target.exr"));
    write_text(path("target.exr/inside"), "kept");
    expect_error([&] { write_exr(path("target.exr"), distinct_image(3, 3, 1), {"Z"}); }, ErrorCategory::Io,
                 {path("target.exr")});
    EXPECT_EQ(contents_of(path("target.exr/inside")), "kept");
    EXPECT_EQ(entries_of(dir_), (std::vector<std::string>{"target.exr"}));
}

}  // namespace
}  // namespace penumbra
