// Pismo's maps as a directory of files (penumbra/pismo_files.h).
#include "penumbra/pismo_files.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "penumbra/error.h"
#include "penumbra/input_file.h"
#include "penumbra/layered_exr.h"
#include "penumbra/output_files.h"
#include "penumbra/pismo.h"

namespace penumbra {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr std::string_view kWrite = "write_pismo_maps", kRead = "read_pismo_maps";
constexpr const char* kFormat = "penumbra pismo maps";
// Version 2 added the surface ids ("surfaces" and each map's channel
// surface); version 1 sets still read, as sets without ids.
constexpr int kVersion = 2, kOldestVersion = 1;
// A manifest of kPismoMaxVertices vertices and twice as many triangles, in
// decimal with 17 digits, is under 1 MB.
constexpr std::uint64_t kMaxManifestBytes = 16u << 20;
// A camera's position matches its vertex within this, relative to the scale.
constexpr double kVertexTolerance = 1e-9;

std::string map_name(std::size_t vertex)
{
    char name[32];
    std::snprintf(name, sizeof name, "map-%04zu.exr", vertex);
    return name;
}

bool near_vertex(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
    double scale = 1, gap = 0;
    for (int k = 0; k < 3; ++k) scale = std::max({scale, std::fabs(a[k]), std::fabs(b[k])}), gap = std::max(gap, std::fabs(a[k] - b[k]));
    return gap <= kVertexTolerance * scale;
}

// What both directions require of a set: the manifest's counts and indices.
// Returns an empty string or what is wrong.
std::string set_problem(std::size_t vertices, std::size_t triangles, std::size_t maps)
{
    if (vertices < 3 || vertices > std::size_t(kPismoMaxVertices))
        return "lists " + std::to_string(vertices) + " vertices; a light mesh has 3 to " +
               std::to_string(kPismoMaxVertices);
    if (triangles < 1 || triangles > 2 * vertices)
        return "lists " + std::to_string(triangles) + " triangles for " + std::to_string(vertices) +
               " vertices; a planar mesh has 1 to twice as many";
    if (maps != vertices)
        return "lists " + std::to_string(maps) + " maps for " + std::to_string(vertices) + " vertices; one per vertex";
    return {};
}

json manifest(const PismoMapSet& set)
{
    json j = {{"format", kFormat}, {"version", kVersion}, {"scene", set.scene}, {"level", set.level},
              {"fixation", set.fixation}, {"vertices", set.vertices}, {"triangles", set.triangles}};
    json names = json::array();
    for (std::size_t v = 0; v < set.maps.size(); ++v) names.push_back(map_name(v));
    j["maps"] = names;
    if (!set.surface_ids.empty()) j["surfaces"] = set.surface_count;
    return j;
}

// Ids, when the set has them: a list a map, an id a layer, each below the
// set's surface_count, itself in [1, kPismoMaxSurfaceId + 1].
void check_ids_for_writing(const PismoMapSet& set)
{
    if (set.surface_ids.empty()) return;
    const auto require_ids = [](bool ok, const std::string& message) { require(ok, kWrite, "surface-ids", message); };
    require_ids(set.surface_count >= 1 && set.surface_count <= kPismoMaxSurfaceId + 1,
                "surface_count " + std::to_string(set.surface_count) + " is outside [1, " +
                    std::to_string(kPismoMaxSurfaceId + 1) + "]");
    require_ids(set.surface_ids.size() == set.maps.size(), "there are " + std::to_string(set.surface_ids.size()) +
                                                               " lists of surface ids for " +
                                                               std::to_string(set.maps.size()) + " maps");
    for (std::size_t v = 0; v < set.maps.size(); ++v) {
        const std::vector<std::int32_t>& ids = set.surface_ids[v];
        require_ids(ids.size() == set.maps[v].depths().size(),
                    "map " + std::to_string(v) + " has " + std::to_string(set.maps[v].depths().size()) +
                        " layers but " + std::to_string(ids.size()) + " surface ids");
        for (std::int32_t id : ids)
            require_ids(id >= 0 && id < set.surface_count, "map " + std::to_string(v) + " has surface id " +
                                                               std::to_string(id) + ", outside [0, " +
                                                               std::to_string(set.surface_count) + ")");
    }
}

void check_for_writing(const PismoMapSet& set)
{
    const std::string problem = set_problem(set.vertices.size(), set.triangles.size(), set.maps.size());
    require(problem.empty(), kWrite, "maps", "the set " + problem);
    for (const auto& t : set.triangles)
        for (int i : t)
            require(i >= 0 && std::size_t(i) < set.vertices.size(), kWrite, "maps",
                    "a triangle's index " + std::to_string(i) + " is not a vertex");
    for (std::size_t v = 0; v < set.maps.size(); ++v) {
        require(near_vertex(set.maps[v].camera().position, set.vertices[v]), kWrite, "maps",
                "map " + std::to_string(v) + "'s camera is not at its vertex");
        require(set.maps[v].width() == set.maps[0].width() && set.maps[v].height() == set.maps[0].height(), kWrite,
                "maps", "the maps must all have one size");
    }
    check_ids_for_writing(set);
}

// Reading the manifest: every complaint names the file and the field.
class Manifest {
public:
    explicit Manifest(std::string path) : path_(std::move(path)) {}

