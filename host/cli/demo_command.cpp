// penumbra demo: every method, with a small sweep of its settings, on every
// built-in scene, measured against the ray-traced ground truth.
//
// Per scene: K frames with the light moved by sub-texel steps (frame 0 is the
// scene itself); the truth of each frame is cached on disk, keyed by the
// scene and the sizes, and frame 0 also gets a truth with 4x the rays, whose
// difference from it is the truth's own noise. Per method and setting, scored
// on the view's receivers (scored_mask: valid ones facing the light): RMSE,
// 99th-percentile error, light leaking and over-darkening on frame 0, flicker
// over the K frames. Timed on a frame of its own size (1920x1080 receivers
// by default, demo_timing.h): the per-map and per-receiver steps, medians of
// interleaved repetitions with their spread. Outputs in --out: results.csv,
// chart.png (time against error, each method's Pareto front), index.html
// (demo_report.h), and per scene <scene>/truth.png and
// <scene>/<method>.{exr,png} + <method>_error.png for the method's preview
// setting.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>

#include "args.h"
#include "commands.h"
#include "demo_images.h"
#include "demo_methods.h"
#include "demo_report.h"
#include "demo_results.h"
#include "demo_summary.h"
#include "demo_timing.h"
#include "output_directory.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/png_io.h"
#include "penumbra/reference/cascades.h"
#include "penumbra/reference/deep_map.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/metrics.h"
#include "penumbra/reference/obscurance_truth.h"
#include "penumbra/ssao.h"
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
    ViewSize frame{1920, 1080};  // the timed receivers
    int strata = 24, frames = 3, repetitions = 5;
    std::vector<double> budgets_ms = kDemoBudgetsMs;
};

// The timed frame's largest side: 4096^2 receivers are 0.8 GB of buffers.
constexpr int kLargestFrame = 4096;
constexpr int kFewestRepetitions = 5, kMostRepetitions = 100;

std::vector<std::string> split_list(const std::string& text)
{
    std::vector<std::string> items;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) items.push_back(item);
    return items;
}

// "16,33,100": milliseconds per timed frame, each in (0, 1e6], at most 8.
std::vector<double> parse_budgets(const std::string& text)
{
    std::vector<double> budgets;
    for (const std::string& item : split_list(text)) {
        char* end = nullptr;
        const double ms = std::strtod(item.c_str(), &end);
        if (end == item.c_str() || *end != '\0' || !(ms > 0.0 && ms <= 1e6))
            throw UsageError{"option --budgets: '" + item + "' is not a time in ms in (0, 1e6]; give e.g. 16,33,100"};
        budgets.push_back(ms);
    }
    if (budgets.empty() || budgets.size() > 8)
        throw UsageError{"option --budgets: give 1 to 8 times in ms, e.g. 16,33,100"};
    std::sort(budgets.begin(), budgets.end());
    return budgets;
}

// --scene: scene names and the sets `opaque` (the five shadow-map scenes),
// `deep` (hair, fog, layers) and `all` (the default: both), in order, each once.
std::vector<std::string> scene_list(const std::string& text)
{
    const std::pair<const char*, reference::SceneSet> sets[] = {
        {"opaque", reference::SceneSet::Opaque}, {"deep", reference::SceneSet::Deep}, {"all", reference::SceneSet::All}};
    std::vector<std::string> scenes;
    auto add = [&](const std::string& name) {
        if (std::find(scenes.begin(), scenes.end(), name) == scenes.end()) scenes.push_back(name);
    };
    for (const std::string& item : split_list(text)) {
        const auto set = std::find_if(std::begin(sets), std::end(sets), [&](const auto& s) { return item == s.first; });
        if (set == std::end(sets)) add(item);
        else
            for (const std::string& name : reference::builtin_scene_names(set->second)) add(name);
    }
    if (scenes.empty()) throw UsageError{"option --scene: give scene names or opaque, deep, all"};
    return scenes;
}

