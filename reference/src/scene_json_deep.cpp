// Media and hair to and from JSON (docs/reference.md, "JSON scenes").
#include "scene_json_deep.h"

namespace penumbra::reference {
namespace {

const json* optional_array(const Reader& r, const json& root, const char* key)
{
    if (!root.contains(key)) return nullptr;
    const json& list = root.at(key);
    if (!list.is_array()) r.fail(key, "must be an array");
    return &list;
}

std::string item_path(const char* key, std::size_t i) { return std::string(key) + "[" + std::to_string(i) + "]"; }

Medium read_medium(const Reader& r, const json& j, const std::string& at)
{
    const Primitive shape = read_shape(r, j, at, {"extinction", "gradient"});
    Medium medium;
    if (const auto* sphere = std::get_if<Sphere>(&shape)) medium.region = *sphere;
    else if (const auto* box = std::get_if<Box>(&shape)) medium.region = *box;
    else r.fail(at + ".type", "must be sphere or box for a medium");
    medium.extinction = r.number(j, at, "extinction");
    medium.gradient = r.vec3_or(j, at, "gradient", {});
    return medium;
}

Hair read_one_hair(const Reader& r, const json& j, const std::string& at)
{
    r.only_keys(j, at,
                {"center", "scalp_radius", "axis", "cap_degrees", "strands", "segments", "length", "radius", "droop",
                 "curl", "opacity", "seed"});
    Hair h;
    h.center = r.vec3(j, at, "center");
    h.scalp_radius = r.number(j, at, "scalp_radius");
    h.axis = r.vec3_or(j, at, "axis", h.axis);
    h.cap_degrees = r.number_or(j, at, "cap_degrees", h.cap_degrees);
    h.strands = int(r.integer(j, at, "strands", 1, kMaxHairCapsules));
    h.segments = j.contains("segments") ? int(r.integer(j, at, "segments", 1, 64)) : h.segments;
    h.length = r.number(j, at, "length");
    h.radius = r.number(j, at, "radius");
    h.droop = r.number_or(j, at, "droop", h.droop);
    h.curl = r.number_or(j, at, "curl", h.curl);
    h.opacity = r.number_or(j, at, "opacity", h.opacity);
    const json& seed = r.member(j, at, "seed");
    if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<std::int64_t>() >= 0))
        r.fail(Reader::join(at, "seed"), "must be an integer in [0, 2^64)");
    h.seed = seed.get<std::uint64_t>();
    return h;
}

}  // namespace

std::vector<Medium> read_media(const Reader& r, const json& root)
{
    std::vector<Medium> media;
    if (const json* list = optional_array(r, root, "media"))
        for (std::size_t i = 0; i < list->size(); ++i) media.push_back(read_medium(r, (*list)[i], item_path("media", i)));
    return media;
}

std::vector<Hair> read_hair(const Reader& r, const json& root)
{
    std::vector<Hair> hair;
    if (const json* list = optional_array(r, root, "hair"))
        for (std::size_t i = 0; i < list->size(); ++i) hair.push_back(read_one_hair(r, (*list)[i], item_path("hair", i)));
    return hair;
}

json media_to_json(const std::vector<Medium>& media)
{
    json list = json::array();
    for (const Medium& m : media) {
        json j = std::visit([](const auto& region) { return shape_to_json(region); }, m.region);
        j["extinction"] = m.extinction;
        j["gradient"] = to_json(m.gradient);
        list.push_back(j);
    }
    return list;
}

json hair_to_json(const std::vector<Hair>& hair)
{
    json list = json::array();
    for (const Hair& h : hair)
        list.push_back({{"center", to_json(h.center)}, {"scalp_radius", h.scalp_radius}, {"axis", to_json(h.axis)},
                        {"cap_degrees", h.cap_degrees}, {"strands", h.strands}, {"segments", h.segments},
                        {"length", h.length}, {"radius", h.radius}, {"droop", h.droop}, {"curl", h.curl},
                        {"opacity", h.opacity}, {"seed", h.seed}});
    return list;
}

}  // namespace penumbra::reference
