// `penumbra demo --quick` and `penumbra render-scene`, run as a user would.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
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

std::string file_text(const fs::path& path)
{
    std::stringstream text;
    text << std::ifstream(path).rdbuf();
    return text.str();
}

// index.html: every picture it names is a file beside it (no address of
// another host, nothing absolute), and it shows the chart, the summary, the
// results and, per scene, the truth and each method's picture and error
// picture with a caption naming the method.
void expect_report_names_only_existing_pictures(const fs::path& out, const std::set<std::string>& methods)
{
    const std::string page = file_text(out / "index.html");
    ASSERT_FALSE(page.empty());
    const std::regex source(R"re(src="([^"]*)")re");
    std::set<std::string> named;
    for (auto it = std::sregex_iterator(page.begin(), page.end(), source); it != std::sregex_iterator(); ++it) {
        const std::string file = (*it)[1];
        EXPECT_EQ(file.find("://"), std::string::npos) << file;
        EXPECT_NE(file.front(), '/') << file;
        EXPECT_TRUE(fs::is_regular_file(out / file)) << "index.html names a missing picture: " << file;
        named.insert(file);
    }
    EXPECT_TRUE(named.count("chart.png"));
    EXPECT_TRUE(named.count("error_scale.png"));
    for (const std::string& scene : reference::builtin_scene_names(reference::SceneSet::All)) {
        EXPECT_TRUE(named.count(scene + "/truth.png")) << scene;
        for (const std::string& method : methods) {
            EXPECT_TRUE(named.count(scene + "/" + method + ".png")) << scene << " " << method;
            EXPECT_TRUE(named.count(scene + "/" + method + "_error.png")) << scene << " " << method;
            EXPECT_NE(page.find("<figcaption>" + method + ", "), std::string::npos) << method;
        }
    }
    for (const char* section : {"id=\"summary\"", "id=\"results\"", "id=\"pictures\""})
        EXPECT_NE(page.find(section), std::string::npos) << section;
}

TEST(Demo, QuickRunCoversEveryMethodOnEverySceneWithoutNaN)
{
    const fs::path out = scratch("demo");
    ASSERT_EQ(run("demo --quick --frame 160x90 --out " + out.string(), out / "log.txt"), 0)
        << std::ifstream(out / "log.txt").rdbuf();
    std::ifstream csv(out / "results.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header,
              "scene,method,settings,backend,frame,map_ms,receiver_ms,frame_ms,frame_ms_min,frame_ms_max,repetitions,"
              "rmse,p99,leak,overdark,flicker,truth_noise");
    std::map<std::string, std::set<std::string>> methods_per_scene;
    std::set<std::string> all_methods;
    for (std::string line; std::getline(csv, line);) {
        const auto cells = split_csv_line(line);
        ASSERT_EQ(cells.size(), 17u) << line;
        methods_per_scene[cells[0]].insert(cells[1]);
        all_methods.insert(cells[1]);
        EXPECT_EQ(cells[4], "160x90") << line;  // the timed frame
        for (int c = 5; c < 17; ++c) {
            const double value = std::stod(cells[c]);
            EXPECT_TRUE(std::isfinite(value)) << line;
            EXPECT_GE(value, 0.0) << line;
        }
        const double map = std::stod(cells[5]), receivers = std::stod(cells[6]), frame = std::stod(cells[7]);
        const double low = std::stod(cells[8]), high = std::stod(cells[9]);
        EXPECT_LE(low, frame) << line;
        EXPECT_LE(frame, high) << line;
        EXPECT_GT(frame, 0.0) << line;
        EXPECT_LE(map, high) << line;
        EXPECT_LE(receivers, high) << line;
        EXPECT_GE(std::stoi(cells[10]), 5) << line;  // medians of at least 5
    }
    // Every scene by default, the deep ones (point lights) included: every
    // method gives a finite row on hair, fog and layers too.
    for (const std::string& scene : reference::builtin_scene_names(reference::SceneSet::All)) {
        EXPECT_EQ(methods_per_scene[scene], all_methods) << scene;
        EXPECT_TRUE(fs::exists(out / scene / "truth.png"));
        for (const std::string& method : all_methods) {
            EXPECT_TRUE(fs::exists(out / scene / (method + ".exr"))) << scene << " " << method;
            EXPECT_TRUE(fs::exists(out / scene / (method + "_error.png"))) << scene << " " << method;
        }
    }
    EXPECT_TRUE(all_methods.count("vsm") && all_methods.count("vssm"));
    EXPECT_TRUE(all_methods.count("dsm"));  // on a deep map the demo renders per frame
    EXPECT_TRUE(all_methods.count("pismo") && all_methods.count("pismo-maxdepth"));  // on the frame's Pismo maps
    EXPECT_TRUE(fs::exists(out / "chart.png"));
    expect_report_names_only_existing_pictures(out, all_methods);
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
    const std::vector<std::string> expected = {"contact: ground truth, 2 frames", "contact: vsm", "contact: pcf",
                                               "contact: timing, 6 settings x 5 on 240x135"};
    EXPECT_EQ(units, expected);
    fs::remove_all(out);
}

// --scene takes the sets opaque, deep and all beside names, each scene once,
// in the order given.
TEST(Demo, SceneSetsExpandInOrderEachSceneOnce)
{
    const fs::path out = scratch("demo_sets");
    ASSERT_EQ(run("demo --quick --frame 32x18 --view-size 32x24 --scene layers,deep --method pcf --out " + out.string(),
                  out / "log.txt"),
              0)
        << std::ifstream(out / "log.txt").rdbuf();
    std::ifstream csv(out / "results.csv");
    std::string line;
    std::getline(csv, line);
    std::vector<std::string> scenes;
    while (std::getline(csv, line)) {
        const std::string scene = split_csv_line(line)[0];
        if (scenes.empty() || scenes.back() != scene) scenes.push_back(scene);
    }
    EXPECT_EQ(scenes, (std::vector<std::string>{"layers", "hair", "fog"}));
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
    // Fewer than 5 repetitions, or a frame that is no WxH or too large: refused
    // with one line naming the option, before any work.
    for (const char* bad : {"--repetitions 4", "--repetitions x", "--frame 1920", "--frame 0x10", "--frame 5000x10",
                            "--budgets 0", "--budgets 4,x", "--budgets nan"}) {
        EXPECT_EQ(run(std::string("demo --quick ") + bad + " --out " + out.string(), out / "log.txt"), 2) << bad;
        const std::string text = file_text(out / "log.txt");
        EXPECT_NE(text.find(std::string(bad).substr(0, std::string(bad).find(' '))), std::string::npos) << text;
        EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
    }
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