DemoOptions parse_options(const std::vector<std::string>& argv)
{
    const Args args(argv,
                    {"--out", "--backend", "--scene", "--method", "--map-size", "--view-size", "--samples", "--frames",
                     "--frame", "--repetitions", "--budgets"},
                    {"--quick"});
    DemoOptions o;
    o.quick = args.flag("--quick");
    if (o.quick) {
        o.view = {128, 96};
        o.frame = {240, 135};
        o.strata = 10;
        o.frames = 2;
    }
    o.out = args.text("--out", o.out.string());
    try {
        o.backend = parse_backend(args.text("--backend", "auto"));
    } catch (const Error& e) {
        throw UsageError{e.what()};
    }
    o.scenes = scene_list(args.text("--scene", "all"));
    o.methods = split_list(args.text("--method", ""));
    o.map_size = args.integer("--map-size", 0);
    if (o.map_size < 0 || o.map_size > 16384) throw UsageError{"option --map-size: must be in [1, 16384]"};
    if (auto view = args.get("--view-size")) o.view = parse_view_size(*view);
    if (auto samples = args.get("--samples")) o.strata = strata_for_samples(args.integer("--samples", 0));
    o.frames = args.integer("--frames", o.frames);
    if (o.frames < 2 || o.frames > 16) throw UsageError{"option --frames: must be in [2, 16] (flicker needs two)"};
    if (auto frame = args.get("--frame")) o.frame = parse_view_size(*frame, "--frame", kLargestFrame);
    o.repetitions = args.integer("--repetitions", o.repetitions);
    if (o.repetitions < kFewestRepetitions || o.repetitions > kMostRepetitions)
        throw UsageError{"option --repetitions: must be in [5, 100] (a median of fewer follows the machine's noise)"};
    if (auto budgets = args.get("--budgets")) o.budgets_ms = parse_budgets(*budgets);
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

// A truth image of the view, cached on disk under `kind` ("truth" for the
// frame's shadow truth), keyed by the scene, the sizes and the strata.
Image cached_image(const std::string& kind, const reference::Scene& scene, const reference::Receivers& rx,
                   int strata, const fs::path& cache, const std::function<Image()>& compute)
{
    char key[17];
    std::snprintf(key, sizeof key, "%016llx",
                  static_cast<unsigned long long>(fnv1a(reference::scene_to_json(scene) + "|" + std::to_string(rx.width()) +
                                                        "x" + std::to_string(rx.height()) + "|" + std::to_string(strata))));
    const fs::path file = cache / (kind + "-" + scene.name + "-" + key + ".exr");
    if (fs::exists(file)) {
        try {
            Image truth = read_exr(file.string(), {"Y"});
            if (truth.width() == rx.width() && truth.height() == rx.height()) return truth;
        } catch (const Error&) {
            // A damaged cache entry is recomputed below.
        }
    }
    Image truth = compute();
    create_output_directory(cache, "--out");
    write_exr(file.string(), truth, {"Y"});
    return truth;
}

Image cached_truth(const reference::Scene& scene, const reference::Receivers& rx, int strata, const fs::path& cache)
{
    return cached_image("truth", scene, rx, strata, cache,
                        [&] { return reference::ground_truth(scene, rx, {strata}); });
}

// Volumetric obscurance of ssao-vo's ball: 8^3 points a receiver (4^3
// quick), docs/ssao.md's accuracy table's; it does not depend on the light,
// so frame 0's serves every frame.
std::shared_ptr<const Image> obscurance_truth(const DemoFrame& f0, bool quick, const fs::path& cache)
{
    const int strata = quick ? 4 : 8;
    return std::make_shared<const Image>(cached_image("obscurance", f0.scene, f0.receivers, strata, cache, [&] {
        return reference::volumetric_obscurance_truth(f0.scene, f0.receivers, {SsaoOptions{}.radius, strata});
    }));
}

// A scene's frames, the receivers its settings are timed on, and the truth's noise.
struct SceneFrames {
    std::vector<DemoFrame> frames;
    reference::Receivers timed;
    double truth_noise = 0;
};

std::shared_ptr<const DeepShadowMap> render_deep_map(const reference::Scene& scene, int map_size)
{
    reference::DeepMapOptions options;
    options.size = demo_deep_map_size(map_size);
    options.samples = kDemoDeepSamples;
    return std::make_shared<const DeepShadowMap>(reference::render_deep_shadow_map(scene, options));
}

// What the wanted methods read beside the shadow map: the deep and Pismo
// maps per frame, the obscurance truth and the sun's inputs once a scene.
struct FrameInputs {
    bool deep = false, pismo = false, obscurance = false, sun = false;
};

std::vector<DemoFrame> render_frames(const reference::Scene& scene, const DemoOptions& o, FrameInputs inputs,
                                     Progress& progress)
{
    const int map = map_size_for(scene, o);
    std::vector<DemoFrame> frames;
    for (const reference::Scene& shifted : reference::flicker_frames(scene, o.frames, map, map)) {
        DemoFrame f{shifted, reference::render_shadow_map(shifted, map, map),
                    reference::render_receivers(shifted, o.view.width, o.view.height), Image(), nullptr, nullptr,
                    nullptr, nullptr};
        if (inputs.deep) f.deep_map = render_deep_map(shifted, map);
        if (inputs.pismo) f.pismo_maps = demo_pismo_maps(shifted, map, f.receivers);
        f.truth = cached_truth(shifted, f.receivers, o.strata, o.out / "cache");
        if (!frames.empty()) {
            f.obscurance_truth = frames[0].obscurance_truth;
            f.sun = frames[0].sun;
        } else {
            if (inputs.obscurance) f.obscurance_truth = obscurance_truth(f, o.quick, o.out / "cache");
            if (inputs.sun) f.sun = render_sun_inputs(shifted, map, f.receivers);
        }
        frames.push_back(std::move(f));
        progress.step(scene.name + ": ground truth");
    }
    return frames;
}

// The receivers the metrics count: valid ones that face the light's centre.
// A surface facing away gets no direct light in any renderer (its N.L term
// is zero, whatever the shadow says), and the truth there is 0 by geometry;
// counting those pixels would score the N.L term, not the shadow filter.
// Obscurance has no light: every valid receiver counts. The sun's are those
// facing against its direction.
Image scored_mask(const DemoFrame& f, DemoTruth truth = DemoTruth::Shadow)
{
    const reference::Receivers& rx = f.receivers;
    Image mask(rx.width(), rx.height(), 1);
    const reference::Vec3 light = f.scene.light.center;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            reference::Vec3 to_light{light.x - rx.world_position.at(0, x, y), light.y - rx.world_position.at(1, x, y),
                                     light.z - rx.world_position.at(2, x, y)};
            if (truth == DemoTruth::Sun) {
                const reference::Vec3 d = f.scene.directional_lights[0].direction;
                to_light = {-d.x, -d.y, -d.z};
            }
            const double facing = to_light.x * rx.normal.at(0, x, y) + to_light.y * rx.normal.at(1, x, y) +
                                  to_light.z * rx.normal.at(2, x, y);
            const bool lit_side = truth == DemoTruth::Obscurance || facing > 0.0;
            mask.at(0, x, y) = rx.mask.at(0, x, y) > 0.5f && lit_side ? 1.0f : 0.0f;
        }
    return mask;
}

