// `penumbra sdf-shade` and `sdf-bake` run as a user would: results equal to
// the library's, exit status 2 and one line naming the file, channel or option
// on bad input, and an existing output left alone by a failed run.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "penumbra/exr_io.h"
#include "penumbra/reference.h"
#include "penumbra/reference/sdf_scene.h"
#include "penumbra/sdf.h"

#include "support/cli.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

using testing::slurp;

class SdfCli : public testing::CliFixture {
protected:
    void SetUp() override
    {
        CliFixture::SetUp();
        scene_ = reference::builtin_scene("contact");
        rx_ = reference::render_receivers(scene_, 23, 17);
        write_receivers("rx.exr", rx_.world_position, rx_.normal);
    }


    // The render-scene layout: u, v, z, P.*, N.* (only the P and N planes matter).
    void write_receivers(const std::string& name, const Image& p, const Image& n) const
    {
        Image all(p.width(), p.height(), 9);
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < p.height(); ++y)
                for (int x = 0; x < p.width(); ++x) {
                    all.at(3 + c, x, y) = p.at(c, x, y);
                    all.at(6 + c, x, y) = n.at(c, x, y);
                }
        write_exr(path(name), all, {"u", "v", "z", "P.x", "P.y", "P.z", "N.x", "N.y", "N.z"});
    }

    std::string shade(const std::string& extra) const
    {
        return "sdf-shade --receivers " + path("rx.exr") + " --out " + path("out.exr") + " " + extra;
    }

    void expect_equal(const Image& got, const Image& want) const
    {
        ASSERT_EQ(got.width(), want.width());
        ASSERT_EQ(got.height(), want.height());
        for (int y = 0; y < got.height(); ++y)
            for (int x = 0; x < got.width(); ++x) ASSERT_EQ(got.at(0, x, y), want.at(0, x, y)) << x << "," << y;
    }

    reference::Scene scene_;
    reference::Receivers rx_;
};

TEST_F(SdfCli, SceneAndGridMatchTheLibrary)
{
    Context ctx(ContextOptions{Backend::Scalar, {}});
    for (const std::string estimate : {"classic", "improved", "inner"}) {
        const testing::ToolRun r = run(shade("--scene contact --backend scalar --steps --estimate " + estimate));
        ASSERT_EQ(r.status, 0) << r.err;
        const SdfOptions o = sdf_options_for(scene_, estimate == "classic"    ? SdfEstimate::Classic
                                                     : estimate == "improved" ? SdfEstimate::Improved
                                                                              : SdfEstimate::InnerPenumbra);
        expect_equal(read_exr(path("out.exr"), {"Y"}),
                     sdf_shadows(ctx, reference::analytic_scene(scene_.primitives), rx_.world_position, &rx_.normal, o));
        EXPECT_GE(read_exr(path("out.exr"), {"steps"}).at(0, 11, 8), 1.0f);
    }
    ASSERT_EQ(run("sdf-bake --scene contact --voxel 0.1 --out " + path("g.pnsdf")).status, 0);
    const DistanceGrid grid = read_distance_grid(path("g.pnsdf"));
    ASSERT_EQ(run(shade("--scene contact --source grid --voxel 0.1 --backend scalar")).status, 0);
    const SdfOptions o = sdf_options_for(scene_);
    const Image from_grid = sdf_shadows(ctx, grid, rx_.world_position, &rx_.normal, o);
    expect_equal(read_exr(path("out.exr"), {"Y"}), from_grid);
    ASSERT_EQ(run(shade("--grid " + path("g.pnsdf") + " --k " + std::to_string(o.k) +
                        " --light-width 1.5 --light-position -2.5,9,-1.5 "
                        "--hit-epsilon " + std::to_string(o.hit_epsilon) + " --t-min " + std::to_string(o.t_min) +
                        " --normal-offset " + std::to_string(o.normal_offset) + " --max-steps 256 --backend scalar"))
                  .status,
              0);
    Image again = read_exr(path("out.exr"), {"Y"});
    double worst = 0;
    for (int y = 0; y < again.height(); ++y)
        for (int x = 0; x < again.width(); ++x)
            worst = std::max(worst, double(std::abs(again.at(0, x, y) - from_grid.at(0, x, y))));
    EXPECT_LT(worst, 1e-3) << "the same settings given as options (epsilons rounded to 6 digits)";
}

