// Pismo's surface ids through the tool (docs/pismo.md, "Surface ids in the
// files"): render-scene's RX.exr carries channel surface, and `shade --method
// pismo` uses it with maps rendered from --scene or read from pismo-build's
// directory, on every backend, giving the library's image with ids exactly;
// on fence the ids change the answer. Bad ids exit with 2 and one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "penumbra/exr_io.h"
#include "penumbra/methods.h"
#include "penumbra/pismo_files.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/render.h"
#include "support/backends.h"
#include "support/cli.h"
#include "support/maps.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

using testing::run_cli;

constexpr int kViewWidth = 24, kViewHeight = 18, kMapSize = 96, kRays = 16;
const std::vector<std::string> kPositionsNormals = {"P.x", "P.y", "P.z", "N.x", "N.y", "N.z"};

std::vector<std::string> with_surface()
{
    std::vector<std::string> channels = kPositionsNormals;
    channels.push_back("surface");
    return channels;
}

// `--backend` and the environment that run the tool on the test's backend.
std::vector<std::string> backend_args(const std::string& backend)
{
    return {"--backend", backend == "scalar" || backend == "opencl" ? backend : "simd"};
}
std::map<std::string, std::string> backend_environment(const std::string& backend)
{
    if (backend == "scalar" || backend == "opencl") return {};
    return {{"PENUMBRA_SIMD_ISA", backend}};
}

class PismoIdsCli : public testing::CliFixture {
protected:
    void SetUp() override
    {
        CliFixture::SetUp();
        ASSERT_EQ(run_cli({"render-scene", "fence", "--shadow-map", path("sm.exr"), "--receivers", path("rx.exr"),
                           "--truth", path("gt.exr"), "--map-size", "8", "--view-size",
                           std::to_string(kViewWidth) + "x" + std::to_string(kViewHeight), "--samples", "1"})
                      .exit_code,
                  0);
    }
    // The library's maps for what the tool renders from --scene fence (level 0).
    static PismoMapSet fence_set()
    {
        const reference::Scene scene = reference::builtin_scene("fence");
        reference::LayeredMapOptions o;
        o.size = kMapSize;
        return reference::render_pismo_map_set(scene, 0, o,
                                               reference::receiver_region(reference::render_receivers(scene, kViewWidth, kViewHeight)));
    }
    testing::CliRun build_maps()
    {
        return run_cli({"pismo-build", "--scene", "fence", "--out", path("maps"), "--light-level", "0", "--map-size",
                        std::to_string(kMapSize), "--receivers", path("rx.exr")});
    }
    testing::CliRun shade(const std::string& backend, const std::vector<std::string>& maps, const std::string& rx)
    {
        std::vector<std::string> args = {"shade", "--method", "pismo", "--receivers", rx, "--out", path("out.exr"),
                                         "--rays", std::to_string(kRays)};
        args.insert(args.end(), maps.begin(), maps.end());
        for (const std::string& a : backend_args(backend)) args.push_back(a);
        return run_cli(args, backend_environment(backend));
    }
    // RX.exr with channel surface set to `id` at pixel (x, y), or without normals.
    std::string edited_receivers(const std::string& name, float id, int x = 3, int y = 2, bool normals = true)
    {
        const std::vector<std::string> names = exr_channel_names(path("rx.exr"));
        Image rx = read_exr(path("rx.exr"), names);
        const auto at = [&](const std::string& n) { return int(std::find(names.begin(), names.end(), n) - names.begin()); };
        rx.at(at("surface"), x, y) = id;
        std::vector<std::string> kept = names;
        if (!normals) std::erase_if(kept, [](const std::string& n) { return n.rfind("N.", 0) == 0; });
        Image out(rx.width(), rx.height(), int(kept.size()));
        for (int c = 0; c < out.channels(); ++c)
            for (int yy = 0; yy < rx.height(); ++yy)
                for (int xx = 0; xx < rx.width(); ++xx) out.at(c, xx, yy) = rx.at(at(kept[std::size_t(c)]), xx, yy);
        write_exr(path(name), out, kept);
        return path(name);
    }
};

class PismoIdsCliBackends : public PismoIdsCli, public ::testing::WithParamInterface<std::string> {};

TEST_F(PismoIdsCli, RenderSceneWritesEachReceiversSurface)
{
    const reference::Receivers rx = reference::render_receivers(reference::builtin_scene("fence"), kViewWidth, kViewHeight);
    const Image stored = read_exr(path("rx.exr"), {"surface"});
    EXPECT_EQ(testing::difference(stored, rx.surface).differing, 0);
}