// What a method's rows are scored against (DemoMethod::truth).
const Image& truth_of(const DemoFrame& f, DemoTruth truth)
{
    switch (truth) {
    case DemoTruth::Obscurance: return *f.obscurance_truth;
    case DemoTruth::Sun: return f.sun->truth;
    default: return f.truth;
    }
}

// Frame 0's truth against one with twice the strata per axis (4x the rays):
// the noise of the truth itself, below which two RMSEs cannot be told apart.
double truth_noise(const DemoFrame& f0, const DemoOptions& o)
{
    const Image finer = cached_truth(f0.scene, f0.receivers, 2 * o.strata, o.out / "cache");
    const Image scored = scored_mask(f0);
    return reference::rmse(f0.truth, finer, &scored);
}

SceneFrames render_scene_frames(const reference::Scene& scene, const DemoOptions& o, FrameInputs inputs,
                                Progress& progress)
{
    SceneFrames s{render_frames(scene, o, inputs, progress), {}, 0.0};
    s.truth_noise = truth_noise(s.frames[0], o);
    s.timed = reference::render_receivers(s.frames[0].scene, o.frame.width, o.frame.height);
    return s;
}

std::string format_ms(double ms)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", ms);
    return text;
}

// The accuracy of one setting (its times come later, from time_settings).
DemoRow measure(Context& ctx, const DemoSetting& setting, DemoTruth truth, const std::vector<DemoFrame>& frames,
                Image& first_estimate)
{
    const DemoFrame& f0 = frames[0];
    first_estimate = run_setting(ctx, setting, f0);
    std::vector<Image> estimates{first_estimate}, truths{truth_of(f0, truth)};
    for (std::size_t k = 1; k < frames.size(); ++k) {
        estimates.push_back(run_setting(ctx, setting, frames[k]));
        truths.push_back(truth_of(frames[k], truth));
    }
    const Image scored = scored_mask(f0, truth);
    const Image* mask = &scored;
    DemoRow row{f0.scene.name, "", setting.label, truth, {}, 0, 0, 0, 0, 0, 0};
    row.rmse = reference::rmse(first_estimate, truths[0], mask);
    row.p99 = reference::p99_abs_error(first_estimate, truths[0], mask);
    row.leak = reference::light_leaking(first_estimate, truths[0], mask);
    row.overdark = reference::over_darkening(first_estimate, truths[0], mask);
    row.flicker = reference::flicker(estimates, truths, mask);
    return row;
}

