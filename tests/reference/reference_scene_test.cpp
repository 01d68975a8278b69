// The scene model: built-in scenes by name, JSON round trips, and errors that
// name the offending field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "penumbra/error.h"
#include "penumbra/reference/scene.h"
#include "support/errors.h"

namespace penumbra::reference {
namespace {

using testing::expect_error;

// A small valid scene as JSON text, with `primitives` spliced in.
std::string scene_text(const std::string& primitives)
{
    return R"({
      "name": "t",
      "light": {"shape": "rectangle", "center": [0, 5, 0], "normal": [0, -1, 0], "size": [1, 1]},
      "light_camera": {"projection": "perspective", "near": 0.5, "far": 10, "fov_degrees": 60},
      "view": {"position": [0, 3, 4], "target": [0, 0, 0], "fov_degrees": 45},
      "primitives": )" + primitives + "}";
}

const std::string kThreePrimitives = R"([
  {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]},
  {"type": "box", "center": [0, 1, 0], "size": [1, 0.1, 1]},
  {"type": "sphere", "center": [1, 1, 0], "radius": 0.5}])";

TEST(ReferenceScene, BuiltinNamesAreTheFiveFailureModesAndTheThreeDeepScenes)
{
    const std::vector<std::string> expected = {"contact", "overlap", "fence", "grazing", "large"};
    EXPECT_EQ(builtin_scene_names(), expected);
    EXPECT_EQ(builtin_scene_names(SceneSet::Opaque), expected);
    EXPECT_EQ(builtin_scene_names(SceneSet::Deep), (std::vector<std::string>{"hair", "fog", "layers"}));
    EXPECT_EQ(builtin_scene_names(SceneSet::All).size(), 8u);
    for (const std::string& name : builtin_scene_names(SceneSet::All)) {
        const Scene scene = builtin_scene(name);
        EXPECT_EQ(scene.name, name);
        EXPECT_FALSE(scene.description.empty());
        EXPECT_NO_THROW(validate_scene(scene, "test")) << name;
    }
    EXPECT_EQ(builtin_scene("large").map_size, 16384);
}

TEST(ReferenceScene, UnknownBuiltinNamesTheValidOnes)
{
    expect_error([] { builtin_scene("contcat"); }, ErrorCategory::InvalidArgument,
                 "contact, overlap, fence, grazing, large, hair, fog, layers");
}

TEST(ReferenceScene, JsonRoundTripOfEveryBuiltinIsExact)
{
    for (const std::string& name : builtin_scene_names(SceneSet::All)) {
        const Scene scene = builtin_scene(name);
        const std::string text = scene_to_json(scene);
        const Scene back = scene_from_json(text);
        EXPECT_EQ(scene_to_json(back), text) << name;
        ASSERT_EQ(back.primitives.size(), scene.primitives.size());
        EXPECT_EQ(back.media.size(), scene.media.size());
        EXPECT_EQ(back.hair.size(), scene.hair.size());
        EXPECT_EQ(back.light.shape, scene.light.shape);
        EXPECT_EQ(back.light.center, scene.light.center);
        EXPECT_EQ(back.view.position, scene.view.position);
        EXPECT_EQ(back.light_camera.fov_degrees, scene.light_camera.fov_degrees);
    }
}

TEST(ReferenceScene, FileRoundTripKeepsDiskLightAndOrthographicCamera)
{
    Scene scene = builtin_scene("contact");
    scene.light.shape = LightShape::Disk;
    scene.light.width = scene.light.height = 0.7;
    scene.light_camera.projection = Projection::Orthographic;
    scene.light_camera.extent = 12.5;
    scene.primitives.push_back(Box{{1, 2, 3}, {0.1, 0.2, 0.3}, {10, 20, 30}});
    const auto path = std::filesystem::temp_directory_path() / "penumbra_reference_scene_test.json";
    save_scene(scene, path);
    const Scene back = load_scene(path);
    std::filesystem::remove(path);
    EXPECT_EQ(back.light.shape, LightShape::Disk);
    EXPECT_EQ(back.light.width, 0.7);
    EXPECT_EQ(back.light_camera.projection, Projection::Orthographic);
    EXPECT_EQ(back.light_camera.extent, 12.5);
    const Box& box = std::get<Box>(back.primitives.back());
    EXPECT_EQ(box.rotation_degrees, (Vec3{10, 20, 30}));
    EXPECT_EQ(scene_to_json(back), scene_to_json(scene));
}

TEST(ReferenceScene, OptionalFieldsTakeTheirDefaults)
{
    const Scene scene = scene_from_json(scene_text(kThreePrimitives));
    EXPECT_EQ(scene.map_size, 1024);
    EXPECT_EQ(scene.view.up, (Vec3{0, 1, 0}));
    EXPECT_EQ(std::get<Box>(scene.primitives[1]).rotation_degrees, (Vec3{0, 0, 0}));
}

