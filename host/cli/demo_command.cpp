// penumbra demo: every method, with a small sweep of its settings, on every
// built-in scene, measured against the ray-traced ground truth.
//
// Per scene: K frames with the light moved by sub-texel steps (frame 0 is the
// scene itself); the truth of each frame is cached on disk, keyed by the
// scene and the sizes. Per method and setting: time (median over repeats on
// frame 0, the table build included, in milliseconds per megapixel of
// receivers), RMSE, 99th-percentile error, light leaking and over-darkening
// on frame 0, flicker over the K frames, all over the valid receivers that
// face the light (scored_mask). Outputs in --out: results.csv,
// chart.png (time against error, each method's Pareto front), and per scene
// <scene>/truth.png and <scene>/<method>.{exr,png} + <method>_error.png for
// the method's preview setting.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "args.h"
#include "commands.h"
#include "demo_methods.h"
#include "output_directory.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/png_io.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/metrics.h"
#include "progress.h"

namespace penumbra::cli {

extern const char* const kSpeedAccuracyChartScript;

namespace {

namespace fs = std::filesystem;

struct DemoOptions {
    bool quick = false;
    fs::path out = "out/demo";
    Backend backend = Backend::Auto;
    std::vector<std::string> scenes, methods;
    int map_size = 0;  // 0: the scene's own, capped (see below)
    ViewSize view{320, 240};
    int strata = 24, frames = 3, repeats = 3;
};

std::vector<std::string> split_list(const std::string& text)
{
    std::vector<std::string> items;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) items.push_back(item);
    return items;
}

DemoOptions parse_options(const std::vector<std::string>& argv)
{
    const Args args(argv, {"--out", "--backend", "--scene", "--method", "--map-size", "--view-size", "--samples", "--frames"},
                    {"--quick"});
    DemoOptions o;
    o.quick = args.flag("--quick");
    if (o.quick) {
        o.view = {128, 96};
        o.strata = 10;
        o.frames = 2;
        o.repeats = 2;
    }
    o.out = args.text("--out", o.out.string());
    try {
        o.backend = parse_backend(args.text("--backend", "auto"));
    } catch (const Error& e) {
        throw UsageError{e.what()};
    }
    o.scenes = split_list(args.text("--scene", ""));
    if (o.scenes.empty()) o.scenes = reference::builtin_scene_names();
    o.methods = split_list(args.text("--method", ""));
    o.map_size = args.integer("--map-size", 0);
    if (o.map_size < 0 || o.map_size > 16384) throw UsageError{"option --map-size: must be in [1, 16384]"};
    if (auto view = args.get("--view-size")) o.view = parse_view_size(*view);
    if (auto samples = args.get("--samples")) o.strata = strata_for_samples(args.integer("--samples", 0));
    o.frames = args.integer("--frames", o.frames);
    if (o.frames < 2 || o.frames > 16) throw UsageError{"option --frames: must be in [2, 16] (flicker needs two)"};
    return o;
}

// Default map sizes keep the whole demo within minutes: the scene's own size
// capped at 2048 (the `large` scene's 16384 only with --map-size), 256 quick.
int map_size_for(const reference::Scene& scene, const DemoOptions& o)
{
    if (o.map_size) return o.map_size;
    return std::min(scene.map_size, o.quick ? 256 : 2048);
}

std::uint64_t fnv1a(const std::string& text)
{
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
    return h;
}

Image cached_truth(const reference::Scene& scene, const reference::Receivers& rx, int strata, const fs::path& cache)
{
    char key[17];
    std::snprintf(key, sizeof key, "%016llx",
                  static_cast<unsigned long long>(fnv1a(reference::scene_to_json(scene) + "|" + std::to_string(rx.width()) +
                                                        "x" + std::to_string(rx.height()) + "|" + std::to_string(strata))));
    const fs::path file = cache / ("truth-" + scene.name + "-" + key + ".exr");
    if (fs::exists(file)) {
        try {
            Image truth = read_exr(file.string(), {"Y"});
            if (truth.width() == rx.width() && truth.height() == rx.height()) return truth;
        } catch (const Error&) {
            // A damaged cache entry is recomputed below.
        }
    }
    Image truth = reference::ground_truth(scene, rx, {strata});
    create_output_directory(cache, "--out");
    write_exr(file.string(), truth, {"Y"});
    return truth;
}

std::vector<DemoFrame> render_frames(const reference::Scene& scene, const DemoOptions& o, Progress& progress)
{
    const int map = map_size_for(scene, o);
    std::vector<DemoFrame> frames;
    for (const reference::Scene& shifted : reference::flicker_frames(scene, o.frames, map, map)) {
        DemoFrame f{shifted, reference::render_shadow_map(shifted, map, map),
                    reference::render_receivers(shifted, o.view.width, o.view.height), Image()};
        f.truth = cached_truth(shifted, f.receivers, o.strata, o.out / "cache");
        frames.push_back(std::move(f));
        progress.step(scene.name + ": ground truth");
    }
    return frames;
}

double median_ms(std::vector<double> times)
{
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

struct Row {
    std::string scene, method, setting;
    double ms_per_mpix, rmse, p99, leak, overdark, flicker;
};

Image signed_error(const Image& estimate, const Image& truth, const Image& mask)
{
    Image e(estimate.width(), estimate.height(), 1);
    for (int y = 0; y < e.height(); ++y)
        for (int x = 0; x < e.width(); ++x)
            e.at(0, x, y) = mask.at(0, x, y) > 0.5f ? estimate.at(0, x, y) - truth.at(0, x, y) : 0.0f;
    return e;
}

// The receivers the metrics count: valid ones that face the light's centre.
// A surface facing away gets no direct light in any renderer (its N.L term
// is zero, whatever the shadow says), and the truth there is 0 by geometry;
// counting those pixels would score the N.L term, not the shadow filter.
Image scored_mask(const DemoFrame& f)
{
    const reference::Receivers& rx = f.receivers;
    Image mask(rx.width(), rx.height(), 1);
    const reference::Vec3 light = f.scene.light.center;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            const double to_light_x = light.x - rx.world_position.at(0, x, y);
            const double to_light_y = light.y - rx.world_position.at(1, x, y);
            const double to_light_z = light.z - rx.world_position.at(2, x, y);
            const double facing = to_light_x * rx.normal.at(0, x, y) + to_light_y * rx.normal.at(1, x, y) +
                                  to_light_z * rx.normal.at(2, x, y);
            mask.at(0, x, y) = rx.mask.at(0, x, y) > 0.5f && facing > 0.0 ? 1.0f : 0.0f;
        }
    return mask;
}

Row measure(Context& ctx, const DemoSetting& setting, const std::vector<DemoFrame>& frames, int repeats,
            Image& first_estimate)
{
    const DemoFrame& f0 = frames[0];
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r) {
        const auto start = std::chrono::steady_clock::now();
        first_estimate = setting.run(ctx, f0);
        times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::vector<Image> estimates{first_estimate}, truths{f0.truth};
    for (std::size_t k = 1; k < frames.size(); ++k) {
        estimates.push_back(setting.run(ctx, frames[k]));
        truths.push_back(frames[k].truth);
    }
    const Image scored = scored_mask(f0);
    const Image* mask = &scored;
    const double mpix = double(f0.truth.width()) * f0.truth.height() / 1e6;
    return {f0.scene.name,
            "",
            setting.label,
            median_ms(times) / mpix,
            reference::rmse(first_estimate, f0.truth, mask),
            reference::p99_abs_error(first_estimate, f0.truth, mask),
            reference::light_leaking(first_estimate, f0.truth, mask),
            reference::over_darkening(first_estimate, f0.truth, mask),
            reference::flicker(estimates, truths, mask)};
}

void write_previews(const fs::path& dir, const std::string& method, const Image& estimate, const DemoFrame& f0)
{
    write_exr((dir / (method + ".exr")).string(), estimate, {"Y"});
    write_png((dir / (method + ".png")).string(), estimate);
    write_png((dir / (method + "_error.png")).string(),
              colormap_error(signed_error(estimate, f0.truth, scored_mask(f0)), 0.5f), PngTransfer::None);
}

void write_csv_rows(const fs::path& path, const std::vector<Row>& rows, const std::string& backend)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << "scene,method,settings,backend,ms_per_mpix,rmse,p99,leak,overdark,flicker\n";
    for (const Row& r : rows)
        out << r.scene << "," << r.method << ",\"" << r.setting << "\"," << backend << "," << r.ms_per_mpix << ","
            << r.rmse << "," << r.p99 << "," << r.leak << "," << r.overdark << "," << r.flicker << "\n";
    out.flush();
    if (!out) throw Error(ErrorCategory::Io, "demo", "could not write " + path.string());
}

