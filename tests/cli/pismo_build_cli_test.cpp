// `penumbra pismo-build`: the directory it writes reads back as the set the
// library renders with the same options, exactly; with --receivers the
// cameras are fitted to them; bad options exit with 2 and one line naming the
// option or the scene, leaving the directory without a manifest.
#include <gtest/gtest.h>

#include <filesystem>

#include "penumbra/exr_io.h"
#include "penumbra/pismo_files.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/render.h"
#include "support/cli.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

using testing::run_cli;

class PismoBuildCli : public testing::CliFixture {};

void expect_same_set(const PismoMapSet& a, const PismoMapSet& b)
{
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.surface_ids, b.surface_ids);  // each layer's surface id, stored since format version 2
    EXPECT_EQ(a.surface_count, b.surface_count);
    ASSERT_EQ(a.maps.size(), b.maps.size());
    for (std::size_t v = 0; v < a.maps.size(); ++v) {
        EXPECT_EQ(a.maps[v].offsets(), b.maps[v].offsets()) << v;
        EXPECT_EQ(a.maps[v].depths(), b.maps[v].depths()) << v;
        EXPECT_EQ(a.maps[v].camera().tan_half_fov, b.maps[v].camera().tan_half_fov) << v;
    }
}

TEST_F(PismoBuildCli, WritesTheLibrarysMapsAndTheyReadBack)
{
    const testing::CliRun run = run_cli({"pismo-build", "--scene", "contact", "--out", path("maps"), "--light-level",
                                         "1", "--map-size", "12", "--layers", "3"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << run.out;
    EXPECT_NE(run.out.find("9 maps of 12^2"), std::string::npos) << run.out;
    reference::LayeredMapOptions o;
    o.size = 12;
    o.max_layers = 3;
    expect_same_set(read_pismo_maps(path("maps")), reference::render_pismo_map_set(reference::builtin_scene("contact"), 1, o));
}

TEST_F(PismoBuildCli, FitsTheCamerasToTheReceivers)
{
    ASSERT_EQ(run_cli({"render-scene", "overlap", "--shadow-map", path("sm.exr"), "--receivers", path("rx.exr"),
                       "--truth", path("gt.exr"), "--map-size", "8", "--view-size", "16x12", "--samples", "1"})
                  .exit_code,
              0);
    const testing::CliRun run = run_cli({"pismo-build", "--scene", "overlap", "--out", path("maps"), "--light-level",
                                         "0", "--map-size", "8", "--receivers", path("rx.exr")});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("fitted to the receivers"), std::string::npos) << run.out;
    const reference::Scene scene = reference::builtin_scene("overlap");
    reference::LayeredMapOptions o;
    o.size = 8;
    const std::vector<reference::Vec3> region = reference::receiver_region(reference::render_receivers(scene, 16, 12));
    expect_same_set(read_pismo_maps(path("maps")), reference::render_pismo_map_set(scene, 0, o, region));
}

TEST_F(PismoBuildCli, RefusesBadOptionsWithOneLine)
{
    const std::string out = path("maps");
    auto build = [&](const std::string& extra) { return "pismo-build --scene contact --out " + out + " " + extra; };
    expect_bad_inputs(build, {
                                 {"--light-level 6", "--light-level"},
                                 {"--light-level -1", "--light-level"},
                                 {"--map-size 0", "--map-size"},
                                 {"--layers 65", "--layers"},
                                 {"--receivers " + path("missing.exr"), "missing.exr"},
                                 {"--light-level 5 --map-size 8192", "over the limit"},
                                 {"--light-level 1 --map-size 8 --max-pixels 575", "raise --max-pixels"},
                             });
    expect_bad_input("pismo-build --scene hair --out " + out, "scene 'hair': a point light has no area");
    expect_bad_input("pismo-build --scene contact --out " + path("out.exr"), "--out");
    EXPECT_FALSE(std::filesystem::exists(path("maps/pismo.json")));
}

}  // namespace
}  // namespace penumbra
