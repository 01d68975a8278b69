// Deep shadow maps as OpenEXR deep files: bit-exact round trips (scanline and
// tiled, every tile size and width class), the sample mapping checked with
// OpenEXR's own reader (compositing A front to back gives t at every vertex),
// files as other renderers write them, exrheader's view, and atomic writes.
#include <OpenEXR/ImfDeepImageStateAttribute.h>
#include <OpenEXR/ImfDeepScanLineOutputPart.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "penumbra/deep_exr.h"
#include "penumbra/dsm_compression.h"
#include "penumbra/error.h"
#include "support/cli.h"
#include "support/deep_files.h"
#include "support/deep_functions.h"

namespace penumbra {
namespace {

using testing::RawDeep;

// Random functions (a sixth of the pixels empty), optionally compressed.
DeepShadowMap random_map(int width, int height, std::uint32_t seed, float tolerance = -1.0f)
{
    DeepShadowMapBuilder builder(width, height);
    for (int p = 0; p < width * height; ++p) {
        const testing::Function f = (p % 6 == 5) ? testing::Function{}
                                                 : testing::random_function(seed + std::uint32_t(p), 1 + p % 23);
        if (tolerance < 0.0f) {
            builder.add_pixel(f.z, f.t);
        } else {
            testing::Function c;
            compress_visibility(f.z, f.t, tolerance, c.z, c.t);
            builder.add_pixel(c.z, c.t);
        }
    }
    return builder.build();
}

// A slope, a step and a slope per pixel: tidy (no two point samples at one depth).
DeepShadowMap tidy_map(int width, int height)
{
    DeepShadowMapBuilder builder(width, height);
    for (int p = 0; p < width * height; ++p) {
        const float step = 2.0f + float(p % 3);
        builder.add_pixel(std::vector<float>{1.0f, step, step, 6.0f + float(p)},
                          std::vector<float>{1.0f, 0.8f, 0.5f, 0.2f});
    }
    return builder.build();
}

void expect_bit_identical(const DeepShadowMap& a, const DeepShadowMap& b)
{
    ASSERT_EQ(a.width(), b.width());
    ASSERT_EQ(a.height(), b.height());
    ASSERT_EQ(a.offsets(), b.offsets());
    ASSERT_EQ(a.vertex_count(), b.vertex_count());
    EXPECT_EQ(std::memcmp(a.depths().data(), b.depths().data(), a.vertex_count() * sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(a.transmittances().data(), b.transmittances().data(), a.vertex_count() * sizeof(float)), 0);
}

class DeepExr : public testing::CliFixture {};

TEST_F(DeepExr, ScanlineRoundTripIsBitExact)
{
    for (const auto& [w, h] : {std::pair{1, 1}, {1, 7}, {13, 5}, {70, 67}}) {
        const DeepShadowMap map = random_map(w, h, std::uint32_t(w * 100 + h));
        write_deep_exr(path("map.exr"), map);
        SCOPED_TRACE(::testing::Message() << w << "x" << h);
        expect_bit_identical(read_deep_exr(path("map.exr")), map);
    }
}

TEST_F(DeepExr, TiledRoundTripIsBitExact)
{
    for (const int tile : {1, 7, 16, 64, 2048})
        for (const auto& [w, h] : {std::pair{1, 1}, {13, 5}, {70, 67}}) {
            const DeepShadowMap map = random_map(w, h, std::uint32_t(tile * 7 + w), 0.02f);
            write_deep_exr(path("map.exr"), map, {DeepExrLayout::Tiled, tile});
            SCOPED_TRACE(::testing::Message() << w << "x" << h << " tiles " << tile);
            expect_bit_identical(read_deep_exr(path("map.exr")), map);
        }
}

TEST_F(DeepExr, EmptyAndOpaqueAndCoincidentStepsRoundTrip)
{
    DeepShadowMapBuilder builder(4, 1);
    builder.add_pixel({}, {});
    builder.add_pixel(std::vector<float>{2, 2, 9}, std::vector<float>{1, 0, 0});  // opaque, then flat at 0
    builder.add_pixel(std::vector<float>{3, 3, 3, 4}, std::vector<float>{1, 0.7f, 0.2f, 0.2f});  // two surfaces at 3
    builder.add_pixel(std::vector<float>{-5, 1e-30f, 1e30f}, std::vector<float>{1, 1e-30f, 1e-38f});
    const DeepShadowMap map = builder.build();
    write_deep_exr(path("map.exr"), map);
    expect_bit_identical(read_deep_exr(path("map.exr")), map);
}

// The samples as OpenEXR itself reads them: Z and ZBack are the vertices'
// depths, and 1 - (accumulated A) is the transmittance at every vertex.
TEST_F(DeepExr, CompositingTheSamplesGivesTheTransmittanceAtEveryVertex)
{
    const DeepShadowMap map = random_map(9, 4, 11);  // with coincident steps: not tidy
    write_deep_exr(path("map.exr"), map);
    Imf::DeepScanLineInputFile file(path("map.exr").c_str());
    EXPECT_EQ(file.header().type(), Imf::DEEPSCANLINE);
    EXPECT_EQ(file.header().findTypedAttribute<Imf::DeepImageStateAttribute>("deepImageState"), nullptr);
    const int w = map.width(), h = map.height();
    std::vector<unsigned> counts(std::size_t(w * h));
    Imf::DeepFrameBuffer frame;
    frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()), 4, 4 * std::size_t(w)));
    file.setFrameBuffer(frame);
    file.readPixelSampleCounts(0, h - 1);
    std::vector<std::vector<float>> z(counts.size()), back(counts.size()), a(counts.size());
    std::vector<float*> pz(counts.size()), pb(counts.size()), pa(counts.size());
    for (std::size_t p = 0; p < counts.size(); ++p) {
        z[p].resize(counts[p]), back[p].resize(counts[p]), a[p].resize(counts[p]);
        pz[p] = z[p].data(), pb[p] = back[p].data(), pa[p] = a[p].data();
    }
    const auto slice = [&](std::vector<float*>& v) {
        return Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(v.data()), sizeof(float*), sizeof(float*) * w,
                              sizeof(float));
    };
    frame.insert("Z", slice(pz)), frame.insert("ZBack", slice(pb)), frame.insert("A", slice(pa));
    file.setFrameBuffer(frame);
    file.readPixelSampleCounts(0, h - 1);  // a new frame buffer forgets them
    file.readPixels(0, h - 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t p = std::size_t(y * w + x);
            const auto vz = map.depths(x, y);
            const auto vt = map.transmittances(x, y);
            ASSERT_EQ(counts[p], vz.empty() ? 0u : vz.size() - 1);
            double accumulated = 0.0;  // "over", front to back
            for (unsigned k = 0; k < counts[p]; ++k) {
                EXPECT_EQ(z[p][k], vz[k]);
                EXPECT_EQ(back[p][k], vz[k + 1]);
                accumulated += (1.0 - accumulated) * a[p][k];
                EXPECT_NEAR(1.0 - accumulated, vt[k + 1], 1e-6) << "pixel " << x << "," << y << " sample " << k;
            }
        }
}

