// Layered depth maps as OpenEXR deep files (penumbra/layered_exr.h): exact
// round trips at odd sizes with empty pixels, the camera exact in the header,
// the samples as OpenEXR's own reader sees them, and bad files refused with
// a typed error naming the file (and the pixel for a bad depth).
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfVecAttribute.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <vector>

#include "penumbra/deep_exr.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/layered_exr.h"
#include "support/cli.h"
#include "support/deep_files.h"

namespace penumbra {
namespace {

using testing::expect_error;
using testing::RawDeep;

// A right-handed orthonormal frame turned off the axes, with a position and
// field of view that no float would carry exactly.
MapCamera tilted_camera()
{
    const double a = 0.3, b = 1.1;
    MapCamera c;
    c.position = {-2.5 + 1e-13, 9.000000000000002, -1.5};
    c.right = {std::cos(a), 0, -std::sin(a)};
    c.forward = {std::sin(a) * std::cos(b), -std::sin(b), std::cos(a) * std::cos(b)};
    const auto& r = c.right;
    const auto& f = c.forward;
    c.down = {f[1] * r[2] - f[2] * r[1], f[2] * r[0] - f[0] * r[2], f[0] * r[1] - f[1] * r[0]};  // f x r
    c.tan_half_fov = 0.7123456789012345;
    return c;
}

// Pixel p holds p % 5 layers (so every fifth is empty), at increasing depths.
LayeredDepthMap layered_map(int width, int height)
{
    LayeredDepthMapBuilder builder(width, height, tilted_camera());
    for (int p = 0; p < width * height; ++p) {
        std::vector<float> layers;
        for (int k = 0; k < p % 5; ++k) layers.push_back(0.37f * float(p + 1) + 1.25f * float(k) + 1e-3f);
        builder.add_pixel(layers);
    }
    return builder.build();
}

void expect_identical(const LayeredDepthMap& a, const LayeredDepthMap& b)
{
    EXPECT_EQ(a.width(), b.width());
    EXPECT_EQ(a.height(), b.height());
    EXPECT_EQ(a.offsets(), b.offsets());
    EXPECT_EQ(a.depths(), b.depths());
    EXPECT_EQ(a.camera().position, b.camera().position);
    EXPECT_EQ(a.camera().right, b.camera().right);
    EXPECT_EQ(a.camera().down, b.camera().down);
    EXPECT_EQ(a.camera().forward, b.camera().forward);
    EXPECT_EQ(a.camera().tan_half_fov, b.camera().tan_half_fov);
}

class LayeredExr : public testing::CliFixture {};

TEST_F(LayeredExr, RoundTripIsExactAtOddSizesWithEmptyPixels)
{
    for (auto [w, h] : {std::pair{1, 1}, {7, 3}, {15, 1}, {17, 65}, {1, 130}}) {
        const LayeredDepthMap map = layered_map(w, h);
        write_layered_exr(path("map.exr"), map);
        expect_identical(read_layered_exr(path("map.exr")), map);
    }
    LayeredDepthMapBuilder empty(3, 2, tilted_camera());  // no layer at all
    for (int p = 0; p < 6; ++p) empty.add_pixel({});
    const LayeredDepthMap none = empty.build();
    write_layered_exr(path("empty.exr"), none);
    expect_identical(read_layered_exr(path("empty.exr")), none);
}

// What another deep reader sees: the layers as Z point samples.
TEST_F(LayeredExr, OpenExrReadsTheLayersAsZSamples)
{
    const LayeredDepthMap map = layered_map(4, 3);
    write_layered_exr(path("map.exr"), map);
    Imf::DeepScanLineInputFile file(path("map.exr").c_str());
    std::vector<std::string> channels;
    for (auto c = file.header().channels().begin(); c != file.header().channels().end(); ++c)
        channels.emplace_back(c.name());
    EXPECT_EQ(channels, std::vector<std::string>{"Z"});
    std::vector<unsigned> counts(12);
    Imf::DeepFrameBuffer frame;
    frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()), sizeof(unsigned),
                                            4 * sizeof(unsigned)));
    file.setFrameBuffer(frame);
    file.readPixelSampleCounts(0, 2);
    for (int p = 0; p < 12; ++p) EXPECT_EQ(counts[std::size_t(p)], unsigned(p % 5)) << p;
}

