// Where Pismo's error over every receiver comes from (docs/pismo.md, "Where
// the floor comes from"): on contact, overlap and fence at one level, the
// RMSE against the truth of Pismo and of the averaged hard shadows split by
// receiver class, and every hard shadow-map decision (receiver P, map j)
// against the exact segment from P to the map's vertex V_j, traced as the
// truth traces it (blocked below P's tangent plane, P's own surface left out
// otherwise; penumbra/reference/ground_truth.h). A wrong
// decision is acne (the map occludes, the segment is clear) or a leak (the
// reverse); each is split by what the map holds at P's pixel.
// Then each class's error split by its source (docs/pismo.md, "Where fence's
// error comes from"): the same test with a part answered by tracing the
// casters, as maps of unlimited resolution would (PismoReferenceOptions::
// exact_tests, exact_estimate), and the mean signed error (below 0: too dark).
// Float64 (tests/support/pismo_reference.h), no kernel. Figures, not checks.
//
// usage: pismo_error_classes [LEVEL [MAP_SIZE [BIAS_TEXELS [NORMALS [SCENES [SHIFTED [LIFT [OTHER [OWN]]]]]]]]]
//        (defaults 3, 384, 2, 0, contact,overlap,fence, 1, 0; fitted cameras;
//        NORMALS 1: the receiver's own surface takes part, docs/pismo.md
//        "The receiver's own surface"; SHIFTED 0: every map's grid centred on
//        the fixation point, as before LayeredMapOptions::shift_grids; LIFT
//        above 0: a normal offset of that many texels instead of the slope
//        term, PismoReferenceOptions::lift_texels, measured, not the method;
//        OTHER 0 or above: surface ids, a layer of another surface than P's
//        occludes with a bias of OTHER texels, one of P's own never (OWN 1,
//        the default) or with the slope term's bias (OWN 0); docs/pismo.md
//        "A surface id per layer", measured, not the method)
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <span>
#include <string>
#include <vector>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/tracer.h"
#include "support/pismo_estimates.h"

using namespace penumbra;
using reference::Vec3;

namespace {

constexpr const char* kClasses[] = {"ground plane", "caster, facing the light", "caster, terminator band",
                                    "caster, facing away"};
// Why a hard decision went wrong, from the layers at P's pixel (texels of depth at P).
constexpr const char* kCauses[] = {"acne: front layer within 8 texels of P", "acne: otherwise",
                                   "leak: pixel empty (silhouette, coverage)", "leak: occluder within the bias",
                                   "leak: no layer in front of P at the pixel centre", "leak: P outside the map"};

struct Tally {
    int receivers = 0;
    double pismo_sq = 0, averaged_sq = 0;
    long tests = 0;
    std::array<long, 6> wrong{};
};

Vec3 at3(const Image& image, int x, int y) { return {image.at(0, x, y), image.at(1, x, y), image.at(2, x, y)}; }
Vec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

// The receiver's class: on a plane, or on a caster by the cosine between its
// normal and the direction to the light's centre (|cos| < 0.25: the terminator).
int receiver_class(const reference::Scene& scene, const Image& planes, Vec3 p, Vec3 n, int x, int y)
{
    if (planes.at(0, x, y) > 0.5f) return 0;
    const double c = dot(n, normalize(scene.light.center - p));
    return c > 0.25 ? 1 : c < -0.25 ? 3 : 2;
}

// -1 when the hard test of `map` at p is right against `exact_blocked`, else the cause's index.
int wrong_decision(const LayeredDepthMap& map, std::span<const std::int32_t> ids, Vec3 p, Vec3 n, int surface,
                   const testing::PismoReferenceOptions& o, bool exact_blocked)
{
    const MapCamera& c = map.camera();
    const Vec3 local = p - vec(c.position);
    const double d = dot(local, vec(c.forward));
    const double u = 0.5 + dot(local, vec(c.right)) / (2 * d * c.tan_half_fov);
    const double v = 0.5 + dot(local, vec(c.down)) / (2 * d * c.tan_half_fov);
    const double fx = std::floor(u * map.width()), fy = std::floor(v * map.height());
    if (!(d > 0 && fx >= 0 && fx < map.width() && fy >= 0 && fy < map.height())) return exact_blocked ? 5 : -1;
    const double depth = length(local), texel = 2 * c.tan_half_fov * depth / map.width();
    const auto layers = map.layers(int(fx), int(fy));
    const bool occluded = testing::hard_shadow_test(map, ids, p, n, surface, o);
    if (occluded == exact_blocked) return -1;
    if (occluded) return !layers.empty() && (depth - layers.front()) / texel < 8 ? 0 : 1;
    if (layers.empty()) return 2;
    return layers.front() < depth ? 3 : 4;
}

// The error's sources: which parts of the test the maps answer.
struct Variant {
    const char* name;
    bool averaged, exact_tests, exact_estimate;
};
constexpr Variant kVariants[] = {{"Pismo", false, false, false},
                                 {"Pismo, exact tests", false, true, false},
                                 {"Pismo, exact estimate", false, false, true},
                                 {"Pismo, both exact", false, true, true},
                                 {"averaged", true, false, false},
                                 {"averaged, exact tests", true, true, false}};

// One variant's estimate at every valid receiver.
Image estimate(const reference::PismoMaps& maps, const reference::Receivers& rx, testing::PismoReferenceOptions o,
               const reference::PreparedScene& casters, const Variant& v, bool normals)
{
    o.exact_casters = &casters;
    o.exact_tests = v.exact_tests;
    o.exact_estimate = v.exact_estimate;
    const auto layered = testing::PismoReferenceMaps::layered(maps);
    Image out(rx.width(), rx.height(), 1);
    tbb::parallel_for(tbb::blocked_range<int>(0, rx.height()), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < rx.width(); ++x) {
                if (rx.mask.at(0, x, y) == 0) continue;
                const Vec3 p = at3(rx.world_position, x, y), n = normals ? at3(rx.normal, x, y) : Vec3{};
                const int surface = int(rx.surface.at(0, x, y));
                out.at(0, x, y) = float(v.averaged ? testing::averaged_hard_shadows(layered, p, o, n, surface)
                                                   : testing::pismo_visibility(layered, p, o, n, surface));
            }
    });
    return out;
}

