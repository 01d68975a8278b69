// Scenes to and from JSON (the field list is in docs/reference.md).
//
// Reading walks the document with the path of each value in hand, so that
// every complaint names the field ("primitives[2].radius: missing"). Unknown
// keys are rejected too: a misspelt optional field would otherwise be
// silently ignored and the scene quietly different from what was written.
// Range checks live in validate_scene, shared with scenes built in code.
#include <cstdint>
#include <fstream>
#include <sstream>

#include "ambient_json_parts.h"
#include "json_reader.h"
#include "penumbra/error.h"
#include "penumbra/input_file.h"
#include "penumbra/reference/scene.h"
#include "scene_json_deep.h"

namespace penumbra::reference {

json to_json(Vec3 v) { return json::array({v.x, v.y, v.z}); }

Primitive read_shape(const Reader& r, const json& j, const std::string& at, std::initializer_list<std::string_view> extra)
{
    const std::string type = r.string(j, at, "type");
    if (type == "plane") {
        r.only_keys(j, at, {"type", "point", "normal"}, extra);
        return Plane{r.vec3(j, at, "point"), r.vec3(j, at, "normal")};
    }
    if (type == "sphere") {
        r.only_keys(j, at, {"type", "center", "radius"}, extra);
        return Sphere{r.vec3(j, at, "center"), r.number(j, at, "radius")};
    }
    if (type == "box") {
        r.only_keys(j, at, {"type", "center", "size", "rotation_degrees"}, extra);
        return Box{r.vec3(j, at, "center"), r.vec3(j, at, "size"), r.vec3_or(j, at, "rotation_degrees", {})};
    }
    if (type == "capsule") {
        r.only_keys(j, at, {"type", "a", "b", "radius"}, extra);
        return Capsule{r.vec3(j, at, "a"), r.vec3(j, at, "b"), r.number(j, at, "radius")};
    }
    r.fail(at + ".type", "must be one of plane, sphere, box, capsule (got \"" + type + "\")");
}

json shape_to_json(const Primitive& primitive)
{
    struct Writer {
        json operator()(const Plane& p) const
        {
            return {{"type", "plane"}, {"point", to_json(p.point)}, {"normal", to_json(p.normal)}};
        }
        json operator()(const Sphere& s) const
        {
            return {{"type", "sphere"}, {"center", to_json(s.center)}, {"radius", s.radius}};
        }
        json operator()(const Box& b) const
        {
            return {{"type", "box"},
                    {"center", to_json(b.center)},
                    {"size", to_json(b.size)},
                    {"rotation_degrees", to_json(b.rotation_degrees)}};
        }
        json operator()(const Capsule& c) const
        {
            return {{"type", "capsule"}, {"a", to_json(c.a)}, {"b", to_json(c.b)}, {"radius", c.radius}};
        }
    };
    return std::visit(Writer{}, primitive);
}

namespace {

// A shape and its optional opacity (1, opaque, when absent).
Primitive read_primitive(const Reader& r, const json& j, const std::string& at)
{
    Primitive primitive = read_shape(r, j, at, {"opacity"});
    const double opacity = r.number_or(j, at, "opacity", 1);
    std::visit([&](auto& shape) { shape.opacity = opacity; }, primitive);
    return primitive;
}

std::vector<Primitive> read_primitives(const Reader& r, const json& root)
{
    const json& list = r.member(root, "", "primitives");
    if (!list.is_array()) r.fail("primitives", "must be an array");
    std::vector<Primitive> primitives;
    for (std::size_t i = 0; i < list.size(); ++i)
        primitives.push_back(read_primitive(r, list[i], "primitives[" + std::to_string(i) + "]"));
    return primitives;
}

AreaLight read_light(const Reader& r, const json& root)
{
    const json& j = r.member(root, "", "light");
    AreaLight light;
    const std::string shape = r.string(j, "light", "shape");
    light.center = r.vec3(j, "light", "center");
    light.normal = r.vec3(j, "light", "normal");
    light.up = r.vec3_or(j, "light", "up", light.up);
    if (shape == "rectangle") {
        r.only_keys(j, "light", {"shape", "center", "normal", "up", "size"});
        const json& size = r.member(j, "light", "size");
        if (!size.is_array() || size.size() != 2 || !size[0].is_number() || !size[1].is_number())
            r.fail("light.size", "must be an array of 2 numbers (width, height)");
        light.shape = LightShape::Rectangle;
        light.width = size[0].get<double>();
        light.height = size[1].get<double>();
    } else if (shape == "disk") {
        r.only_keys(j, "light", {"shape", "center", "normal", "up", "diameter"});
        light.shape = LightShape::Disk;
        light.width = light.height = r.number(j, "light", "diameter");
    } else if (shape == "point") {
        r.only_keys(j, "light", {"shape", "center", "normal", "up"});
        light.shape = LightShape::Point;
        light.width = light.height = 0;
    } else {
        r.fail("light.shape", "must be \"rectangle\", \"disk\" or \"point\" (got \"" + shape + "\")");
    }
    return light;
}

LightCamera read_light_camera(const Reader& r, const json& root)
{
    const json& j = r.member(root, "", "light_camera");
    const std::string at = "light_camera";
    LightCamera camera;
    const std::string projection = r.string(j, at, "projection");
    camera.near = r.number(j, at, "near");
    camera.far = r.number(j, at, "far");
    if (projection == "perspective") {
        r.only_keys(j, at, {"projection", "near", "far", "fov_degrees"});
        camera.projection = Projection::Perspective;
        camera.fov_degrees = r.number(j, at, "fov_degrees");
    } else if (projection == "orthographic") {
        r.only_keys(j, at, {"projection", "near", "far", "extent"});
        camera.projection = Projection::Orthographic;
        camera.extent = r.number(j, at, "extent");
    } else {
        r.fail(at + ".projection", "must be \"perspective\" or \"orthographic\" (got \"" + projection + "\")");
    }
    return camera;
}

ViewCamera read_view(const Reader& r, const json& root)
{
    const json& j = r.member(root, "", "view");
    r.only_keys(j, "view", {"position", "target", "up", "fov_degrees"});
    ViewCamera view;
    view.position = r.vec3(j, "view", "position");
    view.target = r.vec3(j, "view", "target");
    view.up = r.vec3_or(j, "view", "up", view.up);
    view.fov_degrees = r.number(j, "view", "fov_degrees");
    return view;
}

std::vector<DirectionalLight> read_directional_lights(const Reader& r, const json& root)
{
    std::vector<DirectionalLight> lights;
    if (!root.contains("directional_lights")) return lights;
    const json& list = root.at("directional_lights");
    if (!list.is_array()) r.fail("directional_lights", "must be an array");
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string at = "directional_lights[" + std::to_string(i) + "]";
        r.only_keys(list[i], at, {"direction", "up"});
        DirectionalLight light;
        light.direction = r.vec3(list[i], at, "direction");
        light.up = r.vec3_or(list[i], at, "up", light.up);
        lights.push_back(light);
    }
    return lights;
}

int read_map_size(const Reader& r, const json& root)
{
    if (!root.contains("map_size")) return Scene{}.map_size;
    const json& value = root.at("map_size");
    if (!value.is_number_integer()) r.fail("map_size", "must be an integer");
    const auto size = value.get<std::int64_t>();
    if (size < 1 || size > (1 << 20)) r.fail("map_size", "must be in [1, 1048576]");
    return int(size);
}

Scene read_scene(const Reader& r, const json& root)
{
    if (!root.is_object()) r.fail("(document)", "must be a JSON object");
    r.only_keys(root, "",
                {"name", "description", "map_size", "primitives", "media", "hair", "light", "light_camera", "view",
                 "ambient", "directional_lights"});
    Scene scene;
    if (root.contains("name")) scene.name = r.string(root, "", "name");
    if (root.contains("description")) scene.description = r.string(root, "", "description");
    scene.map_size = read_map_size(r, root);
    scene.primitives = read_primitives(r, root);
    scene.media = read_media(r, root);
    scene.hair = read_hair(r, root);
    scene.light = read_light(r, root);
    scene.light_camera = read_light_camera(r, root);
    scene.view = read_view(r, root);
    scene.directional_lights = read_directional_lights(r, root);
    if (root.contains("ambient")) scene.ambient = read_scene_ambient(r, root["ambient"], "ambient");
    return scene;
}

// The opacity only where it is not the default, so opaque scenes read as
// they always did.
json primitive_to_json(const Primitive& primitive)
{
    json j = shape_to_json(primitive);
    if (opacity_of(primitive) != 1) j["opacity"] = opacity_of(primitive);
    return j;
}

json light_to_json(const AreaLight& light)
{
    json j = {{"center", to_json(light.center)}, {"normal", to_json(light.normal)}, {"up", to_json(light.up)}};
    if (light.shape == LightShape::Point) {
        j["shape"] = "point";
    } else if (light.shape == LightShape::Disk) {
        j["shape"] = "disk";
        j["diameter"] = light.width;
    } else {
        j["shape"] = "rectangle";
        j["size"] = json::array({light.width, light.height});
    }
    return j;
}

json light_camera_to_json(const LightCamera& camera)
{
    json j = {{"near", camera.near}, {"far", camera.far}};
    if (camera.projection == Projection::Perspective) {
        j["projection"] = "perspective";
        j["fov_degrees"] = camera.fov_degrees;
    } else {
        j["projection"] = "orthographic";
        j["extent"] = camera.extent;
    }
    return j;
}

}  // namespace