// exrheader (Debian's openexr package) lists the file as deep, with its channels.
TEST_F(DeepExr, ATidyMapSaysSo)
{
    write_deep_exr(path("map.exr"), tidy_map(4, 3));
    Imf::DeepScanLineInputFile file(path("map.exr").c_str());
    const auto* state = file.header().findTypedAttribute<Imf::DeepImageStateAttribute>("deepImageState");
    ASSERT_NE(state, nullptr);
    EXPECT_EQ(state->value(), Imf::DIS_TIDY);
    expect_bit_identical(read_deep_exr(path("map.exr")), tidy_map(4, 3));
}

TEST_F(DeepExr, ExrheaderListsTheDeepFile)
{
    if (std::system("command -v exrheader >/dev/null 2>&1") != 0) GTEST_SKIP() << "exrheader is not installed";
    write_deep_exr(path("scan.exr"), tidy_map(5, 3));
    write_deep_exr(path("tiled.exr"), tidy_map(5, 3), {DeepExrLayout::Tiled, 4});
    for (const auto& [name, type] : {std::pair{"scan.exr", "deepscanline"}, {"tiled.exr", "deeptile"}}) {
        const std::string out = path("header.txt");
        ASSERT_EQ(std::system(("exrheader " + path(name) + " > " + out + " 2>&1").c_str()), 0);
        const std::string text = testing::slurp(out);
        EXPECT_NE(text.find(type), std::string::npos) << text;
        for (const char* channel : {"A, 32-bit floating-point", "Z, 32-bit floating-point",
                                    "ZBack, 32-bit floating-point", "penumbra.T, 32-bit floating-point"})
            EXPECT_NE(text.find(channel), std::string::npos) << channel << "\n" << text;
        EXPECT_NE(text.find("deepImageState"), std::string::npos) << text;
    }
}

// Point samples only (no ZBack), HALF opacity, no penumbra.T, extra colour
// channels: t is the running product of (1 - A).
TEST_F(DeepExr, ReadsPointSamplesWithoutZBackOrExactTransmittance)
{
    RawDeep raw(2, 1);
    raw.channels = {"A", "B", "G", "R", "Z"};
    raw.types["A"] = Imf::HALF;
    raw.at(0, 0) = {{"Z", {1.0f, 4.0f}}, {"A", {0.5f, 0.25f}}, {"R", {1, 1}}, {"G", {0, 0}}, {"B", {0, 0}}};
    raw.at(1, 0) = {{"Z", {}}, {"A", {}}, {"R", {}}, {"G", {}}, {"B", {}}};
    testing::write_raw_deep(path("points.exr"), raw);
    const DeepShadowMap map = read_deep_exr(path("points.exr"));
    EXPECT_EQ(std::vector<float>(map.depths(0, 0).begin(), map.depths(0, 0).end()),
              (std::vector<float>{1, 1, 4, 4}));
    EXPECT_EQ(std::vector<float>(map.transmittances(0, 0).begin(), map.transmittances(0, 0).end()),
              (std::vector<float>{1, 0.5f, 0.5f, 0.375f}));
    EXPECT_TRUE(map.depths(1, 0).empty());
}

