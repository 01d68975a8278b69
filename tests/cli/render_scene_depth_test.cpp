// `penumbra render-scene --depth first|midpoint|second`: the map it writes is
// the reference's render for that depth (whose closed form
// tests/reference/shadow_depth_test.cpp checks), and a bad value is refused.
#include <gtest/gtest.h>

#include "support/cli.h"
#include "penumbra/exr_io.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

using testing::run_cli;

class RenderSceneDepth : public testing::CliFixture {
protected:
    testing::CliRun render(const std::vector<std::string>& extra)
    {
        std::vector<std::string> args{"render-scene", "contact", "--map-size", "9", "--view-size", "5x3",
                                      "--samples", "1", "--shadow-map", path("sm.exr"), "--receivers",
                                      path("rx.exr"), "--truth", path("gt.exr")};
        args.insert(args.end(), extra.begin(), extra.end());
        return run_cli(args);
    }
};

TEST_F(RenderSceneDepth, EachModeWritesTheReferenceMap)
{
    const reference::Scene scene = reference::builtin_scene("contact");
    for (const char* name : {"first", "midpoint", "second"}) {
        const testing::CliRun run = render({"--depth", name});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        EXPECT_NE(run.out.find(std::string(name) + " depth"), std::string::npos) << run.out;
        const Image written = read_exr(path("sm.exr"), {"Z"});
        const Image expected =
            reference::render_shadow_map(scene, 9, 9, reference::shadow_depth_from_name(name, "depth"));
        for (int j = 0; j < 9; ++j)
            for (int i = 0; i < 9; ++i) EXPECT_EQ(written.at(0, i, j), expected.at(0, i, j)) << name;
    }
}

TEST_F(RenderSceneDepth, DefaultIsFirst)
{
    ASSERT_EQ(render({}).exit_code, 0);
    const Image written = read_exr(path("sm.exr"), {"Z"});
    const Image first = reference::render_shadow_map(reference::builtin_scene("contact"), 9, 9);
    for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) EXPECT_EQ(written.at(0, i, j), first.at(0, i, j));
}

TEST_F(RenderSceneDepth, BadValueIsOneLineAndExitTwo)
{
    for (const char* bad : {"third", "", "First", "midpoint "}) {
        const testing::CliRun run = render({"--depth", bad});
        EXPECT_TRUE(run.refused_cleanly()) << "exit " << run.exit_code << ": " << run.err;
        EXPECT_NE(run.err.find("--depth"), std::string::npos) << run.err;
    }
    const testing::CliRun missing = render({"--depth"});
    EXPECT_TRUE(missing.refused_cleanly()) << missing.err;
}

}  // namespace
}  // namespace penumbra
