// `penumbra shade --method dsm --deep-map DSM.exr`: the file dsm-build
// writes, shaded, gives what the library's deep_lookup gives; scanline and
// tiled files both read; every bad deep file (unsorted depths, NaN depths or
// opacities, opacity outside [0, 1], a flat EXR, a truncated file) exits 2
// with one line naming the file and, for a bad value, the pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "penumbra/deep_exr.h"
#include "penumbra/deep_lookup.h"
#include "penumbra/exr_io.h"
#include "support/cli.h"
#include "support/deep_files.h"
#include "support/deep_lookup_reference.h"
#include "support/maps.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

using testing::run_cli;

class DsmShadeCli : public testing::CliFixture {
protected:
    void SetUp() override
    {
        CliFixture::SetUp();
        write_exr(path("rx.exr"), testing::receivers_on_texels(7, 3, 6, 4, 0.0f, 1.0f, 5), {"u", "v", "z"});
    }
    testing::CliRun shade(const std::string& deep, std::vector<std::string> extra = {}) const
    {
        std::vector<std::string> args = {"shade", "--method", "dsm", "--deep-map", deep, "--receivers",
                                         path("rx.exr"), "--out", path("out.exr"), "--backend", "scalar"};
        args.insert(args.end(), extra.begin(), extra.end());
        return run_cli(args);
    }
};

TEST_F(DsmShadeCli, ShadesWhatDsmBuildWroteAsTheLibraryDoes)
{
    const testing::CliRun build = run_cli({"dsm-build", "--scene", "layers", "--out", path("dsm.exr"), "--size", "6",
                                           "--samples", "4"});
    ASSERT_EQ(build.exit_code, 0) << build.err;
    const DeepShadowMap map = read_deep_exr(path("dsm.exr"));
    const Image rx = read_exr(path("rx.exr"), {"u", "v", "z"});
    Context ctx(ContextOptions{Backend::Scalar, {}});
    for (const char* filter : {"box", "tent"}) {
        const testing::CliRun run = shade(path("dsm.exr"), {"--filter", filter, "--radius", "1"});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        DeepLookupOptions o;
        o.filter = std::string(filter) == "box" ? DeepFilter::Box : DeepFilter::Tent;
        o.radius = 1;
        const Image expected = deep_lookup(ctx, map, rx, o);
        EXPECT_EQ(testing::difference(read_exr(path("out.exr"), {"Y"}), expected).differing, 0) << filter;
    }
}

// Two pixels by OpenEXR itself (support/deep_files.h): a sheet of opacity
// 0.4 at z 0.3 over a slab, and one empty pixel.
testing::RawDeep two_pixels()
{
    testing::RawDeep raw(2, 1);
    raw.at(0, 0) = {{"Z", {0.3f, 0.5f}}, {"ZBack", {0.3f, 0.7f}}, {"A", {0.4f, 0.5f}}};
    raw.at(1, 0) = {{"Z", {}}, {"ZBack", {}}, {"A", {}}};
    return raw;
}

TEST_F(DsmShadeCli, ReadsScanlineAndTiledFiles)
{
    for (int tile : {0, 1}) {
        testing::RawDeep raw = two_pixels();
        raw.tile = tile;
        testing::write_raw_deep(path("raw.exr"), raw);
        const testing::CliRun run = shade(path("raw.exr"), {"--filter", "box", "--radius", "0"});
        ASSERT_EQ(run.exit_code, 0) << (tile ? "tiled: " : "scanline: ") << run.err;
        const Image out = read_exr(path("out.exr"), {"Y"});
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) ASSERT_TRUE(out.at(0, x, y) >= 0.0f && out.at(0, x, y) <= 1.0f);
    }
}

TEST_F(DsmShadeCli, BadDeepFilesExitTwoNamingTheFileAndThePixel)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    struct Bad {
        const char* what;
        const char* name;  // the channel changed in sample 0 of pixel (0, 0)
        float value;
    };
    const Bad cases[] = {
        {"unsorted depths", "Z", 0.9f},  // a point sample at 0.9 before the slab at 0.5
        {"a NaN depth", "Z", nan},
        {"a NaN opacity", "A", nan},
        {"an opacity above 1", "A", 1.5f},
        {"an opacity below 0", "A", -0.25f},
    };
    for (const Bad& b : cases) {
        testing::RawDeep raw = two_pixels();
        raw.at(0, 0)[b.name][0] = b.value;
        if (std::string(b.what) == "unsorted depths") raw.at(0, 0)["ZBack"][0] = b.value;
        testing::write_raw_deep(path("bad.exr"), raw);
        std::ofstream(path("out.exr")) << "previous contents";
        const testing::CliRun run = shade(path("bad.exr"));
        EXPECT_TRUE(run.refused_cleanly()) << b.what << ": " << run.exit_code << " " << run.err;
        EXPECT_EQ(run.err.rfind("penumbra shade: ", 0), 0u) << b.what << ": " << run.err;
        EXPECT_NE(run.err.find(path("bad.exr")), std::string::npos) << b.what << ": " << run.err;
        EXPECT_NE(run.err.find("pixel (0, 0)"), std::string::npos) << b.what << ": " << run.err;
        EXPECT_EQ(testing::slurp(path("out.exr")), "previous contents") << b.what;
    }
}

TEST_F(DsmShadeCli, AFlatOrTruncatedFileExitsTwoNamingTheFile)
{
    write_exr(path("flat.exr"), testing::random_depth(4, 4, 1), {"Z"});
    testing::write_raw_deep(path("whole.exr"), two_pixels());
    const std::string whole = testing::slurp(path("whole.exr"));
    std::ofstream(path("cut.exr"), std::ios::binary) << whole.substr(0, whole.size() * 2 / 3);
    for (const char* name : {"flat.exr", "cut.exr"}) {
        const testing::CliRun run = shade(path(name));
        EXPECT_TRUE(run.refused_cleanly()) << name << ": " << run.exit_code << " " << run.err;
        EXPECT_EQ(run.err.rfind("penumbra shade: ", 0), 0u) << run.err;
        EXPECT_NE(run.err.find(path(name)), std::string::npos) << run.err;
    }
    const testing::CliRun flat = shade(path("flat.exr"));
    EXPECT_NE(flat.err.find("flat"), std::string::npos) << flat.err;
}

TEST_F(DsmShadeCli, TheWrongInputFlagOrFilterExitsTwoNamingTheFlag)
{
    testing::write_raw_deep(path("deep.exr"), two_pixels());
    const testing::CliRun shadow_map =
        run_cli({"shade", "--method", "dsm", "--shadow-map", path("deep.exr"), "--receivers", path("rx.exr"), "--out",
                 path("out.exr")});
    EXPECT_TRUE(shadow_map.refused_cleanly()) << shadow_map.err;
    EXPECT_NE(shadow_map.err.find("--deep-map"), std::string::npos) << shadow_map.err;
    const testing::CliRun deep_for_vsm =
        run_cli({"shade", "--method", "vsm", "--deep-map", path("deep.exr"), "--receivers", path("rx.exr"), "--out",
                 path("out.exr")});
    EXPECT_TRUE(deep_for_vsm.refused_cleanly()) << deep_for_vsm.err;
    EXPECT_NE(deep_for_vsm.err.find("--shadow-map"), std::string::npos) << deep_for_vsm.err;
    const testing::CliRun filter = shade(path("deep.exr"), {"--filter", "gaussian"});
    EXPECT_TRUE(filter.refused_cleanly()) << filter.err;
    EXPECT_NE(filter.err.find("--filter"), std::string::npos) << filter.err;
}

}  // namespace
}  // namespace penumbra
