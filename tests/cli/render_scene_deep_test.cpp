// `penumbra render-scene` on the deep-shadow scenes: same options, same three
// files; the truth is the reference's exact point-light transmittance, and the
// shadow map a first-surface map that the existing methods shade.
#include <gtest/gtest.h>

#include "penumbra/exr_io.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "support/cli.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

using testing::run_cli;

class RenderSceneDeep : public testing::CliFixture {};

TEST_F(RenderSceneDeep, EachDeepSceneWritesItsTruthAndAShadowMapTheMethodsShade)
{
    for (const std::string& name : reference::builtin_scene_names(reference::SceneSet::Deep)) {
        const testing::CliRun run =
            run_cli({"render-scene", name, "--map-size", "64", "--view-size", "24x18", "--shadow-map", path("sm.exr"),
                     "--receivers", path("rx.exr"), "--truth", path("gt.exr")});
        ASSERT_EQ(run.exit_code, 0) << name << ": " << run.err;
        EXPECT_NE(run.out.find("point light"), std::string::npos) << run.out;
        const reference::Scene scene = reference::builtin_scene(name);
        const reference::Receivers rx = reference::render_receivers(scene, 24, 18);
        const Image expected = reference::ground_truth(scene, rx, {32});
        const Image written = read_exr(path("gt.exr"), {"Y"});
        bool fractional = false;
        for (int y = 0; y < 18; ++y)
            for (int x = 0; x < 24; ++x) {
                EXPECT_EQ(written.at(0, x, y), expected.at(0, x, y)) << name;
                fractional = fractional || (written.at(0, x, y) > 0 && written.at(0, x, y) < 1);
            }
        EXPECT_TRUE(fractional || name == "hair") << name << ": a truth of fractions";  // opaque strands: 0 or 1
        for (const char* method : {"pcf", "vsm", "msm"}) {
            const testing::CliRun shade = run_cli({"shade", "--method", method, "--shadow-map", path("sm.exr"),
                                                   "--receivers", path("rx.exr"), "--out", path("out.exr")});
            EXPECT_EQ(shade.exit_code, 0) << name << " " << method << ": " << shade.err;
        }
    }
}

}  // namespace
}  // namespace penumbra
