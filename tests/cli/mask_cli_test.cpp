// `penumbra mask` run as a user would: channel `ao` equals the library's
// ssao-vo on the scene's view depth, with and without the blur; bad input
// (a radius <= 0, a sample count beyond the limit, an unknown rule, an unknown
// scene) exits with 2 and one line "penumbra mask: ..." naming the option.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "penumbra/exr_io.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "penumbra/ssao.h"
#include "support/cli.h"

namespace penumbra {
namespace {

class MaskCli : public testing::CliFixture {
protected:
    std::string mask(const std::string& extra) const
    {
        return "mask --scene contact --view-size 37x21 --backend scalar --out " + path("mask.exr") + " " + extra;
    }

    void expect_ao(const SsaoOptions& o, bool blur) const
    {
        const reference::Scene scene = reference::builtin_scene("contact");
        const reference::Receivers rx = reference::render_receivers(scene, 37, 21);
        Context ctx(ContextOptions{Backend::Scalar, {}});
        const Image want = blur ? ssao_blurred(ctx, rx.view_depth, scene.view.fov_degrees, o)
                                : ssao_obscurance(ctx, rx.view_depth, scene.view.fov_degrees, o);
        // contact has a sun and a character light: the shadow steps add theirs (mask_shadow_cli_test.cpp).
        ASSERT_EQ(exr_channel_names(path("mask.exr")), (std::vector<std::string>{"ao", "shadow", "shadow2"}));
        const Image got = read_exr(path("mask.exr"), {"ao"});
        for (int y = 0; y < got.height(); ++y)
            for (int x = 0; x < got.width(); ++x) ASSERT_NEAR(got.at(0, x, y), want.at(0, x, y), 1e-6);
    }
};

TEST_F(MaskCli, AoIsTheLibrarysSsaoVo)
{
    const testing::ToolRun r = run(mask("--ao-radius 0.4 --ao-pairs 5 --ao-unusable zero"));
    ASSERT_EQ(r.status, 0) << r.err;
    SsaoOptions o;
    o.radius = 0.4;
    o.pairs = 5;
    o.unusable = SsaoUnusable::Zero;
    expect_ao(o, false);
}

TEST_F(MaskCli, BlurAppliesTheCrossBilateralPass)
{
    const testing::ToolRun r = run(mask("--blur"));
    ASSERT_EQ(r.status, 0) << r.err;
    expect_ao({}, true);
}

TEST_F(MaskCli, BadInputIsOneLineAndExitTwo)
{
    const std::pair<std::string, std::string> cases[] = {
        {"--ao-radius 0", "--ao-radius"},         {"--ao-radius -1", "--ao-radius"},
        {"--ao-pairs 17", "--ao-pairs"},          {"--ao-pairs 0", "--ao-pairs"},
        {"--ao-falloff 1", "--ao-falloff"},       {"--ao-unusable most", "--ao-unusable"},
        {"--ao-max-screen-radius 2", "--ao-max-screen-radius"}, {"--view-size 0x4", "--view-size"},
        {"--frobnicate", "--frobnicate"},
    };
    for (const auto& [extra, needle] : cases) {
        const testing::ToolRun r = run(mask(extra));
        EXPECT_EQ(r.status, 2) << extra << ": " << r.err;
        EXPECT_EQ(r.err.rfind("penumbra mask: ", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    }
    const testing::ToolRun unknown = run("mask --scene nowhere --out " + path("m.exr"));
    EXPECT_EQ(unknown.status, 2);
    EXPECT_EQ(unknown.err.rfind("penumbra mask: ", 0), 0u) << unknown.err;
}

}  // namespace
}  // namespace penumbra