void write_previews(const fs::path& dir, const DemoMethod& method, const Image& estimate, const DemoFrame& f0)
{
    const Image scored = scored_mask(f0, method.truth);
    write_exr((dir / (method.name + ".exr")).string(), estimate, {"Y"});
    write_visibility_png((dir / (method.name + ".png")).string(), estimate, f0.receivers.mask, scored);
    write_error_png((dir / (method.name + "_error.png")).string(), estimate, truth_of(f0, method.truth),
                    f0.receivers.mask, scored);
}

std::string frame_text(ViewSize frame)
{
    return std::to_string(frame.width) + "x" + std::to_string(frame.height);
}

void write_csv_rows(const fs::path& path, const std::vector<DemoRow>& rows, const std::string& backend,
                    const std::string& frame)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << "scene,method,settings,backend,frame,map_ms,receiver_ms,frame_ms,frame_ms_min,frame_ms_max,repetitions,"
           "rmse,p99,leak,overdark,flicker,truth_noise,truth\n";
    for (const DemoRow& r : rows)
        out << r.scene << "," << r.method << ",\"" << r.setting << "\"," << backend << "," << frame << ","
            << r.time.map_ms << "," << r.time.receiver_ms << "," << r.time.frame_ms << "," << r.time.frame_min_ms << ","
            << r.time.frame_max_ms << "," << r.time.repetitions << "," << r.rmse << "," << r.p99 << "," << r.leak
            << "," << r.overdark << "," << r.flicker << "," << r.truth_noise << "," << truth_name(r.truth) << "\n";
    out.flush();
    if (!out) throw Error(ErrorCategory::Io, "demo", "could not write " + path.string());
}

