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
// results of each truth and, per scene, the truth and each of the scene's
// methods' picture and error picture with a caption naming the method.
void expect_report_names_only_existing_pictures(const fs::path& out,
                                                std::map<std::string, std::set<std::string>> methods_per_scene)
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
        for (const std::string& method : methods_per_scene[scene]) {
            EXPECT_TRUE(named.count(scene + "/" + method + ".png")) << scene << " " << method;
            EXPECT_TRUE(named.count(scene + "/" + method + "_error.png")) << scene << " " << method;
            EXPECT_NE(page.find("<figcaption>" + method + ", "), std::string::npos) << method;
        }
    }
    for (const char* section : {"id=\"summary\"", "id=\"results-shadow\"", "id=\"results-obscurance\"",
                                "id=\"results-sun\"", "id=\"pictures\""})
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
              "rmse,p99,leak,overdark,flicker,truth_noise,truth");
    std::map<std::string, std::set<std::string>> methods_per_scene, shadow_methods_per_scene;
    std::map<std::string, std::set<std::string>> scenes_per_method;
    std::set<std::string> shadow_methods;
    for (std::string line; std::getline(csv, line);) {
        const auto cells = split_csv_line(line);
        ASSERT_EQ(cells.size(), 18u) << line;
        methods_per_scene[cells[0]].insert(cells[1]);
        scenes_per_method[cells[1]].insert(cells[0]);
        if (cells[17] == "shadow") {
            shadow_methods_per_scene[cells[0]].insert(cells[1]);
            shadow_methods.insert(cells[1]);
        } else {
            EXPECT_TRUE(cells[17] == "obscurance" || cells[17] == "sun") << line;
        }
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
    // shadow method gives a finite row on hair, fog and layers too; ssao-vo
    // runs on the opaque scenes (its truth takes the primitives as solids),
    // the sun's rows where a scene has a directional light.
    const std::vector<std::string> opaque = reference::builtin_scene_names(reference::SceneSet::Opaque);
    std::set<std::string> sunlit;
    for (const std::string& scene : reference::builtin_scene_names(reference::SceneSet::All)) {
        EXPECT_EQ(shadow_methods_per_scene[scene], shadow_methods) << scene;
        if (!reference::builtin_scene(scene).directional_lights.empty()) sunlit.insert(scene);
        EXPECT_TRUE(fs::exists(out / scene / "truth.png"));
        for (const std::string& method : methods_per_scene[scene]) {
            EXPECT_TRUE(fs::exists(out / scene / (method + ".exr"))) << scene << " " << method;
            EXPECT_TRUE(fs::exists(out / scene / (method + "_error.png"))) << scene << " " << method;
        }
    }
    EXPECT_TRUE(shadow_methods.count("vsm") && shadow_methods.count("vssm"));
    EXPECT_TRUE(shadow_methods.count("dsm"));  // on a deep map the demo renders per frame
    EXPECT_TRUE(shadow_methods.count("pismo") && shadow_methods.count("pismo-maxdepth"));  // on the frame's Pismo maps
    const std::set<std::string> opaque_set(opaque.begin(), opaque.end());
    for (const char* method : {"ssao-vo", "ssao-vo+blur"}) EXPECT_EQ(scenes_per_method[method], opaque_set) << method;
    EXPECT_EQ(sunlit, (std::set<std::string>{"contact", "large"}));
    for (const char* method : {"cascades", "single-pcf", "single-pcf-gauss", "single-pcf-disc"})
        EXPECT_EQ(scenes_per_method[method], sunlit) << method;
    EXPECT_TRUE(fs::exists(out / "chart.png"));
    expect_report_names_only_existing_pictures(out, methods_per_scene);
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

struct CsvRow {
    std::string scene, method, setting, truth;
    double rmse = 0;
};

std::vector<CsvRow> csv_rows(const fs::path& path)
{
    std::ifstream csv(path);
    std::vector<CsvRow> rows;
    std::string line;
    std::getline(csv, line);
    while (std::getline(csv, line)) {
        const auto cells = split_csv_line(line);
        rows.push_back({cells[0], cells[1], cells[2], cells.at(17), std::stod(cells[11])});
    }
    return rows;
}

double rmse_of(const std::vector<CsvRow>& rows, const std::string& method, const std::string& setting)
{
    const auto row = std::find_if(rows.begin(), rows.end(),
                                  [&](const CsvRow& r) { return r.method == method && r.setting == setting; });
    EXPECT_NE(row, rows.end()) << method << " " << setting;
    return row == rows.end() ? 0.0 : row->rmse;
}

// The new rows by name: ssao-vo's four rules on every opaque scene asked for,
// the cascades on the one with a sun, nothing else; and what their truths
// show, by a wide margin on contact (docs/ssao.md, docs/cascades.md): paired
// samples beat unusable = 0 against the obscurance truth, and three cascades
// beat one map of their texels at the same 4x4 Gaussian PCF against the
// sun's hard shadow.
TEST(Demo, SelectsTheObscuranceAndSunRowsByName)
{
    const fs::path out = scratch("demo_select");
    ASSERT_EQ(run("demo --quick --frame 64x36 --scene contact,fence --method ssao-vo,cascades,single-pcf-gauss --out " +
                      out.string(),
                  out / "log.txt"),
              0)
        << std::ifstream(out / "log.txt").rdbuf();
    const std::vector<CsvRow> rows = csv_rows(out / "results.csv");
    std::map<std::string, std::vector<std::string>> settings;
    for (const CsvRow& r : rows) {
        settings[r.scene + " " + r.method].push_back(r.setting);
        EXPECT_EQ(r.truth, r.method == "ssao-vo" ? "obscurance" : "sun") << r.method;
        EXPECT_TRUE(std::isfinite(r.rmse) && r.rmse >= 0) << r.method;
    }
    const std::vector<std::string> rules = {"paired", "zero", "half", "renormalise"};
    EXPECT_EQ(settings["contact ssao-vo"], rules);
    EXPECT_EQ(settings["fence ssao-vo"], rules);
    EXPECT_EQ(settings["contact cascades"], (std::vector<std::string>{"k=3 box", "k=3 split"}));
    EXPECT_EQ(settings["contact single-pcf-gauss"].size(), 3u);
    EXPECT_EQ(settings.size(), 4u);  // fence has no sun
    const std::vector<CsvRow> contact(rows.begin(), std::find_if(rows.begin(), rows.end(), [](const CsvRow& r) {
                                          return r.scene != "contact";
                                      }));
    EXPECT_LT(1.5 * rmse_of(contact, "ssao-vo", "paired"), rmse_of(contact, "ssao-vo", "zero"));
    EXPECT_LT(1.5 * rmse_of(contact, "cascades", "k=3 box"), rmse_of(contact, "single-pcf-gauss", "4x4 s=1"));
    EXPECT_TRUE(fs::exists(out / "contact" / "cascades_error.png"));
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
    // A method with no rows on the scenes asked for (fence has no sun) names the
    // scenes it runs on.
    EXPECT_EQ(run("demo --quick --scene fence --method cascades --out " + out.string(), out / "log.txt"), 2);
    {
        const std::string text = file_text(out / "log.txt");
        EXPECT_NE(text.find("'cascades' has no rows on the scenes asked for (fence); it runs on contact, large"),
                  std::string::npos)
            << text;
        EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
    }
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
