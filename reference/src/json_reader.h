// Reading a scene's JSON with the path of each value in hand, so that every
// complaint names the field ("primitives[2].radius: missing"). Shared by
// scene_json.cpp and scene_json_deep.cpp; private to reference/src.
#pragma once

#include <cstdint>
#include <algorithm>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "penumbra/error.h"
#include "penumbra/reference/geometry.h"

namespace penumbra::reference {

using nlohmann::json;
inline constexpr std::string_view kLoad = "load_scene";

class Reader {
public:
    // `operation`: the Error's (load_scene, or load_rig for an ambient rig's file).
    explicit Reader(std::string context, std::string_view operation = kLoad)
        : context_(std::move(context)), operation_(operation)
    {
    }

    [[noreturn]] void fail(const std::string& field, std::string_view what) const
    {
        throw Error(ErrorCategory::InvalidArgument, operation_, context_ + field + ": " + std::string(what));
    }

    // `extra`: keys the caller's context adds (a primitive's opacity, a medium's extinction).
    void only_keys(const json& object, const std::string& path, std::initializer_list<std::string_view> keys,
                   std::initializer_list<std::string_view> extra = {}) const
    {
        for (const auto& item : object.items()) {
            bool known = false;
            for (std::string_view key : keys) known = known || item.key() == key;
            for (std::string_view key : extra) known = known || item.key() == key;
            if (!known) fail(join(path, item.key()), "unknown field");
        }
    }

    const json& member(const json& object, const std::string& path, const char* key) const
    {
        if (!object.is_object()) fail(path, "must be an object");
        const auto it = object.find(key);
        if (it == object.end()) fail(join(path, key), "missing");
        return *it;
    }

    double number(const json& object, const std::string& path, const char* key) const
    {
        const json& value = member(object, path, key);
        if (!value.is_number()) fail(join(path, key), "must be a number");
        return value.get<double>();
    }

    double number_or(const json& object, const std::string& path, const char* key, double fallback) const
    {
        return object.contains(key) ? number(object, path, key) : fallback;
    }

    Vec3 vec3(const json& object, const std::string& path, const char* key) const
    {
        const json& value = member(object, path, key);
        if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
            !value[2].is_number())
            fail(join(path, key), "must be an array of 3 numbers");
        return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
    }

    Vec3 vec3_or(const json& object, const std::string& path, const char* key, Vec3 fallback) const
    {
        return object.contains(key) ? vec3(object, path, key) : fallback;
    }

    // An integer in [lo, hi].
    std::int64_t integer(const json& object, const std::string& path, const char* key, std::int64_t lo,
                         std::int64_t hi) const
    {
        const json& value = member(object, path, key);
        if (!value.is_number_integer()) fail(join(path, key), "must be an integer");
        const bool is_unsigned = value.is_number_unsigned();
        const auto n = is_unsigned ? std::int64_t(std::min<std::uint64_t>(value.get<std::uint64_t>(), std::numeric_limits<std::int64_t>::max()))
                                   : value.get<std::int64_t>();
        if (n < lo || n > hi) fail(join(path, key), "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return n;
    }

    std::string string(const json& object, const std::string& path, const char* key) const
    {
        const json& value = member(object, path, key);
        if (!value.is_string()) fail(join(path, key), "must be a string");
        return value.get<std::string>();
    }

    static std::string join(const std::string& path, std::string_view key)
    {
        return path.empty() ? std::string(key) : path + "." + std::string(key);
    }

private:
    std::string context_;
    std::string_view operation_;
};

json to_json(Vec3 v);

// The document in `text`; Error(Io, operation, context + "not valid JSON (...)")
// for one that is not JSON: parse_error, and out_of_range for a number beyond
// a double (1e999). `context` is the source's name and ": ".
inline json parse_json_document(std::string_view text, const std::string& context, std::string_view operation)
{
    try {
        return json::parse(text.begin(), text.end());
    } catch (const json::exception& e) {
        throw Error(ErrorCategory::Io, operation, context + "not valid JSON (" + e.what() + ")");
    }
}

}  // namespace penumbra::reference