void write_csv(const fs::path& path, const std::vector<Row>& rows, const std::string& backend)
{
    detail::write_file_atomically(path.string(), "demo", [&](const std::string& temporary) {
        write_csv_rows(temporary, rows, backend);
    });
}

// Runs `argv` (argv[0] an absolute path) without a shell and waits for it: the
// paths are single arguments whatever characters they hold, so no --out can
// inject a command (std::system with quoting once could: --out "q'; touch X; '").
int run_program(const std::vector<std::string>& argv)
{
    std::vector<char*> pointers;
    for (const std::string& word : argv) pointers.push_back(const_cast<char*>(word.c_str()));
    pointers.push_back(nullptr);
    pid_t child = 0;
    if (::posix_spawn(&child, pointers[0], nullptr, nullptr, pointers.data(), environ) != 0) return -1;
    int status = 0;
    while (::waitpid(child, &status, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Draws the chart with matplotlib through /usr/bin/python3 (Debian's, which
// has python3-matplotlib). A missing matplotlib is a warning, not a failure:
// the CSV and images are the results; the chart is their picture.
void draw_chart(const fs::path& out)
{
    const fs::path script = out / "speed_accuracy_chart.py";
    detail::write_file_atomically(script.string(), "demo", [](const std::string& temporary) {
        std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
        file << kSpeedAccuracyChartScript;
        if (!(file << std::flush)) throw Error(ErrorCategory::Io, "demo", "could not write the chart script");
    });
    const int status = run_program({"/usr/bin/python3", script.string(), (out / "results.csv").string(),
                                    (out / "chart.png").string()});
    if (status != 0)
        std::cerr << "penumbra demo: warning: the chart was not drawn (is python3-matplotlib installed?); "
                     "results.csv has the numbers\n";
}

void print_summary(const std::vector<Row>& rows)
{
    std::printf("%-8s %-12s %-11s %9s %7s %7s %7s %8s %7s\n", "scene", "method", "settings", "ms/Mpix", "RMSE", "p99",
                "leak", "overdark", "flicker");
    for (const Row& r : rows)
        std::printf("%-8s %-12s %-11s %9.2f %7.4f %7.4f %7.4f %8.4f %7.4f\n", r.scene.c_str(), r.method.c_str(),
                    r.setting.c_str(), r.ms_per_mpix, r.rmse, r.p99, r.leak, r.overdark, r.flicker);
}

bool wanted(const std::vector<std::string>& list, const std::string& name)
{
    return list.empty() || std::find(list.begin(), list.end(), name) != list.end();
}

// Refuses unknown names before any work (a typo once ran the whole demo for an
// empty results.csv and a Python traceback).
void require_known_methods(const DemoOptions& o)
{
    std::vector<std::string> known;
    for (const std::string& name : o.scenes) {
        const reference::Scene scene = reference::builtin_scene(name);
        for (const DemoMethod& m : demo_methods(scene, map_size_for(scene, o)))
            if (std::find(known.begin(), known.end(), m.name) == known.end()) known.push_back(m.name);
    }
    for (const std::string& name : o.methods)
        if (std::find(known.begin(), known.end(), name) == known.end()) {
            std::string list;
            for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
            throw UsageError{"option --method: '" + name + "' is not a method; the methods are " + list};
        }
}

}  // namespace

int demo_command(const std::vector<std::string>& argv)
{
    if (!argv.empty() && argv[0] == "--help") {
        std::cout << "usage: penumbra demo [--quick] [--out DIR] [--backend B] [--scene a,b] [--method a,b]\n"
                     "                     [--map-size N] [--view-size WxH] [--samples S] [--frames K]\n"
                     "  every method with a sweep of its settings on every built-in scene, against the\n"
                     "  ray-traced ground truth: DIR/results.csv, DIR/chart.png, DIR/<scene>/*.png|exr\n"
                     "  defaults: DIR=out/demo, 320x240 receivers, 576 rays each, 3 frames for flicker;\n"
                     "  --quick: 128x96 receivers, 100 rays, 2 frames, 256^2 maps\n";
        return 0;
    }
    const DemoOptions o = parse_options(argv);
    for (const std::string& name : o.scenes) reference::builtin_scene(name);  // fail early on a bad name
    require_known_methods(o);
    create_output_directory(o.out, "--out");
    Context ctx(ContextOptions{o.backend, {}});
    for (const std::string& w : ctx.warnings()) std::cerr << "penumbra demo: warning: " << w << "\n";
    std::cout << "penumbra demo on " << ctx.description() << "\n";

    int work = 0;
    for (const std::string& name : o.scenes) {
        const reference::Scene scene = reference::builtin_scene(name);
        work += o.frames;
        for (const DemoMethod& m : demo_methods(scene, map_size_for(scene, o)))
            if (wanted(o.methods, m.name)) work += int(m.settings.size());
    }
    Progress progress(work);
    std::vector<Row> rows;
    for (const std::string& name : o.scenes) {
        const reference::Scene scene = reference::builtin_scene(name);
        const std::vector<DemoFrame> frames = render_frames(scene, o, progress);
        progress.milestone(name + ": ground truth, " + std::to_string(o.frames) + " frames");
        const fs::path dir = o.out / name;
        create_output_directory(dir, "--out");
        write_png((dir / "truth.png").string(), frames[0].truth);
        for (const DemoMethod& m : demo_methods(scene, map_size_for(scene, o))) {
            if (!wanted(o.methods, m.name)) continue;
            for (std::size_t s = 0; s < m.settings.size(); ++s) {
                Image estimate;
                Row row = measure(ctx, m.settings[s], frames, o.repeats, estimate);
                row.method = m.name;
                rows.push_back(row);
                if (int(s) == m.preview_setting) write_previews(dir, m.name, estimate, frames[0]);
                progress.step(name + ": " + m.name + " " + m.settings[s].label);
            }
            progress.milestone(name + ": " + m.name);
        }
    }
    progress.finish();  // the bar's line ends before the chart's and the table's output
    write_csv(o.out / "results.csv", rows, to_string(ctx.backend()));
    draw_chart(o.out);
    print_summary(rows);
    std::cout << "wrote " << (o.out / "results.csv").string() << " and " << (o.out / "chart.png").string() << "\n";
    return 0;
}

}  // namespace penumbra::cli
