// Issue 15's measured convergence of Pismo (docs/pismo.md, "Convergence to
// the truth's noise"): on contact, overlap and fence, the RMSE against the
// ray-traced truth of Pismo (layered maps), the average of hard shadows from
// the same maps and the maximum-depth variant, as the light mesh goes from
// level 0 to 4 (4 to 289 maps; 1024^2 maps to level 3), for these map settings:
//   frustum  cameras holding the scene's whole light frustum (pismo_vertex_camera)
//   fitted   cameras fitted to the view's receivers (pismo_fitted_camera)
// at the map sizes given; beside each row the truth's own noise and the maps'
// memory and render time; and the same errors on the receivers that lie on
// the scene's planes (the ground: outside the casters' hull, where only the
// maps' resolution and the rays limit the answer, not the casters' own
// terminators). Every test counts the receiver's own surface (its normal,
// docs/pismo.md "The receiver's own surface"). All in float64 (tests/support/pismo_reference.h),
// no kernel. Prints a Markdown table and writes every row to a CSV for
// bench/pismo_acceptance_chart.py. Figures, not checks.
//
// usage: pismo_acceptance [--quick] [--scenes A,B] [--settings fitted:1024:3,...] [--centred-grids]
//                         [--surface-ids] OUT.csv
//   --scenes        a subset of contact, overlap, fence
//   --settings      cameras:map size:highest level, instead of the four above
//   --centred-grids every map's pixel grid centred on the fixation point, as
//                   before the shifted grids (LayeredMapOptions::shift_grids)
//   --surface-ids   each test knows the receiver's surface and each layer's
//                   (PismoReferenceOptions::surface_ids, docs/pismo.md "A
//                   surface id per layer"); maps MB then counts the ids (4 B a layer)
//
// The truth has S x S strata per receiver; its noise is its RMSE against the
// truth at 2S x 2S (4x the rays), which holds about sqrt(1 + 1/4) times the
// S truth's own noise. Pismo casts S x S rays per receiver, so at the floor
// its RMSE is about sqrt(2) times the truth's noise: its own sampling noise
// and the truth's, when the maps add no error of their own.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/metrics.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/render.h"
#include "support/pismo_estimates.h"

using namespace penumbra;

namespace {

struct MapSetting {
    std::string cameras;  // "frustum" or "fitted"
    int size;
    int max_level;  // 289 maps of 1024^2 would be about 7 GB
};

struct Config {
    int view_width = 64, view_height = 48;
    int strata = 32;
    std::vector<std::string> scenes = {"contact", "overlap", "fence"};
    std::vector<MapSetting> settings = {{"frustum", 384, 3}, {"fitted", 384, 4}, {"fitted", 512, 4},
                                         {"fitted", 1024, 3}};
    bool shift_grids = true;
    bool surface_ids = false;
};

std::vector<std::string> split(const std::string& list, char separator)
{
    std::vector<std::string> items;
    std::istringstream in(list);
    for (std::string item; std::getline(in, item, separator);) items.push_back(item);
    return items;
}

// "fitted:1024:3" (cameras, map size, highest level), comma-separated.
std::vector<MapSetting> parse_settings(const std::string& list)
{
    std::vector<MapSetting> settings;
    for (const std::string& item : split(list, ',')) {
        const std::vector<std::string> parts = split(item, ':');
        if (parts.size() != 3 || (parts[0] != "fitted" && parts[0] != "frustum"))
            throw std::invalid_argument("a setting is fitted|frustum:SIZE:LEVEL, not '" + item + "'");
        settings.push_back({parts[0], std::stoi(parts[1]), std::stoi(parts[2])});
    }
    return settings;
}

struct Row {
    std::string scene, cameras;
    int size = 0, level = 0, maps = 0;
    double pismo = 0, averaged = 0, maximum_depth = 0, truth_noise = 0;
    double pismo_planes = 0, averaged_planes = 0, planes_noise = 0;  // on the planes' receivers only
    double megabytes = 0, render_seconds = 0;
};

struct SceneTruth {
    reference::Receivers rx;
    Image truth, planes;  // planes: the receivers on the scene's planes, outside the casters' hull
    double noise = 0, planes_noise = 0;
};

SceneTruth truth_for(const reference::Scene& scene, const Config& c)
{
    SceneTruth t{reference::render_receivers(scene, c.view_width, c.view_height), Image(), Image(), 0, 0};
    t.truth = reference::ground_truth(scene, t.rx, {c.strata});
    t.planes = testing::receivers_on_planes(scene, t.rx, true);
    const Image finer = reference::ground_truth(scene, t.rx, {2 * c.strata});
    t.noise = reference::rmse(t.truth, finer, &t.rx.mask);
    t.planes_noise = reference::rmse(t.truth, finer, &t.planes);
    return t;
}

Row measure(const reference::Scene& scene, const SceneTruth& t, const MapSetting& setting, int level, const Config& c)
{
    reference::LayeredMapOptions mo;
    mo.size = setting.size;
    mo.shift_grids = c.shift_grids;
    const bool fitted = setting.cameras == "fitted";
    const std::vector<reference::Vec3> region = fitted ? reference::receiver_region(t.rx) : std::vector<reference::Vec3>{};
    const auto start = std::chrono::steady_clock::now();
    const reference::PismoMaps maps = reference::render_pismo_maps(scene, level, mo, region);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    testing::PismoReferenceOptions po;
    po.rays = c.strata * c.strata;
    po.surface_ids = c.surface_ids;
    std::size_t id_bytes = 0;
    if (c.surface_ids)
        for (const auto& ids : maps.surface_ids) id_bytes += 4 * ids.size();
    const testing::PismoEstimates e = testing::pismo_estimates(maps, t.rx, po, true);
    const Image* mask = &t.rx.mask;
    return {scene.name,
            setting.cameras,
            setting.size,
            level,
            int(maps.maps.size()),
            reference::rmse(e.pismo, t.truth, mask),
            reference::rmse(e.averaged, t.truth, mask),
            reference::rmse(e.maximum_depth, t.truth, mask),
            t.noise,
            reference::rmse(e.pismo, t.truth, &t.planes),
            reference::rmse(e.averaged, t.truth, &t.planes),
            t.planes_noise,
            double(testing::pismo_layered_bytes(maps) + id_bytes) / 1e6,
            seconds};
}

void write_csv(const std::string& path, const std::vector<Row>& rows)
{
    std::ofstream out(path);
    out << "scene,cameras,map_size,level,maps,pismo,averaged,maximum_depth,truth_noise,pismo_planes,averaged_planes,"
           "planes_noise,megabytes,render_seconds\n";
    for (const Row& r : rows)
        out << r.scene << ',' << r.cameras << ',' << r.size << ',' << r.level << ',' << r.maps << ',' << r.pismo << ','
            << r.averaged << ',' << r.maximum_depth << ',' << r.truth_noise << ',' << r.pismo_planes << ','
            << r.averaged_planes << ',' << r.planes_noise << ',' << r.megabytes << ',' << r.render_seconds << '\n';
}

}  // namespace