void write_csv(const fs::path& path, const std::vector<DemoRow>& rows, const std::string& backend,
               const std::string& frame)
{
    detail::write_file_atomically(path.string(), "demo", [&](const std::string& temporary) {
        write_csv_rows(temporary, rows, backend, frame);
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
bool draw_chart(const fs::path& out)
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
    return status == 0;
}

void print_table(const std::vector<DemoRow>& rows, const std::string& frame)
{
    std::printf("times in ms per %s frame: map (the table build), receivers, frame = both (median, min-max)\n",
                frame.c_str());
    std::printf("%-8s %-16s %-18s %8s %8s %8s %15s %7s %7s %7s %8s %7s\n", "scene", "method", "settings", "map",
                "recv", "frame", "min-max", "RMSE", "p99", "leak", "overdark", "flicker");
    for (const DemoRow& r : rows)
        std::printf("%-8s %-16s %-18s %8.3g %8.3g %8.3g %7.3g-%-7.3g %7.4f %7.4f %7.4f %8.4f %7.4f\n", r.scene.c_str(),
                    r.method.c_str(), r.setting.c_str(), r.time.map_ms, r.time.receiver_ms, r.time.frame_ms,
                    r.time.frame_min_ms, r.time.frame_max_ms, r.rmse, r.p99, r.leak, r.overdark, r.flicker);
}

void print_summary(const std::vector<SceneSummary>& summaries, const std::string& frame)
{
    if (summaries.empty()) return;  // only obscurance or sun rows were asked for
    std::printf("\nsummary: the most accurate method within each budget per %s frame, and overall\n",
                frame.c_str());
    for (const SceneSummary& s : summaries) {
        std::printf("%s (the truth's own noise: RMSE %.4f; closer than that is a tie)\n", s.scene.c_str(),
                    s.truth_noise);
        for (const DemoPick& pick : s.picks) {
            const std::string budget = pick.budget_ms > 0 ? "<= " + format_ms(pick.budget_ms) + " ms" : "overall";
            std::printf("  %-10s %s\n", budget.c_str(), describe_pick(pick).c_str());
        }
    }
}

// What --quick's small sizes do to the rows, measured (docs/demo.md): said
// in the output, so that nobody reads a setting with no effect as a defect.
constexpr const char* kQuickCaveat =
    "--quick: 256^2 maps and a coarse distance grid. On `large` (a scene for a 16384^2 map) the map's texels, not "
    "the settings, set most of the error: vssm's and msm-soft's light sizes move RMSE by under 0.001 here, against "
    "0.024-0.038 in the full run. The classic sdf rows share one over-darkening: it comes from the grid's surfaces "
    "(a hit is 0 whatever k), and p99 1.0 from leaks through poles thinner than a voxel.";

// The rule for point lights (the deep scenes), said where the rows are read.
constexpr const char* kPointLightNote =
    "Under a point light (hair, fog, layers) the truth is exact, one ray per receiver, so its noise is 0; the soft "
    "methods, which need a light size, are sized for a square light whose penumbra is one texel of the map "
    "(docs/deep_shadow_maps.md).";

bool wanted(const std::vector<std::string>& list, const std::string& name)
{
    return list.empty() || std::find(list.begin(), list.end(), name) != list.end();
}

std::string joined(const std::vector<std::string>& items)
{
    std::string list;
    for (const std::string& item : items) list += (list.empty() ? "" : ", ") + item;
    return list;
}

// The methods with rows on the scenes named, in order, each once.
std::vector<std::string> methods_on(const std::vector<std::string>& scenes, const DemoOptions& o)
{
    std::vector<std::string> known;
    for (const std::string& name : scenes) {
        const reference::Scene scene = reference::builtin_scene(name);
        for (const DemoMethod& m : demo_methods(scene, map_size_for(scene, o)))
            if (std::find(known.begin(), known.end(), m.name) == known.end()) known.push_back(m.name);
    }
    return known;
}

// Refuses unknown names before any work (a typo once ran the whole demo for an
// empty results.csv and a Python traceback), and a method with no rows on
// the scenes asked for (ssao-vo needs an opaque scene, the sun's rows a
// directional light), naming the scenes it has rows on.
void require_known_methods(const DemoOptions& o)
{
    const std::vector<std::string> known = methods_on(o.scenes, o);
    for (const std::string& name : o.methods) {
        if (std::find(known.begin(), known.end(), name) != known.end()) continue;
        std::vector<std::string> scenes_with_it;
        for (const std::string& scene : reference::builtin_scene_names(reference::SceneSet::All)) {
            const std::vector<std::string> there = methods_on({scene}, o);
            if (std::find(there.begin(), there.end(), name) != there.end()) scenes_with_it.push_back(scene);
        }
        if (!scenes_with_it.empty())
            throw UsageError{"option --method: '" + name + "' has no rows on the scenes asked for (" + joined(o.scenes) +
                             "); it runs on " + joined(scenes_with_it)};
        throw UsageError{"option --method: '" + name + "' is not a method; the methods are " + joined(known)};
    }
}

// What the scenes' runs gather for the outputs.
struct DemoResults {
    std::vector<DemoRow> rows;
    std::vector<std::pair<std::string, double>> truth_noise;        // per scene
    std::vector<std::pair<std::string, std::vector<DemoPicture>>> pictures;  // per scene
};

// The units of progress: per scene its truths, its settings and its timing.
int count_work(const DemoOptions& o)
{
    int work = 0;
    for (const std::string& name : o.scenes) {
        const reference::Scene scene = reference::builtin_scene(name);
        work += o.frames + 1;
        for (const DemoMethod& m : demo_methods(scene, map_size_for(scene, o)))
            if (wanted(o.methods, m.name)) work += int(m.settings.size());
    }
    return work;
}

std::vector<DemoMethod> wanted_methods(const reference::Scene& scene, const DemoOptions& o)
{
    std::vector<DemoMethod> methods;
    for (DemoMethod& m : demo_methods(scene, map_size_for(scene, o)))
        if (wanted(o.methods, m.name)) methods.push_back(std::move(m));
    return methods;
}

// One scene: its truths, each setting's accuracy (and the preview setting's
// pictures), then every setting timed on the frame.
void run_scene(Context& ctx, const DemoOptions& o, const reference::Scene& scene, Progress& progress,
               DemoResults& results)
{
    const std::string& name = scene.name;
    const std::vector<DemoMethod> methods = wanted_methods(scene, o);
    const auto reads = [&](MethodInput input) {
        return std::any_of(methods.begin(), methods.end(), [input](const DemoMethod& m) { return m.input == input; });
    };
    const auto scored_against = [&](DemoTruth truth) {
        return std::any_of(methods.begin(), methods.end(), [truth](const DemoMethod& m) { return m.truth == truth; });
    };
    const SceneFrames scene_frames = render_scene_frames(
        scene, o,
        {reads(MethodInput::DeepMap), reads(MethodInput::PismoMapSet), scored_against(DemoTruth::Obscurance),
         scored_against(DemoTruth::Sun)},
        progress);
    const std::vector<DemoFrame>& frames = scene_frames.frames;
    results.truth_noise.emplace_back(name, scene_frames.truth_noise);
    progress.milestone(name + ": ground truth, " + std::to_string(o.frames) + " frames");
    const fs::path dir = o.out / name;
    create_output_directory(dir, "--out");
    write_visibility_png((dir / "truth.png").string(), frames[0].truth, frames[0].receivers.mask,
                         scored_mask(frames[0]));
    std::vector<const DemoSetting*> settings;
    std::vector<DemoPicture> pictures;
    const std::size_t first_row = results.rows.size();
    for (const DemoMethod& m : methods) {
        for (std::size_t s = 0; s < m.settings.size(); ++s) {
            Image estimate;
            DemoRow row = measure(ctx, m.settings[s], m.truth, frames, estimate);
            row.method = m.name;
            // The sun's truth is one exact ray a receiver; the obscurance
            // truth's noise is not measured here (docs/demo.md).
            row.truth_noise = m.truth == DemoTruth::Shadow ? scene_frames.truth_noise : 0.0;
            results.rows.push_back(row);
            settings.push_back(&m.settings[s]);
            if (int(s) == m.preview_setting) {
                write_previews(dir, m, estimate, frames[0]);
                pictures.push_back({m.name, m.settings[s].label});
            }
            progress.step(name + ": " + m.name + " " + m.settings[s].label);
        }
        progress.milestone(name + ": " + m.name);
    }
    const std::vector<FrameTimes> times = time_settings(ctx, settings, frames[0], scene_frames.timed, o.repetitions);
    for (std::size_t i = 0; i < times.size(); ++i) results.rows[first_row + i].time = times[i];
    progress.step(name + ": timing");
    progress.milestone(name + ": timing, " + std::to_string(settings.size()) + " settings x " +
                       std::to_string(o.repetitions) + " on " + frame_text(o.frame));
    results.pictures.emplace_back(name, std::move(pictures));
}

std::string protocol_text(const DemoOptions& o)
{
    std::string text = "Scored on " + frame_text(o.view) + " receivers against a ground truth of " +
                       std::to_string(o.strata * o.strata) + " rays per receiver, " + std::to_string(o.frames) +
                       " frames for flicker; timed on " + frame_text(o.frame) + " receivers, medians of " +
                       std::to_string(o.repetitions) + " interleaved repetitions after a warm-up.";
    if (std::any_of(o.scenes.begin(), o.scenes.end(), [](const std::string& name) {
            return reference::builtin_scene(name).light.shape == reference::LightShape::Point;
        }))
        text.append(" ").append(kPointLightNote);
    if (o.quick) text.append(" ").append(kQuickCaveat);
    return text;
}

// The CSV, the chart, the printed table and summary, and the report.
void write_outputs(Context& ctx, const DemoOptions& o, DemoResults& results)
{
    const std::string frame = frame_text(o.frame);
    write_csv(o.out / "results.csv", results.rows, to_string(ctx.backend()), frame);
    write_error_scale_png((o.out / "error_scale.png").string());
    DemoReport report;
    report.chart = draw_chart(o.out);
    const std::vector<SceneSummary> summaries = summarize_scenes(results.rows, results.truth_noise, o.budgets_ms);
    print_table(results.rows, frame);
    print_summary(summaries, frame);
    if (o.quick) std::cout << "note: " << kQuickCaveat << "\n";
    report.machine = "penumbra demo on " + ctx.description();
    report.protocol = protocol_text(o);
    report.rows = &results.rows;
    report.summaries = &summaries;
    report.pictures = std::move(results.pictures);
    report.frame = frame;
    write_report(o.out, report);
    std::cout << "wrote " << (o.out / "results.csv").string() << ", " << (o.out / "chart.png").string() << " and "
              << (o.out / "index.html").string() << "\n";
}

}  // namespace

int demo_command(const std::vector<std::string>& argv)
{
    if (!argv.empty() && argv[0] == "--help") {
        std::cout << "usage: penumbra demo [--quick] [--out DIR] [--backend B] [--scene a,b|SET] [--method a,b]\n"
                     "                     [--map-size N] [--view-size WxH] [--samples S] [--frames K]\n"
                     "                     [--frame WxH] [--repetitions N] [--budgets MS,MS,...]\n"
                     "  every method with a sweep of its settings on every built-in scene, against the\n"
                     "  ray-traced ground truth: DIR/index.html (the report), DIR/results.csv,\n"
                     "  DIR/chart.png, DIR/<scene>/*.png|exr\n"
                     "  --scene: names, or a SET: opaque (the five shadow-map scenes), deep (hair,\n"
                     "  fog, layers: point lights, exact truth) and all (the default)\n"
                     "  scored on --view-size receivers (default 320x240, 576 rays each, 3 frames for\n"
                     "  flicker); timed on --frame receivers (default 1920x1080): the map's and the\n"
                     "  receivers' work apart, medians of --repetitions (default 5, at least 5)\n"
                     "  interleaved runs after a warm-up; the summary's budgets per frame: --budgets\n"
                     "  (default 16,33,100 ms)\n"
                     "  --quick: 128x96 receivers, 100 rays, 2 frames, 256^2 maps, a 240x135 frame\n";
        return 0;
    }
    const DemoOptions o = parse_options(argv);
    for (const std::string& name : o.scenes) reference::builtin_scene(name);  // fail early on a bad name
    require_known_methods(o);
    create_output_directory(o.out, "--out");
    Context ctx(ContextOptions{o.backend, {}});
    for (const std::string& w : ctx.warnings()) std::cerr << "penumbra demo: warning: " << w << "\n";
    std::cout << "penumbra demo on " << ctx.description() << "\n";

    Progress progress(count_work(o));
    DemoResults results;
    for (const std::string& name : o.scenes) run_scene(ctx, o, reference::builtin_scene(name), progress, results);
    progress.finish();  // the bar's line ends before the chart's and the table's output
    write_outputs(ctx, o, results);
    return 0;
}

}  // namespace penumbra::cli
