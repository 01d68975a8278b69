// `penumbra ambient` run as a user would: the output equals the library's for
// a light rig, a blend by volumes and a scene's "ambient" field; bad input
// (NaN in a rig, no lights, a zero-scale volume, malformed JSON, a zero
// normal, a missing channel) exits with 2 and one line naming the field,
// pixel or option, leaving an existing output alone.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "penumbra/ambient.h"
#include "penumbra/exr_io.h"
#include "penumbra/reference.h"
#include "penumbra/reference/ambient_json.h"
#include "support/cli.h"

namespace penumbra {
namespace {

const char* kRig = R"({"lights": [{"direction": [0, 1, 0], "color": [1, 0.9, 0.8], "intensity": 1.0},
                                  {"direction": [0, -1, 0], "intensity": -0.3},
                                  {"direction": [1, 0, 0], "color": [0.5, 0.6, 1.0], "intensity": 0.4}]})";
const char* kDark = R"({"lights": [{"direction": [0, 1, 0], "intensity": 0.1}]})";
const char* kVolumes = R"({"volumes": [
    {"shape": "box", "center": [0, 0, 0], "half_size": [1.5, 1, 1.5], "rotation_degrees": [0, 30, 0],
     "scale_bias": 1.05, "falloff_delay": 0.5},
    {"shape": "sphere", "center": [1, 0, 1], "radius": 0.8}]})";

class AmbientCli : public testing::CliFixture {
protected:
    void SetUp() override
    {
        CliFixture::SetUp();
        const reference::Scene scene = reference::builtin_scene("contact");
        rx_ = reference::render_receivers(scene, 23, 17);
        write("rig.json", kRig);
        write("dark.json", kDark);
        write("volumes.json", kVolumes);
        write_receivers("rx.exr", rx_.normal);
    }

    void write(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }

    void write_receivers(const std::string& name, const Image& normals) const
    {
        Image all(normals.width(), normals.height(), 6);
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < normals.height(); ++y)
                for (int x = 0; x < normals.width(); ++x) {
                    all.at(c, x, y) = rx_.world_position.at(c, x, y);
                    all.at(3 + c, x, y) = normals.at(c, x, y);
                }
        write_exr(path(name), all, {"P.x", "P.y", "P.z", "N.x", "N.y", "N.z"});
    }

    std::string ambient(const std::string& extra) const
    {
        return "ambient --receivers " + path("rx.exr") + " --out " + path("out.exr") + " " + extra;
    }

    // The library's result for the same inputs, on the scalar backend.
    Image expected(const AmbientLighting& l) const
    {
        Context ctx(ContextOptions{Backend::Scalar, {}});
        Image rx(rx_.normal.width(), rx_.normal.height(), ambient_receiver_channels(l));
        for (int y = 0; y < rx.height(); ++y)
            for (int x = 0; x < rx.width(); ++x)
                for (int c = 0; c < 3; ++c) {
                    rx.at(c, x, y) = rx_.normal.at(c, x, y);
                    if (rx.channels() == 6) rx.at(3 + c, x, y) = rx_.world_position.at(c, x, y);
                }
        return ambient_irradiance(ctx, rx, l);
    }

    void expect_output(const AmbientLighting& l) const
    {
        const Image got = read_exr(path("out.exr"), {"R", "G", "B"});
        const Image want = expected(l);
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < got.height(); ++y)
                for (int x = 0; x < got.width(); ++x) ASSERT_NEAR(got.at(c, x, y), want.at(c, x, y), 2e-5);
    }

    reference::Receivers rx_;
};

TEST_F(AmbientCli, LightRigMatchesTheLibrary)
{
    const testing::ToolRun r = run(ambient("--rig " + path("rig.json") + " --backend scalar"));
    ASSERT_EQ(r.status, 0) << r.err;
    AmbientLighting l;
    l.light = project_rig(reference::load_rig(path("rig.json")));
    expect_output(l);
}

TEST_F(AmbientCli, VolumesBlendTowardsTheDarkRig)
{
    const testing::ToolRun r = run(ambient("--rig " + path("rig.json") + " --dark-rig " + path("dark.json") +
                                           " --volumes " + path("volumes.json") + " --cheap-dark"));
    ASSERT_EQ(r.status, 0) << r.err;
    AmbientLighting l;
    l.light = project_rig(reference::load_rig(path("rig.json")));
    l.dark = project_rig(reference::load_rig(path("dark.json")));
    l.volumes = AmbientVolumes(reference::load_volumes(path("volumes.json")));
    l.cheap_dark = true;
    expect_output(l);
}