TEST_F(SdfCli, RejectsBadFilesAndChannels)
{
    expect_bad_input(shade("--scene nowhere"), "nowhere");
    expect_bad_input("sdf-shade --scene contact --receivers " + path("missing.exr") + " --out " + path("out.exr"),
                     "missing.exr");
    Image p = rx_.world_position;
    p.at(1, 4, 3) = NAN;
    write_receivers("nan.exr", p, rx_.normal);
    expect_bad_input("sdf-shade --scene contact --receivers " + path("nan.exr") + " --out " + path("out.exr"),
                     "nan.exr: channel P.y at pixel (4, 3)");
    write_exr(path("p_only.exr"), rx_.world_position, {"P.x", "P.y", "P.z"});
    expect_bad_input("sdf-shade --scene contact --receivers " + path("p_only.exr") + " --out " + path("out.exr"),
                     "N.x, N.y, N.z");
    EXPECT_EQ(run("sdf-shade --scene contact --normal-offset 0 --receivers " + path("p_only.exr") + " --out " +
                  path("ok.exr"))
                  .status,
              0);
    write_exr(path("uvz.exr"), rx_.light_uvz, {"u", "v", "z"});
    expect_bad_input("sdf-shade --scene contact --receivers " + path("uvz.exr") + " --out " + path("out.exr"),
                     "P.x");
    std::ofstream(path("bad.pnsdf")) << "garbage";
    expect_bad_input(shade("--grid " + path("bad.pnsdf") + " --k 4 --light-direction 0,1,0"), "bad.pnsdf");
    DistanceGrid g(3, 3, 3, {-1, -1, -1}, 1.0);
    g.at(1, 2, 0) = NAN;
    std::ofstream raw(path("nan.pnsdf"), std::ios::binary);
    raw.write("PNSDFGR1", 8);
    for (int n : {3, 3, 3}) raw.write(reinterpret_cast<const char*>(&n), 4);
    const float header[4] = {-1, -1, -1, 1};
    raw.write(reinterpret_cast<const char*>(header), 16);
    raw.write(reinterpret_cast<const char*>(g.data()), 27 * 4);
    raw.close();
    expect_bad_input(shade("--grid " + path("nan.pnsdf") + " --k 4 --light-direction 0,1,0"),
                     "nan.pnsdf: node (1, 2, 0) is nan");
}

TEST_F(SdfCli, RejectsBadOptions)
{
    expect_bad_inputs([&](const std::string& options) { return shade(options); },
                      {
                          {"--scene contact --k 0", "--k"},
                          {"--scene contact --k -2", "--k"},
                          {"--scene contact --t-min 2 --t-max 1", "--t-max"},
                          {"--scene contact --t-max 0", "--t-max"},
                          {"--scene contact --max-steps 0", "--max-steps"},
                          {"--scene contact --hit-epsilon 0", "--hit-epsilon"},
                          {"--scene contact --estimate better", "--estimate"},
                          {"--scene contact --source voxels", "--source"},
                          {"--scene contact --voxel 0.1", "--voxel"},
                          {"--scene contact --source grid --voxel -1", "--voxel"},
                          {"--scene contact --light-position 1,2", "--light-position"},
                          {"--scene contact --light-direction 0,0,0", "--light-direction"},
                          {"--scene contact --light-direction 0,1,0 --light-width 1", "--light-width"},
                          {"--scene contact --backend cuda", "backend"},
                          {"", "--scene and --grid"},
                          {"--scene contact --grid g.pnsdf", "--scene and --grid"},
                          {"--grid g.pnsdf --light-direction 0,1,0", "--k"},
                          {"--grid g.pnsdf --k 3", "--light-position or --light-direction"},
                      });
    expect_bad_input("sdf-bake --scene contact --out " + path("out.exr") + " --margin 1", "--margin");
    expect_bad_input("sdf-bake --scene contact --out " + path("out.exr") + " --voxel 0", "--voxel");
}

}  // namespace
}  // namespace penumbra