TEST_P(PismoIdsCliBackends, TheToolsImageWithIdsIsTheLibrarysAndDiffersFromWithout)
{
    std::string why;
    Context* ctx = testing::shared_context(GetParam(), &why);
    if (!ctx) GTEST_SKIP() << why;
    const PismoMapSet set = fence_set();
    const Image with_ids = read_exr(path("rx.exr"), with_surface());
    MethodSettings s;
    s.rays = kRays;
    const Method& pismo = find_method("pismo");
    const Image expected = pismo.run(*ctx, set, with_ids, s);
    const testing::CliRun scene = shade(GetParam(), {"--scene", "fence", "--light-level", "0", "--map-size",
                                                     std::to_string(kMapSize)}, path("rx.exr"));
    ASSERT_EQ(scene.exit_code, 0) << scene.err;
    EXPECT_EQ(testing::difference(read_exr(path("out.exr"), {"Y"}), expected).differing, 0) << "--scene";

    ASSERT_EQ(build_maps().exit_code, 0);
    const testing::CliRun files = shade(GetParam(), {"--pismo-maps", path("maps")}, path("rx.exr"));
    ASSERT_EQ(files.exit_code, 0) << files.err;
    EXPECT_TRUE(files.err.empty()) << files.err;
    EXPECT_EQ(testing::difference(read_exr(path("out.exr"), {"Y"}), expected).differing, 0) << "--pismo-maps";

    const Image without = pismo.run(*ctx, set, read_exr(path("rx.exr"), kPositionsNormals), s);
    int changed = 0;
    for (int y = 0; y < kViewHeight; ++y)
        for (int x = 0; x < kViewWidth; ++x) changed += std::fabs(expected.at(0, x, y) - without.at(0, x, y)) > 0.01f;
    EXPECT_GE(changed, 3) << "on fence the ids change the answer (the rails on the pickets)";
}

INSTANTIATE_TEST_SUITE_P(Backends, PismoIdsCliBackends, ::testing::ValuesIn(testing::backend_names()),
                         testing::backend_test_name);

TEST_F(PismoIdsCli, BadSurfaceIdsExitTwoWithOneLine)
{
    const auto shade_with = [&](const std::string& rx) {
        return "shade --method pismo --scene fence --light-level 0 --map-size 16 --rays 4 --backend scalar --receivers " +
               rx + " --out " + path("out.exr");
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    expect_bad_input(shade_with(edited_receivers("neg.exr", -2.0f)), "channel surface at pixel (3, 2) is -2");
    expect_bad_input(shade_with(edited_receivers("half.exr", 2.5f)), "is 2.5; a surface id is -1 (unknown)");
    expect_bad_input(shade_with(edited_receivers("nan.exr", nan)), "channel surface at pixel (3, 2) is nan");
    expect_bad_input(shade_with(edited_receivers("far.exr", 99.0f)), "render the receivers from the maps' scene");
    expect_bad_input(shade_with(edited_receivers("plain.exr", 0.0f, 3, 2, false)), "not the normals");
}

// Maps written before format version 2 carry no ids: the receivers' ids are
// shaded as unknown, as without the channel, and the tool says so.
TEST_F(PismoIdsCli, AVersionOneSetShadesWithoutIdsAndSaysSo)
{
    ASSERT_EQ(build_maps().exit_code, 0);
    PismoMapSet set = read_pismo_maps(path("maps"));
    set.surface_ids.clear(), set.surface_count = 0;
    write_pismo_maps(path("maps"), set);
    nlohmann::json manifest = nlohmann::json::parse(testing::slurp(path("maps/pismo.json")));
    manifest["version"] = 1;
    std::ofstream(path("maps/pismo.json")) << manifest.dump();
    const testing::CliRun run = shade("scalar", {"--pismo-maps", path("maps")}, path("rx.exr"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("warning: " + path("rx.exr") + " has surface ids but the maps carry none"), std::string::npos)
        << run.err;
    Context ctx(ContextOptions{Backend::Scalar, {}});
    MethodSettings s;
    s.rays = kRays;
    const Image without = find_method("pismo").run(ctx, set, read_exr(path("rx.exr"), kPositionsNormals), s);
    EXPECT_EQ(testing::difference(read_exr(path("out.exr"), {"Y"}), without).differing, 0);
}

// A map file whose ids the manifest does not cover: exit 2, one line naming it.
TEST_F(PismoIdsCli, AMapWithAnIdPastTheManifestsCountExitsTwo)
{
    ASSERT_EQ(build_maps().exit_code, 0);
    nlohmann::json manifest = nlohmann::json::parse(testing::slurp(path("maps/pismo.json")));
    manifest["surfaces"] = 1;  // fence's casters are surfaces 1 and up (the ground, 0, is in no map)
    std::ofstream(path("maps/pismo.json")) << manifest.dump();
    expect_bad_input("shade --method pismo --pismo-maps " + path("maps") + " --receivers " + path("rx.exr") +
                         " --out " + path("out.exr") + " --backend scalar",
                     "is not below the manifest's \"surfaces\", 1");
    manifest["surfaces"] = "all";
    std::ofstream(path("maps/pismo.json")) << manifest.dump();
    expect_bad_input("shade --method pismo --pismo-maps " + path("maps") + " --receivers " + path("rx.exr") +
                         " --out " + path("out.exr") + " --backend scalar",
                     "field \"surfaces\" is \"all\"");
}

}  // namespace
}  // namespace penumbra
