// The shadow channels of `penumbra mask` (host/cli/mask_shadow_step.cpp):
// `shadow` and `shadow2` equal the library's cascade_mask of the scene's two
// directional lights on the view the command renders; a scene without one
// gets no shadow channel; bad input (more than 4 cascades, an unknown rule,
// cascades asked for a scene without a directional light) exits with 2 and
// one line "penumbra mask: ...".
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "penumbra/cascades.h"
#include "penumbra/exr_io.h"
#include "penumbra/reference/cascades.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "support/cli.h"

namespace penumbra {
namespace {

class MaskShadowCli : public testing::CliFixture {
protected:
    std::string mask(const std::string& scene, const std::string& extra) const
    {
        return "mask --scene " + scene + " --view-size 41x23 --backend scalar --out " + path("mask.exr") + " " + extra;
    }
};

TEST_F(MaskShadowCli, ShadowChannelsAreTheLibrarysCascadeMaskOfEachLight)
{
    const testing::ToolRun r = run(mask("contact", "--cascades 2 --cascade-size 64 --cascade-select split"));
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_EQ(exr_channel_names(path("mask.exr")), (std::vector<std::string>{"ao", "shadow", "shadow2"}));
    const reference::Scene scene = reference::builtin_scene("contact");
    const reference::Receivers receivers = reference::render_receivers(scene, 41, 23);
    Context ctx(ContextOptions{Backend::Scalar, {}});
    reference::CascadeSetup setup;
    setup.count = 2;
    setup.map_size = 64;
    CascadeOptions o;
    o.selection = CascadeSelection::SplitDepth;
    for (int light = 0; light < 2; ++light) {
        const Image want = cascade_mask(ctx, reference::render_cascades(scene, light, receivers, setup),
                                        reference::cascade_receivers(receivers), o);
        const std::string channel = light == 0 ? "shadow" : "shadow2";
        const Image got = read_exr(path("mask.exr"), {channel});
        int shadowed = 0;
        for (int y = 0; y < got.height(); ++y)
            for (int x = 0; x < got.width(); ++x) {
                ASSERT_NEAR(got.at(0, x, y), want.at(0, x, y), 1e-6) << channel;
                shadowed += got.at(0, x, y) < 0.5f;
            }
        EXPECT_GT(shadowed, 0) << channel;
    }
}

TEST_F(MaskShadowCli, ASceneWithoutADirectionalLightGetsNoShadowChannel)
{
    const testing::ToolRun r = run(mask("fence", ""));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(exr_channel_names(path("mask.exr")), std::vector<std::string>{"ao"});
}

TEST_F(MaskShadowCli, BadInputIsOneLineAndExitTwo)
{
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--cascades 5", "--cascades"},
        {"--cascades 0", "--cascades"},
        {"--cascade-select nearest", "--cascade-select"},
        {"--cascade-near-plane far", "--cascade-near-plane"},
        {"--cascade-size 4", "--cascade-size"},
        {"--shadow-near 5 --shadow-far 2", "--shadow-far"},
    };
    for (const auto& [extra, needle] : cases) {
        const testing::ToolRun r = run(mask("contact", extra));
        EXPECT_EQ(r.status, 2) << extra << ": " << r.err;
        EXPECT_EQ(r.err.rfind("penumbra mask: ", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    }
    const testing::ToolRun none = run(mask("fence", "--cascades 3"));
    EXPECT_EQ(none.status, 2) << none.err;
    EXPECT_EQ(none.err.rfind("penumbra mask: ", 0), 0u) << none.err;
    EXPECT_EQ(std::count(none.err.begin(), none.err.end(), '\n'), 1) << none.err;
    EXPECT_NE(none.err.find("no directional light"), std::string::npos) << none.err;
}

}  // namespace
}  // namespace penumbra