Scene scene_from_json(std::string_view text, std::string_view source_name)
{
    const std::string context = std::string(source_name) + ": ";
    const json root = parse_json_document(text, context, kLoad);
    Scene scene;
    try {
        scene = read_scene(Reader(context), root);
    } catch (const json::exception& e) {  // a value of the right type but out of its C++ range
        throw Error(ErrorCategory::InvalidArgument, kLoad, context + e.what());
    }
    validate_scene(scene, kLoad, context);
    return scene;
}

Scene load_scene(const std::filesystem::path& path)
{
    // A regular file of bounded size: `--scene /dev/zero` or a FIFO is refused
    // before a byte is read (penumbra/input_file.h).
    return scene_from_json(read_input_file(path.string(), kLoad, kMaxSceneFileBytes), path.string());
}

std::string scene_to_json(const Scene& scene)
{
    json primitives = json::array();
    for (const Primitive& p : scene.primitives) primitives.push_back(primitive_to_json(p));
    json root = {
        {"name", scene.name},
        {"description", scene.description},
        {"map_size", scene.map_size},
        {"light", light_to_json(scene.light)},
        {"light_camera", light_camera_to_json(scene.light_camera)},
        {"view",
         {{"position", to_json(scene.view.position)},
          {"target", to_json(scene.view.target)},
          {"up", to_json(scene.view.up)},
          {"fov_degrees", scene.view.fov_degrees}}},
        {"primitives", primitives},
    };
    // Written only when present, so the scenes without them read as they did.
    if (!scene.media.empty()) root["media"] = media_to_json(scene.media);
    if (!scene.hair.empty()) root["hair"] = hair_to_json(scene.hair);
    if (scene.ambient) root["ambient"] = scene_ambient_to_json(*scene.ambient);
    if (!scene.directional_lights.empty()) {
        json lights = json::array();
        for (const DirectionalLight& light : scene.directional_lights)
            lights.push_back({{"direction", to_json(light.direction)}, {"up", to_json(light.up)}});
        root["directional_lights"] = lights;
    }
    return root.dump(2) + "\n";
}

void save_scene(const Scene& scene, const std::filesystem::path& path)
{
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    if (!file) throw Error(ErrorCategory::Io, "save_scene", path.string() + ": cannot open for writing");
    file << scene_to_json(scene);
    file.flush();
    if (!file) throw Error(ErrorCategory::Io, "save_scene", path.string() + ": write failed");
}

}  // namespace penumbra::reference
