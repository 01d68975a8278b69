// `penumbra shade --method pismo|pismo-maxdepth`: the method table's entries
// (prepare then shade is run, and is pismo_shade on the same maps), the tool's
// image equal to the library's on the same maps (rendered from --scene with
// cameras fitted to the receivers, or read from pismo-build's directory), and
// bad input (a light level past the limit, zero rays, a point light, a missing
// input) exiting with 2 and one line "penumbra shade: ...".
#include <gtest/gtest.h>

#include "penumbra/context.h"
#include "penumbra/exr_io.h"
#include "penumbra/methods.h"
#include "penumbra/pismo.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/render.h"
#include "support/cli.h"
#include "support/maps.h"
#include "support/pismo_scenes.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

using testing::run_cli;

// Ground points of the half-plane scene, inside and beside the blocker's shadow.
Image ground_receivers(int width, int height)
{
    Image rx(width, height, 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            rx.at(0, x, y) = -1.5f + 3.0f * float(x) / float(std::max(1, width - 1));
            rx.at(2, x, y) = -0.5f + float(y) / float(std::max(1, height - 1));
        }
    return rx;
}

TEST(PismoMethod, PrepareThenShadeIsRunAndIsPismoShade)
{
    Context ctx(ContextOptions{Backend::Scalar, {}});
    reference::LayeredMapOptions o;
    o.size = 24;
    const PismoMapSet set = reference::render_pismo_map_set(testing::half_plane_scene(), 1, o);
    const Image rx = ground_receivers(7, 3);
    for (auto [name, depths] : {std::pair{"pismo", PismoDepths::Layered}, {"pismo-maxdepth", PismoDepths::MaximumDepth}}) {
        const Method& m = find_method(name);
        ASSERT_EQ(m.input, MethodInput::PismoMapSet);
        EXPECT_EQ(receiver_channels(m, {}), (std::vector<std::string>{"P.x", "P.y", "P.z"}));
        MethodSettings s;
        s.rays = 16;
        const Image expected = pismo_shade(ctx, PismoMaps(set.vertices, set.triangles, set.maps, depths), rx, {16});
        EXPECT_EQ(testing::difference(m.run(ctx, set, rx, s), expected).differing, 0) << name;
        const PreparedMap prepared = m.prepare_pismo(ctx, set, s);
        EXPECT_EQ(&prepared.pismo_set(), &set);
        for (int call = 0; call < 2; ++call) {
            Image out(rx.width(), rx.height(), 1);
            m.shade(ctx, prepared, rx, s, out);
            EXPECT_EQ(testing::difference(out, expected).differing, 0) << name << " call " << call;
        }
        EXPECT_THROW((void)m.run(ctx, Image(1, 1, 1), rx, s), Error) << "a shadow map is not its input";
    }
}

class PismoShadeCli : public testing::CliFixture {
protected:
    void SetUp() override
    {
        CliFixture::SetUp();
        ASSERT_EQ(run_cli({"render-scene", "contact", "--shadow-map", path("sm.exr"), "--receivers", path("rx.exr"),
                           "--truth", path("gt.exr"), "--map-size", "8", "--view-size", "9x7", "--samples", "1"})
                      .exit_code,
                  0);
    }
};

TEST_F(PismoShadeCli, TheToolsImageIsTheLibrarysOnTheSameMaps)
{
    const reference::Scene scene = reference::builtin_scene("contact");
    const reference::Receivers rx = reference::render_receivers(scene, 9, 7);
    reference::LayeredMapOptions o;
    o.size = 32;
    o.max_layers = 4;
    const PismoMapSet set = reference::render_pismo_map_set(scene, 0, o, reference::receiver_region(rx));
    Context ctx(ContextOptions{Backend::Scalar, {}});
    // render-scene's RX.exr has the normals and the surface ids: the tool reads them with the positions.
    const Image positions = read_exr(path("rx.exr"), {"P.x", "P.y", "P.z", "N.x", "N.y", "N.z", "surface"});
    for (const char* method : {"pismo", "pismo-maxdepth"}) {
        const testing::CliRun run = run_cli({"shade", "--method", method, "--scene", "contact", "--receivers",
                                             path("rx.exr"), "--out", path("out.exr"), "--light-level", "0",
                                             "--map-size", "32", "--layers", "4", "--rays", "16", "--backend", "scalar"});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        MethodSettings s;
        s.rays = 16;
        const Image expected = find_method(method).run(ctx, set, positions, s);
        EXPECT_EQ(testing::difference(read_exr(path("out.exr"), {"Y"}), expected).differing, 0) << method;
    }
    // The same maps from pismo-build's directory.
    ASSERT_EQ(run_cli({"pismo-build", "--scene", "contact", "--out", path("maps"), "--light-level", "0", "--map-size",
                       "32", "--layers", "4", "--receivers", path("rx.exr")})
                  .exit_code,
              0);
    const testing::CliRun run = run_cli({"shade", "--method", "pismo", "--pismo-maps", path("maps"), "--receivers",
                                         path("rx.exr"), "--out", path("out.exr"), "--rays", "16", "--backend", "scalar"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    MethodSettings s;
    s.rays = 16;
    EXPECT_EQ(testing::difference(read_exr(path("out.exr"), {"Y"}), find_method("pismo").run(ctx, set, positions, s))
                  .differing,
              0);
    // Positions alone: the receivers' surface is not known, and the tool shades as the library does on them.
    const Image positions_only = read_exr(path("rx.exr"), {"P.x", "P.y", "P.z"});
    write_exr(path("rx_p.exr"), positions_only, {"P.x", "P.y", "P.z"});
    const testing::CliRun alone = run_cli({"shade", "--method", "pismo", "--pismo-maps", path("maps"), "--receivers",
                                           path("rx_p.exr"), "--out", path("out.exr"), "--rays", "16", "--backend", "scalar"});
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    EXPECT_EQ(testing::difference(read_exr(path("out.exr"), {"Y"}), find_method("pismo").run(ctx, set, positions_only, s))
                  .differing,
              0);
}

TEST_F(PismoShadeCli, BadInputExitsTwoWithOneLine)
{
    const std::string rx = path("rx.exr"), out = path("out.exr");
    auto shade = [&](const std::string& extra) {
        return "shade --method pismo --receivers " + rx + " --out " + out + " --backend scalar " + extra;
    };
    expect_bad_inputs(shade, {
                                 {"--scene contact --light-level 6", "penumbra shade: option --light-level"},
                                 {"--scene contact --rays 0", "penumbra shade: option --rays"},
                                 {"--scene contact --rays 5000", "option --rays"},
                                 {"--scene hair", "penumbra shade: scene 'hair': a point light has no area"},
                                 {"--scene contact --map-size 0", "option --map-size"},
                                 {"", "--scene or --pismo-maps is required"},
                                 {"--scene contact --pismo-maps " + path("maps"), "not both"},
                                 {"--pismo-maps " + path("maps") + " --light-level 1", "--light-level"},
                                 {"--pismo-maps " + path("nowhere"), "nowhere"},
                                 {"--scene contact --shadow-map " + path("sm.exr"), "--shadow-map"},
                             });
    expect_bad_input("shade --method vsm --shadow-map " + path("sm.exr") + " --receivers " + rx + " --out " + out +
                         " --scene contact",
                     "option --scene: only pismo");
    // Receivers without world positions: the file and the channel named.
    write_exr(path("uvz.exr"), Image(3, 2, 3), {"u", "v", "z"});
    expect_bad_input("shade --method pismo --scene contact --receivers " + path("uvz.exr") + " --out " + out,
                     "uvz.exr");
}

}  // namespace
}  // namespace penumbra