int main(int argc, char** argv)
{
    Config c;
    std::string csv;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--quick") {
            c.view_width = 32, c.view_height = 24, c.strata = 8;
            c.settings = {{"frustum", 128, 1}, {"fitted", 128, 1}};
        } else if (arg == "--scenes" && i + 1 < argc) {
            c.scenes = split(argv[++i], ',');
        } else if (arg == "--settings" && i + 1 < argc) {
            c.settings = parse_settings(argv[++i]);
        } else if (arg == "--centred-grids") {
            c.shift_grids = false;
        } else if (arg == "--surface-ids") {
            c.surface_ids = true;
        } else {
            csv = arg;
        }
    }
    if (csv.empty()) {
        std::fprintf(stderr, "usage: pismo_acceptance [--quick] [--scenes A,B] [--settings fitted:1024:3,...] "
                             "[--centred-grids] [--surface-ids] OUT.csv\n");
        return 2;
    }
    std::printf("pismo_acceptance: %dx%d receivers, truth %d^2 strata (noise against %d^2), Pismo %d rays, grids %s%s\n\n",
                c.view_width, c.view_height, c.strata, 2 * c.strata, c.strata * c.strata,
                c.shift_grids ? "shifted (pismo_subtexel_shift)" : "centred on the fixation point",
                c.surface_ids ? ", surface ids" : "");
    std::printf("| scene | cameras | map | level | maps | Pismo (layered) | averaged hard shadows | Pismo (maximum depth) "
                "| truth noise | Pismo, planes | averaged, planes | truth noise, planes | maps MB | render s |\n"
                "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    std::vector<Row> rows;
    for (const std::string& name : c.scenes) {
        const reference::Scene scene = reference::builtin_scene(name);
        const SceneTruth t = truth_for(scene, c);
        for (const MapSetting& setting : c.settings)
            for (int level = 0; level <= setting.max_level; ++level) {
                const Row r = measure(scene, t, setting, level, c);
                std::printf("| %s | %s | %d | %d | %d | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.1f | %.1f |\n",
                            r.scene.c_str(), r.cameras.c_str(), r.size, r.level, r.maps, r.pismo, r.averaged,
                            r.maximum_depth, r.truth_noise, r.pismo_planes, r.averaged_planes, r.planes_noise,
                            r.megabytes, r.render_seconds);
                std::fflush(stdout);
                rows.push_back(r);
                write_csv(csv, rows);  // every row so far: a long run leaves what it measured
            }
    }
    return 0;
}
