// Ambient rigs and volumes from JSON (penumbra/reference/ambient_json.h;
// formats in docs/ambient.md), and the same readers for a scene's "ambient"
// field (scene_json.cpp).
#include "penumbra/reference/ambient_json.h"

#include "ambient_json_parts.h"
#include "penumbra/input_file.h"
#include "penumbra/reference/geometry.h"

namespace penumbra::reference {
namespace {

constexpr std::string_view kLoadRig = "load_rig";
constexpr std::string_view kLoadVolumes = "load_volumes";

AmbientVector to_ambient(Vec3 v) { return {v.x, v.y, v.z}; }

AmbientLight read_light(const Reader& r, const json& j, const std::string& at)
{
    r.only_keys(j, at, {"direction", "color", "intensity"});
    AmbientLight light;
    light.direction = to_ambient(r.vec3(j, at, "direction"));
    light.color = to_ambient(r.vec3_or(j, at, "color", {1, 1, 1}));
    light.intensity = r.number_or(j, at, "intensity", 1.0);
    return light;
}

// "axes": the local x, y, z axes in world space (what a scene file saves).
Rotation read_axes(const Reader& r, const json& j, const std::string& at)
{
    const json& axes = r.member(j, at, "axes");
    const std::string path = Reader::join(at, "axes");
    if (!axes.is_array() || axes.size() != 3) r.fail(path, "must be an array of 3 axes");
    json named = {{"x", axes[0]}, {"y", axes[1]}, {"z", axes[2]}};
    return {r.vec3(named, path, "x"), r.vec3(named, path, "y"), r.vec3(named, path, "z")};
}

json to_json(AmbientVector v) { return json::array({v.x, v.y, v.z}); }

json rig_to_json(const AmbientRig& rig)
{
    json lights = json::array();
    for (const AmbientLight& l : rig.lights)
        lights.push_back({{"direction", to_json(l.direction)}, {"color", to_json(l.color)}, {"intensity", l.intensity}});
    return {{"lights", lights}};
}

json volume_to_json(const AmbientVolume& v)
{
    return {{"shape", v.shape == AmbientVolume::Shape::Box ? "box" : "sphere"},
            {"center", to_json(v.center)},
            {"half_size", to_json(v.half_size)},
            {"axes", json::array({to_json(v.axis_x), to_json(v.axis_y), to_json(v.axis_z)})},
            {"scale_bias", v.scale_bias},
            {"falloff_delay", v.falloff_delay}};
}

AmbientVolume read_volume(const Reader& r, const json& j, const std::string& at)
{
    r.only_keys(j, at,
                {"shape", "center", "half_size", "radius", "rotation_degrees", "axes", "scale_bias", "falloff_delay"});
    AmbientVolume v;
    const std::string shape = r.string(j, at, "shape");
    if (shape != "sphere" && shape != "box") r.fail(at + ".shape", "must be sphere or box (got \"" + shape + "\")");
    v.shape = shape == "box" ? AmbientVolume::Shape::Box : AmbientVolume::Shape::Sphere;
    v.center = to_ambient(r.vec3(j, at, "center"));
    if (j.contains("radius") == j.contains("half_size"))
        r.fail(at, shape == "sphere" ? "give exactly one of radius and half_size" : "half_size: missing");
    if (j.contains("radius") && shape == "box") r.fail(at + ".radius", "a box has half_size, not radius");
    if (j.contains("radius")) {
        const double radius = r.number(j, at, "radius");
        v.half_size = {radius, radius, radius};
    } else {
        v.half_size = to_ambient(r.vec3(j, at, "half_size"));
    }
    if (j.contains("axes") && j.contains("rotation_degrees")) r.fail(at, "give rotation_degrees or axes, not both");
    const Rotation rotation = j.contains("axes") ? read_axes(r, j, at)
                                                 : rotation_from_euler_degrees(r.vec3_or(j, at, "rotation_degrees", {}));
    v.axis_x = to_ambient(rotation.x);
    v.axis_y = to_ambient(rotation.y);
    v.axis_z = to_ambient(rotation.z);
    v.scale_bias = r.number_or(j, at, "scale_bias", 1.0);
    v.falloff_delay = r.number_or(j, at, "falloff_delay", 0.0);
    return v;
}

template <class Read>
auto parse(std::string_view text, std::string_view source_name, std::string_view operation, Read&& read)
{
    const std::string context = std::string(source_name) + ": ";
    const json root = parse_json_document(text, context, operation);
    try {
        return read(Reader(context, operation), root);
    } catch (const json::exception& e) {
        throw Error(ErrorCategory::InvalidArgument, operation, context + e.what());
    }
}

}  // namespace

AmbientRig read_rig(const Reader& r, const json& j, const std::string& at)
{
    r.only_keys(j, at, {"lights"});
    const json& lights = r.member(j, at, "lights");
    const std::string path = Reader::join(at, "lights");
    if (!lights.is_array()) r.fail(path, "must be an array of lights");
    if (lights.empty()) r.fail(path, "must hold at least one light");
    AmbientRig rig;
    for (std::size_t i = 0; i < lights.size(); ++i)
        rig.lights.push_back(read_light(r, lights[i], path + "[" + std::to_string(i) + "]"));
    return rig;
}

std::vector<AmbientVolume> read_volumes(const Reader& r, const json& volumes, const std::string& path)
{
    if (!volumes.is_array()) r.fail(path, "must be an array of volumes");
    std::vector<AmbientVolume> out;
    for (std::size_t i = 0; i < volumes.size(); ++i)
        out.push_back(read_volume(r, volumes[i], path + "[" + std::to_string(i) + "]"));
    return out;
}

SceneAmbient read_scene_ambient(const Reader& r, const json& j, const std::string& at)
{
    r.only_keys(j, at, {"rig", "dark_rig", "volumes"});
    SceneAmbient ambient;
    ambient.rig = read_rig(r, r.member(j, at, "rig"), Reader::join(at, "rig"));
    if (j.contains("dark_rig")) ambient.dark_rig = read_rig(r, j["dark_rig"], Reader::join(at, "dark_rig"));
    if (j.contains("volumes")) ambient.volumes = read_volumes(r, j["volumes"], Reader::join(at, "volumes"));
    if (!ambient.volumes.empty() && !ambient.dark_rig) r.fail(Reader::join(at, "volumes"), "blend towards a dark_rig; give one");
    // The values as the library checks them, named by their field here.
    auto checked = [&](const std::string& field, auto&& check) {
        try {
            check();
        } catch (const Error& e) {
            r.fail(field.empty() ? at : Reader::join(at, field), e.message());
        }
    };
    checked("rig", [&] { project_rig(ambient.rig); });
    if (ambient.dark_rig) checked("dark_rig", [&] { project_rig(*ambient.dark_rig); });
    checked("", [&] { AmbientVolumes{ambient.volumes}; });
    return ambient;
}

json scene_ambient_to_json(const SceneAmbient& ambient)
{
    json j = {{"rig", rig_to_json(ambient.rig)}};
    if (ambient.dark_rig) j["dark_rig"] = rig_to_json(*ambient.dark_rig);
    if (!ambient.volumes.empty()) {
        json volumes = json::array();
        for (const AmbientVolume& v : ambient.volumes) volumes.push_back(volume_to_json(v));
        j["volumes"] = volumes;
    }
    return j;
}

AmbientRig rig_from_json(std::string_view text, std::string_view source_name)
{
    return parse(text, source_name, kLoadRig, [](const Reader& r, const json& root) {
        if (!root.is_object()) r.fail("(document)", "must be a JSON object with \"lights\"");
        return read_rig(r, root, "");
    });
}

AmbientRig load_rig(const std::filesystem::path& path)
{
    return rig_from_json(read_input_file(path.string(), kLoadRig, kMaxSceneFileBytes), path.string());
}

std::vector<AmbientVolume> volumes_from_json(std::string_view text, std::string_view source_name)
{
    return parse(text, source_name, kLoadVolumes, [](const Reader& r, const json& root) {
        if (!root.is_object()) r.fail("(document)", "must be a JSON object with \"volumes\"");
        r.only_keys(root, "", {"volumes"});
        const json& volumes = r.member(root, "", "volumes");
        if (volumes.is_array() && volumes.empty()) r.fail("volumes", "must hold at least one volume");
        return read_volumes(r, volumes, "volumes");
    });
}

std::vector<AmbientVolume> load_volumes(const std::filesystem::path& path)
{
    return volumes_from_json(read_input_file(path.string(), kLoadVolumes, kMaxSceneFileBytes), path.string());
}

}  // namespace penumbra::reference
