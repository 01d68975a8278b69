// read_deep_exr on bad, damaged and lying files: each is a typed Error naming
// the file (and, for a bad value, the pixel and the sample), never a crash, a
// hang or an allocation the file's size cannot justify.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "penumbra/deep_exr.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "support/cli.h"
#include "support/deep_files.h"

namespace penumbra {
namespace {

using testing::RawDeep;

class DeepExrRobustness : public testing::CliFixture {
protected:
    // A 3x2 file whose pixel (2, 1) holds `samples` (per channel), the rest one sample each.
    std::string file_with(const std::map<std::string, std::vector<float>>& samples,
                          std::vector<std::string> channels = {"A", "Z", "ZBack"})
    {
        RawDeep raw(3, 2);
        raw.channels = channels;
        for (int p = 0; p < 5; ++p) {
            auto& pixel = raw.pixels[std::size_t(p)];
            for (const std::string& c : channels) pixel[c] = {c == "A" ? 0.5f : c == "penumbra.T" ? 0.5f : 1.0f};
        }
        raw.at(2, 1) = samples;
        testing::write_raw_deep(path("bad.exr"), raw);
        return path("bad.exr");
    }

    // The read fails with `category`, naming the file and holding `needle`.
    static void expect_refused(const std::string& file, ErrorCategory category, const std::string& needle)
    {
        try {
            read_deep_exr(file);
            ADD_FAILURE() << "read: " << needle;
        } catch (const Error& e) {
            EXPECT_EQ(e.category(), category) << e.what();
            EXPECT_NE(e.message().find("'" + file + "'"), std::string::npos) << e.what();
            EXPECT_NE(e.message().find(needle), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();  // one line
        }
    }

    void expect_bad_sample(const std::map<std::string, std::vector<float>>& samples, const std::string& needle,
                           std::vector<std::string> channels = {"A", "Z", "ZBack"})
    {
        SCOPED_TRACE(needle);
        expect_refused(file_with(samples, channels), ErrorCategory::InvalidData, "pixel (2, 1), sample ");
        expect_refused(path("bad.exr"), ErrorCategory::InvalidData, needle);
    }
};

TEST_F(DeepExrRobustness, RefusesBadSampleValuesNamingThePixel)
{
    expect_bad_sample({{"Z", {3, 2}}, {"ZBack", {4, 2.5f}}, {"A", {0.1f, 0.1f}}}, "out of depth order or overlap");
    expect_bad_sample({{"Z", {1, 2}}, {"ZBack", {3, 4}}, {"A", {0.1f, 0.1f}}}, "out of depth order or overlap");
    expect_bad_sample({{"Z", {NAN}}, {"ZBack", {1}}, {"A", {0.1f}}}, "Z is NaN");
    expect_bad_sample({{"Z", {1}}, {"ZBack", {NAN}}, {"A", {0.1f}}}, "ZBack is NaN");
    expect_bad_sample({{"Z", {-INFINITY}}, {"ZBack", {1}}, {"A", {0.1f}}}, "Z is -inf");
    expect_bad_sample({{"Z", {2}}, {"ZBack", {1}}, {"A", {0.1f}}}, "lies before Z");
    expect_bad_sample({{"Z", {1}}, {"ZBack", {2}}, {"A", {NAN}}}, "A is NaN");
    expect_bad_sample({{"Z", {1}}, {"ZBack", {2}}, {"A", {1.5f}}}, "A is 1.5, outside [0, 1]");
    expect_bad_sample({{"Z", {1}}, {"ZBack", {2}}, {"A", {-0.25f}}}, "A is -0.25, outside [0, 1]");
    const std::vector<std::string> with_t{"A", "Z", "ZBack", "penumbra.T"};
    expect_bad_sample({{"Z", {1}}, {"ZBack", {2}}, {"A", {0.5f}}, {"penumbra.T", {NAN}}}, "penumbra.T is NaN", with_t);
    expect_bad_sample({{"Z", {1}}, {"ZBack", {2}}, {"A", {0.5f}}, {"penumbra.T", {0.9f}}}, "the channels disagree",
                      with_t);
    expect_bad_sample({{"Z", {1}}, {"ZBack", {2}}, {"A", {0.0f}}, {"penumbra.T", {1.5f}}}, "outside [0, 1]", with_t);
}

TEST_F(DeepExrRobustness, TheBadPixelIsReportedInFileCoordinates)
{
    file_with({{"Z", {NAN}}, {"ZBack", {1}}, {"A", {0.1f}}});
    try {
        read_deep_exr(path("bad.exr"));
        FAIL();
    } catch (const Error& e) {
        ASSERT_TRUE(e.pixel().has_value());
        EXPECT_EQ(e.pixel()->x, 2);
        EXPECT_EQ(e.pixel()->y, 1);
        EXPECT_EQ(e.pixel()->channel, 0);  // Z
    }
}

TEST_F(DeepExrRobustness, RefusesFilesThatAreNotDeepMaps)
{
    Image flat(4, 4, 1);
    write_exr(path("flat.exr"), flat, {"Z"});
    expect_refused(path("flat.exr"), ErrorCategory::Io, "is a flat (not deep) image");
    std::ofstream(path("text.exr")) << "not an image at all";
    expect_refused(path("text.exr"), ErrorCategory::Io, "is not an OpenEXR file");
    expect_refused(file_with({{"Z", {1}}, {"ZBack", {2}}}, {"Z", "ZBack"}), ErrorCategory::Io, "has no A channel");
    expect_refused(file_with({{"A", {1}}}, {"A"}), ErrorCategory::Io, "has no Z channel");
    EXPECT_THROW(read_deep_exr(path("missing.exr")), Error);
}

TEST_F(DeepExrRobustness, RefusesAWindowBeyondTheLimit)
{
    write_deep_exr(path("map.exr"), DeepShadowMap(8, 8, std::vector<std::uint32_t>(65, 0), {}, {}));
    try {
        read_deep_exr(path("map.exr"), ExrReadLimits{63});
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(e.message().find("more than the limit of 63"), std::string::npos) << e.what();
    }
}

// The damage of ExrRobustness.HeaderTheTwoParsersReadDifferentlyIsRefused (an
// attribute with an empty type after the channel list), on a deep file: the
// core library keeps defaults for a flat file there, but a deep one needs its
// type attribute, which comes later, so the core refuses the header itself.
// (require_readers_agree guards the deep reader too, for damage the core
// passes.)
TEST_F(DeepExrRobustness, AnAttributeWithAnEmptyTypeIsRefused)
{
    write_deep_exr(path("map.exr"), DeepShadowMap(8, 8, std::vector<std::uint32_t>(65, 0), {}, {}));
    std::ifstream in(path("map.exr"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string channels("channels\0chlist\0", 16);
    const std::size_t size_at = bytes.find(channels) + channels.size();
    ASSERT_NE(bytes.find(channels), std::string::npos);
    std::int32_t size = 0;
    std::memcpy(&size, bytes.data() + size_at, sizeof size);
    bytes.insert(size_at + 4 + std::size_t(size), std::string("junk\0\0\x01\0\0\0\0", 11));
    std::ofstream(path("map.exr"), std::ios::binary | std::ios::trunc) << bytes;
    expect_refused(path("map.exr"), ErrorCategory::Io, "its header cannot be read");
}

// Every truncation of a genuine file, scanline and tiled, compressed and not,
// is an Error: never a crash, never a map.
TEST_F(DeepExrRobustness, EveryTruncationIsATypedError)
{
    for (const int tile : {0, 4})
        for (const Imf::Compression c : {Imf::NO_COMPRESSION, Imf::ZIPS_COMPRESSION}) {
            RawDeep raw(6, 5);
            raw.tile = tile, raw.compression = c;
            for (int p = 0; p < 30; ++p)
                raw.pixels[std::size_t(p)] = {{"Z", {1, 2, 2 + float(p)}}, {"ZBack", {2, 2, 3 + float(p)}},
                                              {"A", {0.1f, 0.2f, 0.3f}}};
            testing::write_raw_deep(path("whole.exr"), raw);
            const std::string bytes = testing::slurp(path("whole.exr"));
            ASSERT_NO_THROW(read_deep_exr(path("whole.exr")));
            int refused = 0;
            for (std::size_t size = 0; size < bytes.size(); size += (size < 400 ? 1 : 3)) {
                std::ofstream(path("cut.exr"), std::ios::binary | std::ios::trunc) << bytes.substr(0, size);
                try {
                    read_deep_exr(path("cut.exr"));
                    ADD_FAILURE() << "a file cut to " << size << " of " << bytes.size() << " bytes was read";
                } catch (const Error& e) {
                    EXPECT_NE(e.message().find("cut.exr"), std::string::npos) << size << ": " << e.what();
                    ++refused;
                }
            }
            EXPECT_GT(refused, 100);
        }
}

// Random damage to genuine files (a few bytes anywhere, seeded): each read
// either refuses with Error or returns a map, whose invariants the builder has
// checked. Any other exception fails the test; a crash ends it.
TEST_F(DeepExrRobustness, RandomDamageIsRefusedOrReadAsAValidMap)
{
    std::vector<std::string> originals;
    for (const int tile : {0, 3})
        for (const Imf::Compression c : {Imf::NO_COMPRESSION, Imf::RLE_COMPRESSION, Imf::ZIPS_COMPRESSION}) {
            RawDeep raw(5, 4);
            raw.tile = tile, raw.compression = c;
            for (int p = 0; p < 20; ++p) {
                const float z = float(p % 7);
                raw.pixels[std::size_t(p)] = {{"Z", {z, z + 1, z + 1}}, {"ZBack", {z + 1, z + 1, z + 4}},
                                              {"A", {0.2f, 0.5f, 0.1f}}};
            }
            testing::write_raw_deep(path("seed.exr"), raw);
            originals.push_back(testing::slurp(path("seed.exr")));
        }
    std::mt19937 rng(2024);
    int read = 0, refused = 0;
    for (const std::string& original : originals)
        for (int trial = 0; trial < 250; ++trial) {
            std::string bytes = original;
            const int changes = 1 + int(rng() % 6);
            for (int k = 0; k < changes; ++k) {
                const std::size_t at = rng() % bytes.size();
                bytes[at] = (rng() % 3 == 0) ? char(0xff) : char(rng() & 0xff);
            }
            std::ofstream(path("damaged.exr"), std::ios::binary | std::ios::trunc) << bytes;
            try {
                const DeepShadowMap map = read_deep_exr(path("damaged.exr"));
                EXPECT_GE(map.width() * map.height(), 1);
                ++read;
            } catch (const Error& e) {
                EXPECT_NE(e.message().find("damaged.exr"), std::string::npos) << e.what();
                ++refused;
            }
        }
    EXPECT_GT(refused, 0);
    EXPECT_EQ(read + refused, 1500);
}

// An uncompressed one-line file, so that its chunk's fields sit at known places
// at its end: y (4 bytes), the sample count table's size, the data's stored
// and decoded sizes (8 bytes each), the table (cumulative counts), the data.
class LyingCounts : public DeepExrRobustness {
protected:
    static constexpr int kWidth = 4, kSamples = 2, kBytesPerSample = 12;  // A, Z, ZBack as FLOAT
    std::string bytes_;
    std::size_t chunk_ = 0;

    void SetUp() override
    {
        DeepExrRobustness::SetUp();
        RawDeep raw(kWidth, 1);
        raw.compression = Imf::NO_COMPRESSION;
        for (auto& pixel : raw.pixels) pixel = {{"Z", {1, 2}}, {"ZBack", {2, 3}}, {"A", {0.5f, 0.5f}}};
        testing::write_raw_deep(path("lie.exr"), raw);
        bytes_ = testing::slurp(path("lie.exr"));
        chunk_ = bytes_.size() - (4 + 24 + 4 * kWidth + std::size_t(kWidth * kSamples * kBytesPerSample));
        ASSERT_NO_THROW(read_deep_exr(path("lie.exr")));
    }
    void put_u64(std::size_t at, std::uint64_t value) { std::memcpy(&bytes_[at], &value, 8); }
    void put_u32(std::size_t at, std::uint32_t value) { std::memcpy(&bytes_[at], &value, 4); }
    std::string written()
    {
        std::ofstream(path("lie.exr"), std::ios::binary | std::ios::trunc) << bytes_;
        return path("lie.exr");
    }
};

TEST_F(LyingCounts, AChunkClaimingMoreDecodedBytesThanItStoresIsRefused)
{
    put_u64(chunk_ + 20, std::uint64_t(1) << 40);  // decoded size: 1 TiB from 96 bytes
    expect_refused(written(), ErrorCategory::Io, "unpacked data size 1099511627776");
}

TEST_F(LyingCounts, AbsurdSampleCountsAreRefusedBeforeAllocation)
{
    // The last pixel's cumulative count: 2^31 - 1 samples (24 GiB) in a 400-byte
    // file (OpenEXR's count reader compares them with the chunk's size), and
    // 2^31 and more (which it calls negative).
    for (const std::uint32_t count : {0x7fffffffu, 0x80000000u, 0xffffffffu}) {
        put_u32(chunk_ + 28 + 4 * (kWidth - 1), count);
        expect_refused(written(), ErrorCategory::Io, "corrupt");
    }
}

TEST_F(LyingCounts, CountsThatDisagreeWithTheDataAreRefused)
{
    // One sample fewer for the last pixel: the counts no longer fill the data.
    put_u32(chunk_ + 28 + 4 * (kWidth - 1), kWidth * kSamples - 1);
    expect_refused(written(), ErrorCategory::Io, "counts 7 samples but declares 96 bytes");
}

}  // namespace
}  // namespace penumbra