TEST(ReferenceScene, BadFieldsAreNamed)
{
    const auto load = [](const std::string& primitives) {
        return [primitives] { scene_from_json(scene_text(primitives), "bad.json"); };
    };
    const auto invalid = ErrorCategory::InvalidArgument;
    expect_error(load(R"([{"type": "plane", "point": [0,0,0], "normal": [0,1,0]},
                          {"type": "box", "center": [0,1,0], "size": [1,1,1]},
                          {"type": "sphere", "center": [1,1,0], "radius": -0.5}])"),
                 invalid, "bad.json: primitives[2].radius: must be > 0");
    expect_error(load(R"([{"type": "sphere", "center": [1,1,0]}])"), invalid, "primitives[0].radius: missing");
    expect_error(load(R"([{"type": "sphere", "center": [1,1], "radius": 1}])"), invalid,
                 "primitives[0].center: must be an array of 3 numbers");
    expect_error(load(R"([{"type": "sphere", "center": [1,1,0], "radius": "big"}])"), invalid,
                 "primitives[0].radius: must be a number");
    expect_error(load(R"([{"type": "cone", "center": [1,1,0]}])"), invalid,
                 "primitives[0].type: must be one of plane, sphere, box, capsule");
    expect_error(load(R"([{"type": "sphere", "center": [1,1,0], "radius": 1, "radus": 2}])"), invalid,
                 "primitives[0].radus: unknown field");
    expect_error(load(R"([{"type": "box", "center": [0,1,0], "size": [1,0,1]}])"), invalid,
                 "primitives[0].size[1]: must be > 0");
    expect_error(load(R"([{"type": "plane", "point": [0,0,0], "normal": [0,0,0]}])"), invalid,
                 "primitives[0].normal: must be a non-zero vector");
    expect_error(load("[]"), invalid, "primitives: must hold at least one primitive");
    expect_error(load("{}"), invalid, "primitives: must be an array");
}

TEST(ReferenceScene, BadLightAndCameraFieldsAreNamed)
{
    const auto invalid = ErrorCategory::InvalidArgument;
    std::string text = scene_text(kThreePrimitives);
    auto with = [&](const std::string& from, const std::string& to) {
        std::string changed = text;
        const auto at = changed.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        changed.replace(at, from.size(), to);
        return [changed] { scene_from_json(changed); };
    };
    expect_error(with(R"("far": 10)", R"("far": 0.2)"), invalid, "light_camera.far: must be > light_camera.near");
    expect_error(with(R"("fov_degrees": 60)", R"("fov_degrees": 180)"), invalid,
                 "light_camera.fov_degrees: must be in (0, 179)");
    expect_error(with(R"("projection": "perspective")", R"("projection": "fisheye")"), invalid,
                 "light_camera.projection: must be \"perspective\" or \"orthographic\"");
    expect_error(with(R"("size": [1, 1])", R"("size": [1, -1])"), invalid, "light.size[1]: must be > 0");
    expect_error(with(R"("shape": "rectangle")", R"("shape": "disk")"), invalid, "light.size: unknown field");
    expect_error(with(R"("target": [0, 0, 0])", R"("target": [0, 3, 4])"), invalid,
                 "view.target: must differ from view.position");
    expect_error(with(R"("name": "t",)", R"("name": "t", "map_size": 0,)"), invalid, "map_size: must be in");
}

TEST(ReferenceScene, OpaqueScenesWriteNoDeepFields)
{
    // Opacity 1, no media and no hair are the defaults and are not written,
    // so the opaque scenes' JSON is what it was before they existed.
    const std::string text = scene_to_json(builtin_scene("fence"));
    for (const char* field : {"opacity", "media", "hair"}) EXPECT_EQ(text.find(field), std::string::npos) << field;
    const Scene layers = scene_from_json(scene_to_json(builtin_scene("layers")));
    EXPECT_EQ(opacity_of(layers.primitives[3]), 0.7);
    EXPECT_EQ(opacity_of(layers.primitives[0]), 1.0);
}

