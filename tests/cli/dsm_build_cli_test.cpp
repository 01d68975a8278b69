// `penumbra dsm-build`: the file it writes reads back as the map the library
// renders with the same options, bit for bit; bad options exit with 2 and one
// line naming the option, leaving an existing output as it was.
#include <gtest/gtest.h>

#include <fstream>

#include "penumbra/deep_exr.h"
#include "penumbra/reference/deep_map.h"
#include "penumbra/reference/scene.h"
#include "support/cli.h"
#include "support/deep_scenes.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

using testing::run_cli;

class DsmBuildCli : public testing::CliFixture {};

TEST_F(DsmBuildCli, WritesTheLibrarysMapAndItReadsBack)
{
    for (const char* filter : {"box", "gaussian"}) {
        const testing::CliRun run = run_cli({"dsm-build", "--scene", "layers", "--out", path("dsm.exr"), "--size", "24",
                                             "--samples", "9", "--filter", filter, "--seed", "3"});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << run.out;
        EXPECT_NE(run.out.find("576 pixels"), std::string::npos) << run.out;
        EXPECT_NE(run.out.find("compression ratio"), std::string::npos) << run.out;
        reference::DeepMapOptions o;
        o.size = 24;
        o.samples = 9;
        o.filter = reference::deep_map_filter_from_name(filter, "filter");
        o.seed = 3;
        const DeepShadowMap expected = reference::render_deep_shadow_map(reference::builtin_scene("layers"), o);
        EXPECT_TRUE(testing::same_deep_map(read_deep_exr(path("dsm.exr")), expected)) << filter;
    }
}

TEST_F(DsmBuildCli, TakesAJsonSceneAndATolerance)
{
    std::ofstream(path("sheet.json")) << testing::overhead_json(testing::sheet_json(2, 0.4));
    const testing::CliRun run = run_cli({"dsm-build", "--scene", path("sheet.json"), "--out", path("dsm.exr"),
                                         "--size", "4", "--samples", "4", "--tolerance", "0.01"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("tolerance 0.0100"), std::string::npos) << run.out;
    const DeepShadowMap map = read_deep_exr(path("dsm.exr"));
    ASSERT_EQ(map.width(), 4);
    // Between the sheet (z 0.4) and the ground (z 0.8), within the tolerance.
    EXPECT_NEAR(map.visibility(1, 1, 0.5f), 0.6f, 0.01f);
}

TEST_F(DsmBuildCli, RefusesBadOptionsWithOneLine)
{
    const std::string out = path("out.exr");
    auto build = [&](const std::string& extra) { return "dsm-build --scene layers --out " + out + " --size 4 " + extra; };
    expect_bad_inputs(build, {
                                 {"--samples 0", "--samples"},
                                 {"--samples 5000", "--samples"},
                                 {"--tolerance -0.1", "--tolerance"},
                                 {"--tolerance 2", "--tolerance"},
                                 {"--tolerance nan", "--tolerance"},
                                 {"--filter tent", "--filter"},
                                 {"--seed -1", "--seed"},
                                 {"--bogus 1", "--bogus"},
                                 {"--samples", "--samples"},
                             });
    expect_bad_input("dsm-build --scene layers --out " + out + " --size 0", "--size");
    expect_bad_input("dsm-build --scene layers --out " + out + " --size x", "--size");
    expect_bad_input("dsm-build --scene nowhere --out " + out, "nowhere");
    expect_bad_input("dsm-build --scene " + path("missing.json") + " --out " + out, "missing.json");
    expect_bad_input("dsm-build --out " + out, "--scene");
    expect_bad_input("dsm-build --scene layers", "--out");
}

}  // namespace
}  // namespace penumbra