// The casters laid out as scene_surfaces, the others there with opacity 0 (left
// out), so that a hit's primitive is its surface id (Receivers::surface).
std::vector<reference::Primitive> casters_by_surface(const reference::Scene& scene)
{
    std::vector<reference::Primitive> surfaces = reference::scene_surfaces(scene);
    const std::vector<int> kept = reference::pismo_caster_surfaces(scene);
    for (std::size_t i = 0; i < surfaces.size(); ++i)
        if (std::find(kept.begin(), kept.end(), int(i)) == kept.end())
            std::get<reference::Plane>(surfaces[i]).opacity = 0;  // only planes are left out
    return surfaces;
}

// Per class and variant: RMSE and mean signed error against the truth.
void report_sources(const reference::Scene& scene, const reference::PismoMaps& maps, const reference::Receivers& rx,
                    const Image& truth, const Image& classes, const testing::PismoReferenceOptions& o, bool normals)
{
    const reference::PreparedScene casters(casters_by_surface(scene));
    constexpr int kCount = int(std::size(kVariants));
    std::array<std::array<double, kCount>, 4> sq{}, signed_sum{};
    std::array<int, 4> count{};
    for (int k = 0; k < kCount; ++k) {
        const Image e = estimate(maps, rx, o, casters, kVariants[k], normals);
        for (int y = 0; y < rx.height(); ++y)
            for (int x = 0; x < rx.width(); ++x) {
                if (rx.mask.at(0, x, y) == 0) continue;
                const auto c = std::size_t(classes.at(0, x, y));
                const double d = e.at(0, x, y) - truth.at(0, x, y);
                sq[c][std::size_t(k)] += d * d;
                signed_sum[c][std::size_t(k)] += d;
                count[c] += k == 0;
            }
    }
    std::printf("\nthe error's sources (RMSE / mean signed error; exact: traced as by maps of unlimited resolution)\n\n"
                "| receivers |");
    for (const Variant& v : kVariants) std::printf(" %s |", v.name);
    std::printf("\n|---|---|---|---|---|---|---|\n");
    for (std::size_t c = 0; c < count.size(); ++c) {
        if (count[c] == 0) continue;
        std::printf("| %s |", kClasses[c]);
        for (std::size_t k = 0; k < std::size_t(kCount); ++k)
            std::printf(" %.4f / %+.4f |", std::sqrt(sq[c][k] / count[c]), signed_sum[c][k] / count[c]);
        std::printf("\n");
    }
    std::fflush(stdout);
}