// Volume samples with gaps between them: the gaps are flat stretches.
TEST_F(DeepExr, ReadsVolumeSamplesWithGaps)
{
    for (const int tile : {0, 2}) {
        RawDeep raw(1, 1);
        raw.tile = tile;
        raw.at(0, 0) = {{"Z", {1.0f, 5.0f}}, {"ZBack", {2.0f, 5.0f}}, {"A", {0.5f, 1.0f}}};
        testing::write_raw_deep(path("gaps.exr"), raw);
        const DeepShadowMap map = read_deep_exr(path("gaps.exr"));
        EXPECT_EQ(std::vector<float>(map.depths(0, 0).begin(), map.depths(0, 0).end()),
                  (std::vector<float>{1, 2, 5, 5}));
        EXPECT_EQ(std::vector<float>(map.transmittances(0, 0).begin(), map.transmittances(0, 0).end()),
                  (std::vector<float>{1, 0.5f, 0.5f, 0.0f}));
        EXPECT_FLOAT_EQ(map.visibility(0, 0, 1.5f), 0.75f);
    }
}

TEST_F(DeepExr, ReadsEveryLosslessDeepCompression)
{
    for (const Imf::Compression c : {Imf::NO_COMPRESSION, Imf::RLE_COMPRESSION, Imf::ZIPS_COMPRESSION}) {
        RawDeep raw(3, 20);
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 3; ++x)
                raw.at(x, y) = {{"Z", {float(x + y)}}, {"ZBack", {float(x + y) + 1}}, {"A", {0.125f * float(x)}}};
        raw.compression = c;
        testing::write_raw_deep(path("c.exr"), raw);
        const DeepShadowMap map = read_deep_exr(path("c.exr"));
        EXPECT_FLOAT_EQ(map.visibility(2, 19, 22.0f), 0.75f) << int(c);
        EXPECT_FLOAT_EQ(map.visibility(1, 3, 4.5f), 0.9375f) << int(c);
    }
}

// Of a multi-part file the first part is read, as read_exr does.
TEST_F(DeepExr, ReadsTheFirstPartOfAMultiPartFile)
{
    std::vector<Imf::Header> headers(2);
    for (int part = 0; part < 2; ++part) {
        Imf::Header& h = headers[std::size_t(part)];
        h = Imf::Header(1, 1);
        h.compression() = Imf::ZIPS_COMPRESSION;
        h.setName(part == 0 ? "shadow" : "other");
        h.setType(Imf::DEEPSCANLINE);
        for (const char* c : {"A", "Z", "ZBack"}) h.channels().insert(c, Imf::Channel(Imf::FLOAT));
    }
    {
        Imf::MultiPartOutputFile file(path("parts.exr").c_str(), headers.data(), 2);
        for (int part = 0; part < 2; ++part) {
            unsigned count = 1;
            float z = 1.0f + float(part), back = 2.0f + float(part), a = part == 0 ? 0.25f : 0.75f;
            float *pz = &z, *pb = &back, *pa = &a;
            Imf::DeepFrameBuffer frame;
            frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(&count), 0, 0));
            frame.insert("Z", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(&pz), 0, 0, sizeof(float)));
            frame.insert("ZBack", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(&pb), 0, 0, sizeof(float)));
            frame.insert("A", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(&pa), 0, 0, sizeof(float)));
            Imf::DeepScanLineOutputPart out(file, part);
            out.setFrameBuffer(frame);
            out.writePixels(1);
        }
    }
    const DeepShadowMap map = read_deep_exr(path("parts.exr"));
    EXPECT_EQ(std::vector<float>(map.depths(0, 0).begin(), map.depths(0, 0).end()), (std::vector<float>{1, 2}));
    EXPECT_EQ(map.transmittances(0, 0).back(), 0.75f);
}

TEST_F(DeepExr, AFailedWriteLeavesTheTargetAsItWas)
{
    std::ofstream(path("old.exr")) << "previous contents";
    EXPECT_THROW(write_deep_exr(path("old.exr"), random_map(3, 3, 1), {DeepExrLayout::Tiled, 0}), Error);
    EXPECT_EQ(testing::slurp(path("old.exr")), "previous contents");
    EXPECT_THROW(write_deep_exr(path("missing/dir/map.exr"), random_map(3, 3, 1)), Error);
    EXPECT_THROW(write_deep_exr("/dev/null", random_map(3, 3, 1)), Error);  // a device, never replaced
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(path(""))) ++files;
    EXPECT_EQ(files, 1u);  // no temporary left
}

}  // namespace
}  // namespace penumbra