    [[noreturn]] void fail(const std::string& what) const
    {
        throw Error(ErrorCategory::Io, kRead, "'" + path_ + "' " + what + "; re-create it with penumbra pismo-build");
    }
    const json& field(const json& object, const char* key) const
    {
        const auto it = object.find(key);
        if (it == object.end()) fail(std::string("has no field \"") + key + "\"");
        return *it;
    }
    const json& array(const json& object, const char* key) const
    {
        const json& a = field(object, key);
        if (!a.is_array()) fail(std::string("field \"") + key + "\" is not an array");
        return a;
    }
    std::array<double, 3> point(const json& j, const std::string& where) const
    {
        if (!j.is_array() || j.size() != 3) fail(where + " is not an array of 3 numbers");
        std::array<double, 3> p{};
        for (int k = 0; k < 3; ++k) {
            if (!j[std::size_t(k)].is_number()) fail(where + " is not an array of 3 numbers");
            p[std::size_t(k)] = j[std::size_t(k)].get<double>();
            if (!std::isfinite(p[std::size_t(k)])) fail(where + " is not finite");
        }
        return p;
    }
    std::array<int, 3> triangle(const json& j, const std::string& where, std::size_t vertices) const
    {
        if (!j.is_array() || j.size() != 3) fail(where + " is not an array of 3 vertex indices");
        std::array<int, 3> t{};
        for (int k = 0; k < 3; ++k) {
            const json& i = j[std::size_t(k)];
            if (!i.is_number_integer() || i.get<std::int64_t>() < 0 || i.get<std::int64_t>() >= std::int64_t(vertices))
                fail(where + " holds " + i.dump() + ", which is no vertex index in [0, " + std::to_string(vertices) +
                     ")");
            t[std::size_t(k)] = i.get<int>();
        }
        return t;
    }
    // A plain file name: the maps stay inside the set's directory.
    std::string map_file(const json& j, const std::string& where) const
    {
        if (!j.is_string()) fail(where + " is not a file name");
        const std::string name = j.get<std::string>();
        if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos ||
            name.find('\0') != std::string::npos)
            fail(where + " \"" + name + "\" is not a plain file name inside the directory");
        return name;
    }

private:
    std::string path_;
};

struct ManifestContents {
    PismoMapSet set;  // without maps
    std::vector<std::string> files;
};

ManifestContents read_manifest(const std::string& path)
{
    const Manifest m(path);
    const json j = json::parse(read_input_file(path, kRead, kMaxManifestBytes), nullptr, false);
    if (j.is_discarded() || !j.is_object()) m.fail("is not a JSON object");
    const json& format = m.field(j, "format");
    if (!format.is_string() || format.get<std::string>() != kFormat)
        m.fail(std::string("is not a manifest of Pismo's maps (its \"format\" is not \"") + kFormat + "\")");
    const json& version = m.field(j, "version");
    if (!version.is_number_integer() || version.get<std::int64_t>() < kOldestVersion ||
        version.get<std::int64_t>() > kVersion)
        m.fail("has version " + version.dump() + "; this penumbra reads versions " + std::to_string(kOldestVersion) +
               " to " + std::to_string(kVersion));
    const json &vertices = m.array(j, "vertices"), &triangles = m.array(j, "triangles"), &maps = m.array(j, "maps");
    if (const std::string problem = set_problem(vertices.size(), triangles.size(), maps.size()); !problem.empty())
        m.fail(problem);
    ManifestContents out;
    for (std::size_t v = 0; v < vertices.size(); ++v) {
        out.set.vertices.push_back(m.point(vertices[v], "vertices[" + std::to_string(v) + "]"));
        out.files.push_back(m.map_file(maps[v], "maps[" + std::to_string(v) + "]"));
    }
    for (std::size_t t = 0; t < triangles.size(); ++t)
        out.set.triangles.push_back(m.triangle(triangles[t], "triangles[" + std::to_string(t) + "]", vertices.size()));
    if (const auto s = j.find("scene"); s != j.end() && s->is_string()) out.set.scene = s->get<std::string>();
    if (const auto l = j.find("level"); l != j.end() && l->is_number_integer()) out.set.level = l->get<int>();
    if (const auto f = j.find("fixation"); f != j.end()) out.set.fixation = m.point(*f, "fixation");
    if (const auto n = j.find("surfaces"); n != j.end() && version.get<std::int64_t>() >= 2) {
        if (!n->is_number_integer() || n->get<std::int64_t>() < 1 || n->get<std::int64_t>() > kPismoMaxSurfaceId + 1)
            m.fail("field \"surfaces\" is " + n->dump() + ", not a count of surfaces in [1, " +
                   std::to_string(kPismoMaxSurfaceId + 1) + "]");
        out.set.surface_count = n->get<int>();
    }
    return out;
}

