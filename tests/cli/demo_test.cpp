// `penumbra demo --quick` and `penumbra render-scene`, run as a user would.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "penumbra/exr_io.h"
#include "penumbra/reference/scene.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name)
{
    const fs::path dir = fs::temp_directory_path() / ("penumbra_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

int run(const std::string& args, const fs::path& log)
{
    const std::string cmd = std::string(PENUMBRA_CLI_PATH) + " " + args + " >" + log.string() + " 2>&1";
    return WEXITSTATUS(std::system(cmd.c_str()));
}

std::vector<std::string> split_csv_line(const std::string& line)
{
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (char c : line) {
        if (c == '"') quoted = !quoted;
        else if (c == ',' && !quoted) {
            cells.push_back(cell);
            cell.clear();
        } else cell += c;
    }
    cells.push_back(cell);
    return cells;
}

TEST(Demo, QuickRunCoversEveryMethodOnEverySceneWithoutNaN)
{
    const fs::path out = scratch("demo");
    ASSERT_EQ(run("demo --quick --out " + out.string(), out / "log.txt"), 0) << std::ifstream(out / "log.txt").rdbuf();
    std::ifstream csv(out / "results.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header, "scene,method,settings,backend,ms_per_mpix,rmse,p99,leak,overdark,flicker");
    std::map<std::string, std::set<std::string>> methods_per_scene;
    std::set<std::string> all_methods;
    for (std::string line; std::getline(csv, line);) {
        const auto cells = split_csv_line(line);
        ASSERT_EQ(cells.size(), 10u) << line;
        methods_per_scene[cells[0]].insert(cells[1]);
        all_methods.insert(cells[1]);
        for (int c = 4; c < 10; ++c) {
            const double value = std::stod(cells[c]);
            EXPECT_TRUE(std::isfinite(value)) << line;
            EXPECT_GE(value, 0.0) << line;
        }
    }
    for (const std::string& scene : reference::builtin_scene_names()) {
        EXPECT_EQ(methods_per_scene[scene], all_methods) << scene;
        EXPECT_TRUE(fs::exists(out / scene / "truth.png"));
        for (const std::string& method : all_methods) {
            EXPECT_TRUE(fs::exists(out / scene / (method + ".exr"))) << scene << " " << method;
            EXPECT_TRUE(fs::exists(out / scene / (method + "_error.png"))) << scene << " " << method;
        }
    }
    EXPECT_TRUE(all_methods.count("vsm") && all_methods.count("vssm"));
    EXPECT_TRUE(fs::exists(out / "chart.png"));
    fs::remove_all(out);
}

// With stdout in a file (a CI log), the run reports itself line by line: one
// line per scene's truth and per method, in order, counting up to the whole
// work, each with the time so far and an estimate of the rest, all before the
// results table.
TEST(Demo, ALogGetsOneProgressLinePerSceneAndMethod)
{
    const fs::path out = scratch("demo_log");
    ASSERT_EQ(run("demo --quick --scene contact --method vsm,pcf --out " + out.string(), out / "log.txt"), 0)
        << std::ifstream(out / "log.txt").rdbuf();
    std::ifstream log(out / "log.txt");
    const std::regex progress_line(R"(\[(\d+)/(\d+)\] \d+\.\d s, about \d+ s left: (.*))");
    std::vector<std::string> units;
    int last_done = 0, total = 0;
    bool table_seen = false;
    for (std::string line; std::getline(log, line);) {
        std::smatch m;
        if (std::regex_match(line, m, progress_line)) {
            EXPECT_FALSE(table_seen) << "progress after the table: " << line;
            EXPECT_GT(std::stoi(m[1]), last_done) << line;
            last_done = std::stoi(m[1]);
            total = std::stoi(m[2]);
            units.push_back(m[3]);
        } else if (line.rfind("scene ", 0) == 0) {
            table_seen = true;
        }
    }
    EXPECT_TRUE(table_seen);
    EXPECT_EQ(last_done, total);
    const std::vector<std::string> expected = {"contact: ground truth, 2 frames", "contact: vsm", "contact: pcf"};
    EXPECT_EQ(units, expected);
    fs::remove_all(out);
}

TEST(Demo, BadSceneOrOptionIsBadInput)
{
    const fs::path out = scratch("demo_bad");
    EXPECT_EQ(run("demo --quick --scene nowhere --out " + out.string(), out / "log.txt"), 2);
    std::stringstream log;
    log << std::ifstream(out / "log.txt").rdbuf();
    EXPECT_NE(log.str().find("contact"), std::string::npos) << log.str();  // names the valid scenes
    EXPECT_EQ(run("demo --frames 1 --out " + out.string(), out / "log.txt"), 2);
    fs::remove_all(out);
}

TEST(RenderScene, WritesTheShadeContract)
{
    const fs::path out = scratch("render_scene");
    const std::string args = "render-scene overlap --shadow-map " + (out / "sm.exr").string() + " --receivers " +
                             (out / "rx.exr").string() + " --truth " + (out / "gt.exr").string() +
                             " --map-size 64 --view-size 40x30 --samples 16";
    ASSERT_EQ(run(args, out / "log.txt"), 0) << std::ifstream(out / "log.txt").rdbuf();
    const Image map = read_exr((out / "sm.exr").string(), {"Z"});
    const Image rx = read_exr((out / "rx.exr").string(), {"u", "v", "z", "P.x", "N.y", "mask"});
    const Image truth = read_exr((out / "gt.exr").string(), {"Y"});
    EXPECT_EQ(map.width(), 64);
    EXPECT_EQ(rx.width(), 40);
    EXPECT_EQ(rx.height(), 30);
    EXPECT_EQ(truth.width(), 40);
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
            EXPECT_GE(truth.at(0, x, y), 0.0f);
            EXPECT_LE(truth.at(0, x, y), 1.0f);
        }
    EXPECT_EQ(run("render-scene nowhere --shadow-map a.exr --receivers b.exr --truth c.exr", out / "log.txt"), 2);
    EXPECT_EQ(run("render-scene contact --shadow-map a.exr --receivers b.exr --truth c.exr --view-size 10by3",
                  out / "log.txt"),
              2);
    fs::remove_all(out);
}

}  // namespace
}  // namespace penumbra