TEST(ReferenceScene, BadDeepFieldsAreNamed)
{
    const auto invalid = ErrorCategory::InvalidArgument;
    const auto load = [](const std::string& primitives, const std::string& extra = "") {
        std::string text = scene_text(primitives);
        text.insert(text.rfind('}'), extra);
        return [text] { scene_from_json(text, "deep.json"); };
    };
    const std::string plane = R"([{"type": "plane", "point": [0,0,0], "normal": [0,1,0]}])";
    expect_error(load(R"([{"type": "sphere", "center": [0,1,0], "radius": 1, "opacity": 1.5}])"), invalid,
                 "deep.json: primitives[0].opacity: must be in [0, 1]");
    expect_error(load(R"([{"type": "box", "center": [0,1,0], "size": [1,1,1], "opacity": -0.1}])"), invalid,
                 "primitives[0].opacity: must be in [0, 1]");
    expect_error(load(R"([{"type": "sphere", "center": [0,1,0], "radius": 1, "opacity": "half"}])"), invalid,
                 "primitives[0].opacity: must be a number");
    expect_error(load(plane, R"(, "media": [{"type": "sphere", "center": [0,1,0], "radius": 1, "extinction": -2}])"),
                 invalid, "media[0].extinction: must be >= 0");
    expect_error(load(plane, R"(, "media": [{"type": "box", "center": [0,1,0], "size": [2,2,2], "extinction": 0.5,
                                             "gradient": [0, 1, 0]}])"),
                 invalid, "media[0].gradient: makes the extinction negative inside the region");
    expect_error(load(plane, R"(, "media": [{"type": "capsule", "a": [0,0,0], "b": [0,1,0], "radius": 1,
                                             "extinction": 1}])"),
                 invalid, "media[0].type: must be sphere or box for a medium");
    expect_error(load(plane, R"(, "media": [{"type": "sphere", "center": [0,1,0], "radius": 1}])"), invalid,
                 "media[0].extinction: missing");
    expect_error(load(plane, R"(, "media": [{"type": "sphere", "center": [0,1,0], "radius": 1, "extinction": 1,
                                             "opacity": 0.5}])"),
                 invalid, "media[0].opacity: unknown field");
    expect_error(load(plane, R"(, "media": {})"), invalid, "media: must be an array");
    const std::string hair = R"(, "hair": [{"center": [0,1,0], "scalp_radius": 0.5, "length": 0.3, "radius": 0.001,
                                            "seed": 3, )";
    expect_error(load(plane, hair + R"("strands": 0}])"), invalid, "hair[0].strands: must be in [1, 1048576]");
    expect_error(load(plane, hair + R"("strands": 10.5}])"), invalid, "hair[0].strands: must be an integer");
    expect_error(load(plane, hair + R"("strands": 10, "segments": 65}])"), invalid, "hair[0].segments: must be in [1, 64]");
    expect_error(load(plane, hair + R"("strands": 10, "opacity": 2}])"), invalid, "hair[0].opacity: must be in [0, 1]");
    expect_error(load(plane, hair + R"("strands": 10, "cap_degrees": 0}])"), invalid,
                 "hair[0].cap_degrees: must be in (0, 180]");
    expect_error(load(plane, hair + R"("strands": 100000, "segments": 64}])"), invalid,
                 "hair[0].strands: strands x segments must be <= 1048576");
    expect_error(load(plane, R"(, "hair": [{"center": [0,1,0], "scalp_radius": 0.5, "length": 0.3, "radius": 0.001,
                                            "strands": 10, "seed": -1}])"),
                 invalid, "hair[0].seed: must be an integer in [0, 2^64)");
    std::string point = scene_text(plane);
    point.replace(point.find(R"("shape": "rectangle")"), 20, R"("shape": "point")");
    expect_error([point] { scene_from_json(point); }, invalid, "light.size: unknown field");
    point.replace(point.find(R"(, "size": [1, 1])"), 16, "");
    EXPECT_EQ(scene_from_json(point).light.shape, LightShape::Point);
}

TEST(ReferenceScene, ScenesBuiltInCodeGetTheSameDeepChecks)
{
    const auto invalid = ErrorCategory::InvalidArgument;
    Scene scene = builtin_scene("layers");
    std::get<Box>(scene.primitives[1]).opacity = std::nan("");
    expect_error([&] { validate_scene(scene, "test"); }, invalid, "primitives[1].opacity: must be a finite number");
    scene = builtin_scene("fog");
    std::get<Box>(scene.media[0].region).opacity = 0.5;
    expect_error([&] { validate_scene(scene, "test"); }, invalid, "media[0].opacity: a medium has no surface opacity");
    scene = builtin_scene("hair");
    scene.light.width = 0.1;
    expect_error([&] { validate_scene(scene, "test"); }, invalid, "light.size: must be 0 x 0 for a point light");
    scene = builtin_scene("hair");
    scene.hair[0].radius = 0;
    expect_error([&] { validate_scene(scene, "test"); }, invalid, "hair[0].radius: must be > 0");
}

TEST(ReferenceScene, UnreadableOrMalformedFilesAreIoErrors)
{
    expect_error([] { load_scene("/nonexistent/penumbra/scene.json"); }, ErrorCategory::Io,
                 "'/nonexistent/penumbra/scene.json' does not exist");
    expect_error([] { scene_from_json("{ \"name\": ", "broken.json"); }, ErrorCategory::Io,
                 "broken.json: not valid JSON");
    expect_error([] { scene_from_json("[1, 2]", "list.json"); }, ErrorCategory::InvalidArgument,
                 "list.json: (document): must be a JSON object");
}

}  // namespace
}  // namespace penumbra::reference