void report(const reference::Scene& scene, int level, int size, double bias_texels, bool normals, bool shifted,
            double lift, double other, bool skip_own)
{
    const reference::Receivers rx = reference::render_receivers(scene, 64, 48);
    const Image truth = reference::ground_truth(scene, rx, {32});
    const Image planes = testing::receivers_on_planes(scene, rx, true);
    reference::LayeredMapOptions mo;
    mo.size = size;
    mo.shift_grids = shifted;
    const reference::PismoMaps maps = reference::render_pismo_maps(scene, level, mo, reference::receiver_region(rx));
    testing::PismoReferenceOptions po;
    po.rays = 1024;
    po.bias_texels = bias_texels;
    po.lift_texels = lift;
    po.surface_ids = other >= 0;
    po.other_bias_texels = other;
    po.skip_own_layers = skip_own;
    const testing::PismoEstimates e = testing::pismo_estimates(maps, rx, po, normals);
    const reference::PreparedScene prepared(scene);
    const std::vector<bool> opaque = reference::opaque_surfaces(scene);
    std::array<Tally, 4> tally{};
    Image classes(rx.width(), rx.height(), 1);
    double total_sq = 0;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            if (rx.mask.at(0, x, y) == 0) continue;
            const Vec3 p = at3(rx.world_position, x, y), n = at3(rx.normal, x, y);
            const int c = receiver_class(scene, planes, p, n, x, y);
            classes.at(0, x, y) = float(c);
            Tally& t = tally[std::size_t(c)];
            ++t.receivers;
            const double ep = e.pismo.at(0, x, y) - truth.at(0, x, y), ea = e.averaged.at(0, x, y) - truth.at(0, x, y);
            t.pismo_sq += ep * ep;
            t.averaged_sq += ea * ea;
            total_sq += ep * ep;
            const reference::ReceiverRays rays(p, n, reference::receiver_own_surface(rx, opaque, x, y));
            for (std::size_t j = 0; j < maps.maps.size(); ++j) {
                const Vec3 vertex = maps.mesh.vertices[j];
                const bool blocked = rays.transmittance(prepared, vertex - rays.origin, 1.0) < 0.5;
                ++t.tests;
                if (const int cause = wrong_decision(maps.maps[j], maps.surface_ids[j], p, normals ? n : Vec3{},
                                                     int(rx.surface.at(0, x, y)), po, blocked);
                    cause >= 0)
                    ++t.wrong[std::size_t(cause)];
            }
        }
    std::printf("\n%s, level %d (%zu maps), fitted %d^2, bias %.1f texels%s, grids %s\n\n", scene.name.c_str(), level,
                maps.maps.size(), size, bias_texels, normals ? ", with the receiver's own surface" : "",
                shifted ? "shifted" : "centred");
    if (lift > 0) std::printf("(a normal offset of %.2f texels instead of the slope term: measured, not the method)\n\n", lift);
    if (other >= 0)
        std::printf("(surface ids: other surfaces' layers biased %.2f texels, P's own %s: measured, not the method)\n\n",
                    other, skip_own ? "never occlude" : "with the slope term's bias");
    std::printf("| receivers | count | Pismo RMSE | averaged RMSE | share of Pismo's squared error |");
    for (const char* cause : kCauses) std::printf(" %s |", cause);
    std::printf("\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (std::size_t k = 0; k < tally.size(); ++k) {
        const Tally& t = tally[k];
        if (t.receivers == 0) continue;
        std::printf("| %s | %d | %.4f | %.4f | %.0f%% |", kClasses[k], t.receivers, std::sqrt(t.pismo_sq / t.receivers),
                    std::sqrt(t.averaged_sq / t.receivers), 100 * t.pismo_sq / total_sq);
        for (long w : t.wrong) std::printf(" %.2f%% |", 100.0 * double(w) / double(t.tests));
        std::printf("\n");
    }
    std::fflush(stdout);
    report_sources(scene, maps, rx, truth, classes, po, normals);
}

}  // namespace

int main(int argc, char** argv)
{
    const int level = argc > 1 ? std::atoi(argv[1]) : 3;
    const int size = argc > 2 ? std::atoi(argv[2]) : 384;
    const double bias = argc > 3 ? std::atof(argv[3]) : 2.0;
    const bool normals = argc > 4 && std::atoi(argv[4]) != 0;
    std::vector<std::string> scenes;
    std::istringstream names(argc > 5 ? argv[5] : "contact,overlap,fence");
    for (std::string name; std::getline(names, name, ',');) scenes.push_back(name);
    const bool shifted = argc <= 6 || std::atoi(argv[6]) != 0;
    const double lift = argc > 7 ? std::atof(argv[7]) : 0.0;
    const double other = argc > 8 ? std::atof(argv[8]) : -1.0;
    const bool skip_own = argc <= 9 || std::atoi(argv[9]) != 0;
    std::printf("pismo_error_classes: 64x48 receivers, truth 32^2 strata, Pismo 1024 rays; hard decisions: "
                "%% of (receiver, map) pairs of the class\n");
    for (const std::string& name : scenes) report(reference::builtin_scene(name), level, size, bias, normals, shifted, lift, other, skip_own);
    return 0;
}