// A deep file with Z samples `z` in its one pixel and, unless told, the camera;
// `extra` channels (FLOAT unless typed in `types`) beside Z.
void write_file(const std::string& path, std::vector<float> z, bool with_camera, MapCamera camera = tilted_camera(),
                const std::map<std::string, std::vector<float>>& extra = {},
                const std::map<std::string, Imf::PixelType>& types = {})
{
    RawDeep raw(1, 1);
    raw.channels = {"Z"};
    raw.at(0, 0)["Z"] = z;
    for (const auto& [name, values] : extra) raw.channels.push_back(name), raw.at(0, 0)[name] = values;
    raw.types = types;
    if (with_camera)
        raw.edit_header = [camera](Imf::Header& h) {
            const std::array<double, 3> axes[4] = {camera.position, camera.right, camera.down, camera.forward};
            const char* names[4] = {"penumbra.cameraPosition", "penumbra.cameraRight", "penumbra.cameraDown",
                                    "penumbra.cameraForward"};
            for (int k = 0; k < 4; ++k) h.insert(names[k], Imf::V3dAttribute({axes[k][0], axes[k][1], axes[k][2]}));
            h.insert("penumbra.tanHalfFov", Imf::DoubleAttribute(camera.tan_half_fov));
        };
    testing::write_raw_deep(path, raw);
}

TEST_F(LayeredExr, AFileAnotherToolWroteWithTheCameraReads)
{
    write_file(path("other.exr"), {1.5f, 2.5f}, true);
    const LayeredDepthMap map = read_layered_exr(path("other.exr"));
    ASSERT_EQ(map.layers(0, 0).size(), 2u);
    EXPECT_EQ(map.layers(0, 0)[1], 2.5f);
}

TEST_F(LayeredExr, BadFilesAreRefusedNamingTheFile)
{
    const auto refused = [&](const std::string& name, ErrorCategory category, const std::string& needle) {
        expect_error([&] { (void)read_layered_exr(path(name)); }, category, "read_layered_exr", {name, needle});
    };
    refused("missing.exr", ErrorCategory::Io, "missing.exr");
    std::ofstream(path("text.exr")) << "not an image";
    refused("text.exr", ErrorCategory::Io, "not an OpenEXR file");
    Image flat(2, 2, 1);
    write_exr(path("flat.exr"), flat, {"Z"});
    refused("flat.exr", ErrorCategory::Io, "flat (not deep)");
    write_file(path("no_camera.exr"), {1.0f}, false);
    refused("no_camera.exr", ErrorCategory::Io, "penumbra.cameraPosition");
    write_file(path("backwards.exr"), {2.0f, 1.0f}, true);
    refused("backwards.exr", ErrorCategory::InvalidData, "pixel (0, 0)");
    write_file(path("nan.exr"), {std::numeric_limits<float>::quiet_NaN()}, true);
    refused("nan.exr", ErrorCategory::InvalidData, "finite and > 0");
    write_file(path("zero.exr"), {0.0f}, true);
    refused("zero.exr", ErrorCategory::InvalidData, "finite and > 0");
    MapCamera skew = tilted_camera();
    skew.right = {1, 0, 0}, skew.down = {1, 0, 0};
    write_file(path("skew.exr"), {1.0f}, true, skew);
    refused("skew.exr", ErrorCategory::InvalidData, "orthonormal");
    // A deep shadow map is no layered map: it has no camera.
    write_deep_exr(path("dsm.exr"), DeepShadowMap(1, 1, {0, 2}, {1.0f, 2.0f}, {1.0f, 0.5f}));
    refused("dsm.exr", ErrorCategory::Io, "penumbra.cameraPosition");
    // Truncated: every check of the deep reader applies.
    write_layered_exr(path("whole.exr"), layered_map(17, 9));
    std::filesystem::copy_file(path("whole.exr"), path("cut.exr"));
    std::filesystem::resize_file(path("cut.exr"), std::filesystem::file_size(path("whole.exr")) / 2);
    refused("cut.exr", ErrorCategory::Io, "cut.exr");
}

