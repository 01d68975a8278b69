// Pismo's maps as a directory of files (penumbra/pismo_files.h): a set
// rendered from a scene survives the round trip exactly; a bad manifest or
// map is refused with a typed error naming the file and what is wrong, and a
// set that cannot be read back is not written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "penumbra/error.h"
#include "penumbra/pismo_files.h"
#include "penumbra/reference/pismo_maps.h"
#include "support/cli.h"

namespace penumbra {
namespace {

using nlohmann::json;
using testing::expect_error;

PismoMapSet contact_set(int level, int size)
{
    reference::LayeredMapOptions o;
    o.size = size;
    return reference::render_pismo_map_set(reference::builtin_scene("contact"), level, o);
}

class PismoFiles : public testing::CliFixture {
protected:
    json manifest() const { return json::parse(testing::slurp(path("set/pismo.json"))); }
    void rewrite(const json& j) const { std::ofstream(path("set/pismo.json")) << j.dump(); }
    // A map's own reader may name itself (read_layered_exr): any operation, the file named.
    void expect_refused(ErrorCategory category, const std::string& needle, ExrReadLimits limits = {}) const
    {
        expect_error([&] { (void)read_pismo_maps(path("set"), limits); }, category, "", {needle});
    }
    void SetUp() override
    {
        CliFixture::SetUp();
        std::filesystem::create_directories(path("set"));
        write_pismo_maps(path("set"), contact_set(0, 9));
    }
};

TEST_F(PismoFiles, RoundTripIsExact)
{
    const PismoMapSet set = contact_set(1, 13);
    write_pismo_maps(path("set"), set);
    const PismoMapSet back = read_pismo_maps(path("set"));
    EXPECT_EQ(back.vertices, set.vertices);
    EXPECT_EQ(back.triangles, set.triangles);
    EXPECT_EQ(back.scene, "contact");
    EXPECT_EQ(back.level, 1);
    EXPECT_EQ(back.fixation, set.fixation);
    ASSERT_EQ(back.maps.size(), 9u);
    for (std::size_t v = 0; v < 9; ++v) {
        EXPECT_EQ(back.maps[v].offsets(), set.maps[v].offsets()) << v;
        EXPECT_EQ(back.maps[v].depths(), set.maps[v].depths()) << v;
        EXPECT_EQ(back.maps[v].camera().position, set.maps[v].camera().position) << v;
        EXPECT_EQ(back.maps[v].camera().tan_half_fov, set.maps[v].camera().tan_half_fov) << v;
    }
}

TEST_F(PismoFiles, BadManifestsAreRefused)
{
    const json good = manifest();
    std::filesystem::remove(path("set/pismo.json"));
    expect_refused(ErrorCategory::Io, "pismo.json");
    std::ofstream(path("set/pismo.json")) << "{ not json";
    expect_refused(ErrorCategory::Io, "not a JSON object");
    const auto with = [&](const char* key, json value) {
        json j = good;
        j[key] = std::move(value);
        return j;
    };
    const std::vector<std::pair<json, std::string>> cases = {
        {with("format", "penumbra deep map"), "not a manifest"},
        {with("version", 3), "version 3"},
        {with("version", 0), "version 0"},
        {with("vertices", json::array()), "0 vertices"},
        {with("vertices", "many"), "not an array"},
        {with("maps", json::array({"map-0000.exr"})), "1 maps for 4 vertices"},
        {with("triangles", json::array({{0, 1, 4}, {0, 2, 3}})), "no vertex index"},
        {with("triangles", json::array({{0, 1, -1}, {0, 2, 3}})), "no vertex index"},
        {with("maps", json::array({"../x.exr", "map-0001.exr", "map-0002.exr", "map-0003.exr"})), "plain file name"},
        {with("vertices", json::array({{0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}})), "vertices[0]"},
    };
    for (const auto& [j, needle] : cases) {
        rewrite(j);
        expect_refused(ErrorCategory::Io, needle);
    }
    json no_maps = good;
    no_maps.erase("maps");
    rewrite(no_maps);
    expect_refused(ErrorCategory::Io, "no field \"maps\"");
}

TEST_F(PismoFiles, BadMapsAreRefusedNamingTheMap)
{
    json j = manifest();
    j["vertices"][2][0] = j["vertices"][2][0].get<double>() + 0.5;  // map 2's camera is no longer at its vertex
    rewrite(j);
    expect_refused(ErrorCategory::InvalidData, "map-0002.exr");
    write_pismo_maps(path("set"), contact_set(0, 9));
    std::filesystem::remove(path("set/map-0003.exr"));
    expect_refused(ErrorCategory::Io, "map-0003.exr");
    // Maps of two sizes: map 1 from a set of 5^2.
    std::filesystem::create_directories(path("other"));
    write_pismo_maps(path("other"), contact_set(0, 5));
    write_pismo_maps(path("set"), contact_set(0, 9));
    std::filesystem::copy_file(path("other/map-0001.exr"), path("set/map-0001.exr"),
                               std::filesystem::copy_options::overwrite_existing);
    expect_refused(ErrorCategory::InvalidData, "one size");
}

// A set rendered from a scene carries each layer's surface id (version 2).
TEST_F(PismoFiles, SurfaceIdsRoundTripAndAVersionOneSetReadsWithoutThem)
{
    const PismoMapSet set = contact_set(1, 13);
    ASSERT_EQ(set.surface_ids.size(), 9u);
    ASSERT_EQ(set.surface_count, int(reference::scene_surfaces(reference::builtin_scene("contact")).size()));
    write_pismo_maps(path("set"), set);
    EXPECT_EQ(manifest()["version"], 2);
    EXPECT_EQ(manifest()["surfaces"], set.surface_count);
    const PismoMapSet back = read_pismo_maps(path("set"));
    EXPECT_EQ(back.surface_count, set.surface_count);
    EXPECT_EQ(back.surface_ids, set.surface_ids);
    // Version 1: no "surfaces", maps without the channel; read as a set without ids.
    PismoMapSet plain = set;
    plain.surface_ids.clear(), plain.surface_count = 0;
    write_pismo_maps(path("set"), plain);
    json j = manifest();
    EXPECT_FALSE(j.contains("surfaces"));
    j["version"] = 1;
    rewrite(j);
    const PismoMapSet old = read_pismo_maps(path("set"));
    EXPECT_TRUE(old.surface_ids.empty());
    EXPECT_EQ(old.surface_count, 0);
    EXPECT_EQ(old.maps[4].depths(), set.maps[4].depths());
}

TEST_F(PismoFiles, BadSurfaceIdsAreRefusedNamingTheFile)
{
    const PismoMapSet set = contact_set(0, 9);
    const json good = manifest();
    for (const json& count : {json(0), json(-1), json("six"), json(1.5), json((1 << 24) + 1)}) {
        json j = good;
        j["surfaces"] = count;
        rewrite(j);
        expect_refused(ErrorCategory::Io, "field \"surfaces\" is " + count.dump());
    }
    // A count below a layer's id: the map, the pixel and the layer named.
    std::int32_t largest = 0;
    for (const auto& ids : set.surface_ids)
        for (std::int32_t id : ids) largest = std::max(largest, id);
    ASSERT_GE(largest, 1);
    json j = good;
    j["surfaces"] = largest;
    rewrite(j);
    expect_refused(ErrorCategory::InvalidData, "is not below the manifest's \"surfaces\"");
    expect_refused(ErrorCategory::InvalidData, ", layer ");
    // "surfaces" promised, a map without the channel.
    rewrite(good);
    PismoMapSet plain = set;
    plain.surface_ids.clear(), plain.surface_count = 0;
    std::filesystem::create_directories(path("plain"));
    write_pismo_maps(path("plain"), plain);
    std::filesystem::copy_file(path("plain/map-0000.exr"), path("set/map-0000.exr"),
                               std::filesystem::copy_options::overwrite_existing);
    ASSERT_FALSE(set.maps[0].depths().empty()) << "a map without layers needs no ids";
    expect_refused(ErrorCategory::InvalidData, "map-0000.exr' has no channel surface");
    // Ids that could not be read back are not written.
    const std::size_t v = std::size_t(std::find_if(set.surface_ids.begin(), set.surface_ids.end(),
                                                   [](const auto& ids) { return !ids.empty(); }) -
                                      set.surface_ids.begin());
    ASSERT_LT(v, set.surface_ids.size()) << "no map has a layer";
    PismoMapSet bad = set;
    bad.surface_ids[v][0] = bad.surface_count;
    expect_error([&] { write_pismo_maps(path("bad"), bad); }, ErrorCategory::InvalidArgument, "write_pismo_maps",
                 {"outside [0, "});
    bad = set;
    bad.surface_ids[v].pop_back();
    expect_error([&] { write_pismo_maps(path("bad"), bad); }, ErrorCategory::InvalidArgument, "write_pismo_maps",
                 {"surface ids"});
    EXPECT_FALSE(std::filesystem::exists(path("bad")));
}

TEST_F(PismoFiles, ThePixelBudgetCoversEveryMap)
{
    EXPECT_NO_THROW((void)read_pismo_maps(path("set"), {4 * 81}));
    expect_refused(ErrorCategory::Io, "map-0003.exr", {3 * 81 + 80});
}

TEST_F(PismoFiles, ASetThatCannotBeReadBackIsNotWritten)
{
    PismoMapSet set = contact_set(0, 5);
    set.triangles[0][1] = 7;
    expect_error([&] { write_pismo_maps(path("bad"), set); }, ErrorCategory::InvalidArgument, "write_pismo_maps",
                 {"not a vertex"});
    set = contact_set(0, 5);
    set.maps.pop_back();
    expect_error([&] { write_pismo_maps(path("bad"), set); }, ErrorCategory::InvalidArgument, "write_pismo_maps",
                 {"3 maps for 4 vertices"});
    EXPECT_FALSE(std::filesystem::exists(path("bad")));
}

}  // namespace
}  // namespace penumbra