[[noreturn]] void bad_map(const std::string& path, const std::string& what)
{
    throw Error(ErrorCategory::InvalidData, kRead, "'" + path + "' " + what + "; re-create the set with penumbra pismo-build");
}

// A map's ids, when the manifest counts surfaces: present, and each below the count.
void check_map_ids(const std::string& path, const LayeredDepthMap& map, const std::vector<std::int32_t>& ids,
                   int surface_count)
{
    if (ids.size() != map.depths().size())
        bad_map(path, "has no channel surface, which its manifest's \"surfaces\" promises");
    const std::vector<std::uint32_t>& offsets = map.offsets();
    for (std::size_t p = 0; p + 1 < offsets.size(); ++p)
        for (std::uint32_t l = offsets[p]; l < offsets[p + 1]; ++l)
            if (ids[l] >= surface_count)
                bad_map(path, "at pixel (" + std::to_string(p % std::size_t(map.width())) + ", " +
                                  std::to_string(p / std::size_t(map.width())) + "), layer " +
                                  std::to_string(l - offsets[p]) + ": surface id " + std::to_string(ids[l]) +
                                  " is not below the manifest's \"surfaces\", " + std::to_string(surface_count));
}

}  // namespace

void write_pismo_maps(const std::string& dir, const PismoMapSet& set)
{
    check_for_writing(set);
    OutputFiles output{std::string(kWrite)};
    for (std::size_t v = 0; v < set.maps.size(); ++v)
        stage_layered_exr(output, (fs::path(dir) / map_name(v)).string(), set.maps[v],
                          set.surface_ids.empty() ? std::span<const std::int32_t>{} : set.surface_ids[v]);
    const std::string path = (fs::path(dir) / kPismoManifest).string();
    require_safe_outputs({path}, {}, kWrite);
    const std::string text = manifest(set).dump(1) + "\n";
    output.stage(path, [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << text;
        out.close();
        if (!out) throw Error(ErrorCategory::Io, kWrite, "cannot write '" + path + "'; check free disk space");
    });
    output.publish();
}

PismoMapSet read_pismo_maps(const std::string& dir, const ExrReadLimits& limits)
{
    const std::string manifest_path = (fs::path(dir) / kPismoManifest).string();
    ManifestContents contents = read_manifest(manifest_path);
    PismoMapSet& set = contents.set;
    ExrReadLimits left = limits;  // the pixels of all maps together
    for (std::size_t v = 0; v < contents.files.size(); ++v) {
        const std::string path = (fs::path(dir) / contents.files[v]).string();
        const bool with_ids = set.surface_count > 0;
        std::vector<std::int32_t> ids;
        LayeredDepthMap map = read_layered_exr(path, left, with_ids ? &ids : nullptr);
        left.max_pixels -= std::uint64_t(map.width()) * std::uint64_t(map.height());
        if (!near_vertex(map.camera().position, set.vertices[v]))
            bad_map(path, "has its camera away from vertex " + std::to_string(v) + " of " + manifest_path);
        if (v > 0 && (map.width() != set.maps[0].width() || map.height() != set.maps[0].height()))
            bad_map(path, "is " + std::to_string(map.width()) + " x " + std::to_string(map.height()) + ", not " +
                              std::to_string(set.maps[0].width()) + " x " + std::to_string(set.maps[0].height()) +
                              " as the first map: the maps of a set have one size");
        if (with_ids) check_map_ids(path, map, ids, set.surface_count), set.surface_ids.push_back(std::move(ids));
        set.maps.push_back(std::move(map));
    }
    return std::move(set);
}

}  // namespace penumbra