TEST_F(AmbientCli, ASceneCarriesItsRigAndVolumes)
{
    reference::Scene scene = reference::builtin_scene("contact");
    scene.ambient = reference::SceneAmbient{reference::load_rig(path("rig.json")), reference::load_rig(path("dark.json")),
                                            reference::load_volumes(path("volumes.json"))};
    reference::save_scene(scene, path("scene.json"));
    const testing::ToolRun r = run(ambient("--scene " + path("scene.json")));
    ASSERT_EQ(r.status, 0) << r.err;
    AmbientLighting l;
    l.light = project_rig(scene.ambient->rig);
    l.dark = project_rig(*scene.ambient->dark_rig);
    l.volumes = AmbientVolumes(scene.ambient->volumes);
    expect_output(l);
    const reference::Scene again = reference::load_scene(path("scene.json"));
    ASSERT_TRUE(again.ambient);
    EXPECT_EQ(again.ambient->volumes.size(), 2u);
}

// A normals image of its own (R, G, B here), and its zero normal named by file.
TEST_F(AmbientCli, NormalsFromTheirOwnFile)
{
    write_exr(path("n.exr"), rx_.normal, {"R", "G", "B"});
    const std::string args = ambient("--rig " + path("rig.json") + " --dark-rig " + path("dark.json") + " --volumes " +
                                     path("volumes.json") + " --normals " + path("n.exr"));
    const testing::ToolRun r = run(args);
    ASSERT_EQ(r.status, 0) << r.err;
    AmbientLighting l;
    l.light = project_rig(reference::load_rig(path("rig.json")));
    l.dark = project_rig(reference::load_rig(path("dark.json")));
    l.volumes = AmbientVolumes(reference::load_volumes(path("volumes.json")));
    expect_output(l);
    Image zero = rx_.normal;
    for (int c = 0; c < 3; ++c) zero.at(c, 2, 1) = 0.0f;
    write_exr(path("n.exr"), zero, {"R", "G", "B"});
    expect_bad_input(args, "n.exr: pixel (2, 1) of the receivers: the normal is zero");
}

TEST_F(AmbientCli, BadInputExitsWithOneLine)
{
    write("nan.json", R"({"lights": [{"direction": [0, 1, 0], "intensity": NaN}]})");
    write("huge.json", R"({"lights": [{"direction": [0, 1e999, 0]}]})");
    write("empty.json", R"({"lights": []})");
    write("zero.json", R"({"lights": [{"direction": [0, 0, 0]}]})");
    write("typo.json", R"({"lights": [{"direction": [0, 1, 0], "intensty": 2}]})");
    write("badtype.json", R"({"lights": [{"direction": [0, "up", 0]}]})");
    write("flat.json", R"({"volumes": [{"shape": "box", "center": [0, 0, 0], "half_size": [1, 0, 1]}]})");
    write("cone.json", R"({"volumes": [{"shape": "cone", "center": [0, 0, 0], "radius": 1}]})");
    write("broken.json", R"({"lights": [)");
    write("novolumes.json", R"({"volumes": []})");
    const std::string rig = "--rig " + path("rig.json");
    const std::string dark = " --dark-rig " + path("dark.json");
    expect_bad_input(ambient("--rig " + path("nan.json")), "not valid JSON");
    expect_bad_input(ambient("--rig " + path("huge.json")), "not valid JSON");
    expect_bad_input(ambient("--rig " + path("empty.json")), "lights: must hold at least one light");
    EXPECT_EQ(run(ambient("--rig " + path("empty.json"))).err.rfind("penumbra ambient: ", 0), 0u)
        << "the line is the command's, not its JSON reader's";
    expect_bad_input(ambient("--rig " + path("zero.json")), "lights[0].direction is zero");
    expect_bad_input(ambient("--rig " + path("typo.json")), "lights[0].intensty: unknown field");
    expect_bad_input(ambient("--rig " + path("badtype.json")), "lights[0].direction: must be an array of 3 numbers");
    expect_bad_input(ambient("--rig " + path("broken.json")), "broken.json: not valid JSON");
    expect_bad_input(ambient(rig + dark + " --volumes " + path("flat.json")), "volumes[0].half_size");
    expect_bad_input(ambient(rig + dark + " --volumes " + path("cone.json")), "volumes[0].shape: must be sphere or box");
    expect_bad_input(ambient(rig + dark + " --volumes " + path("novolumes.json")), "volumes: must hold at least one volume");
    expect_bad_input(ambient(rig + " --volumes " + path("volumes.json")), "--dark-rig");
    expect_bad_input(ambient(rig + dark), "blend");
    expect_bad_input(ambient(rig + " --order 3"), "--order");
    expect_bad_input(ambient(rig + " --window gauss"), "--window");
    Image normals = rx_.normal;
    for (int c = 0; c < 3; ++c) normals.at(c, 4, 3) = 1.0f;
    for (int c = 0; c < 3; ++c) normals.at(c, 5, 3) = 0.0f;
    write_receivers("rx.exr", normals);
    expect_bad_input(ambient(rig), "pixel (5, 3) of the receivers: the normal is zero");
    expect_bad_input(ambient(rig), "--zero-normals black");
    const testing::ToolRun black = run(ambient(rig + " --zero-normals black"));
    EXPECT_EQ(black.status, 0) << black.err;
}

}  // namespace
}  // namespace penumbra