// One id a layer, past a float's exact range (2^24) too.
std::vector<std::int32_t> ids_of(const LayeredDepthMap& map)
{
    std::vector<std::int32_t> ids(map.depths().size());
    for (std::size_t l = 0; l < ids.size(); ++l) ids[l] = std::int32_t((std::uint64_t(l) * 2654435761u) % 2147483647u);
    return ids;
}

TEST_F(LayeredExr, SurfaceIdsRoundTripExactlyInAUintChannel)
{
    std::vector<std::int32_t> back;
    for (auto [w, h] : {std::pair{1, 1}, {7, 3}, {17, 65}}) {
        const LayeredDepthMap map = layered_map(w, h);
        const std::vector<std::int32_t> ids = ids_of(map);
        write_layered_exr(path("map.exr"), map, ids);
        expect_identical(read_layered_exr(path("map.exr"), {}, &back), map);
        EXPECT_EQ(back, ids) << w << "x" << h;
        expect_identical(read_layered_exr(path("map.exr")), map);  // not asked for: not read
    }
    Imf::DeepScanLineInputFile file(path("map.exr").c_str());
    ASSERT_NE(file.header().channels().findChannel("surface"), nullptr);
    EXPECT_EQ(file.header().channels().findChannel("surface")->type, Imf::UINT);
    write_layered_exr(path("plain.exr"), layered_map(7, 3));
    back = {1, 2};
    (void)read_layered_exr(path("plain.exr"), {}, &back);
    EXPECT_TRUE(back.empty()) << "a file without the channel has no ids";
}

TEST_F(LayeredExr, BadSurfaceIdsAreRefused)
{
    std::vector<std::int32_t> ids;
    const auto refused = [&](const std::string& name, ErrorCategory category, const std::string& needle) {
        expect_error([&] { (void)read_layered_exr(path(name), {}, &ids); }, category, "read_layered_exr", {name, needle});
    };
    write_file(path("float_ids.exr"), {1.0f, 2.0f}, true, tilted_camera(), {{"surface", {3.0f, 4.0f}}});
    refused("float_ids.exr", ErrorCategory::Io, "as FLOAT; its ids are UINT");
    EXPECT_NO_THROW((void)read_layered_exr(path("float_ids.exr"))) << "ids not asked for: the channel is ignored";
    write_file(path("huge_ids.exr"), {1.0f, 2.0f}, true, tilted_camera(), {{"surface", {3.0f, 3e9f}}},
               {{"surface", Imf::UINT}});
    refused("huge_ids.exr", ErrorCategory::InvalidData, "pixel (0, 0), layer 1: surface id 3000000000");
    const LayeredDepthMap map = layered_map(7, 3);
    std::vector<std::int32_t> wrong = ids_of(map);
    wrong.pop_back();
    expect_error([&] { write_layered_exr(path("w.exr"), map, wrong); }, ErrorCategory::InvalidArgument,
                 "write_layered_exr", {"surface ids"});
    wrong = ids_of(map);
    wrong[2] = -1;
    expect_error([&] { write_layered_exr(path("w.exr"), map, wrong); }, ErrorCategory::InvalidArgument,
                 "write_layered_exr", {"negative"});
    EXPECT_FALSE(std::filesystem::exists(path("w.exr")));
}

TEST_F(LayeredExr, AnEmptyMapIsNotWritten)
{
    expect_error([&] { write_layered_exr(path("none.exr"), LayeredDepthMap()); }, ErrorCategory::InvalidArgument,
                 "write_layered_exr", {"empty"});
    EXPECT_FALSE(std::filesystem::exists(path("none.exr")));
}

}  // namespace
}  // namespace penumbra
