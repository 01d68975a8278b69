// Host operations sdf_shadows(): validate, fill SdfParams, dispatch; the
// lane-utilisation measurement of a march; k from a light's size.
#include "penumbra/sdf.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "host/backend/backend.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

const std::string kSdfOp = "sdf_shadows";

std::string str(double v) { return std::to_string(v); }

double length(SdfVec3 v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

void check_options(const SdfOptions& o)
{
    require(std::isfinite(o.k) && o.k > 0.0f, kSdfOp, "k must be a finite value > 0 (got " + str(o.k) + ")");
    require(std::isfinite(o.t_min) && o.t_min >= 0.0f, kSdfOp,
            "t_min must be a finite value >= 0 (got " + str(o.t_min) + ")");
    require(std::isfinite(o.t_max) && o.t_max > o.t_min, kSdfOp,
            "t_max must be finite and > t_min (got t_max " + str(o.t_max) + ", t_min " + str(o.t_min) + ")");
    require(o.max_steps >= 1 && o.max_steps <= 1000000, kSdfOp,
            "max_steps must be in [1, 1000000] (got " + std::to_string(o.max_steps) + ")");
    require(std::isfinite(o.hit_epsilon) && o.hit_epsilon > 0.0f, kSdfOp,
            "hit_epsilon must be a finite value > 0 (got " + str(o.hit_epsilon) + ")");
    require(std::isfinite(o.normal_offset) && o.normal_offset >= 0.0f, kSdfOp,
            "normal_offset must be a finite value >= 0 (got " + str(o.normal_offset) + ")");
    require(std::isfinite(o.light_width) && o.light_width >= 0.0f, kSdfOp,
            "light_width must be a finite value >= 0 (got " + str(o.light_width) + ")");
    require(o.light_width == 0.0f || !o.light.directional, kSdfOp,
            "light_width applies to a light at a point (SdfLight::at); give a directional light an absolute k");
    const SdfVec3 v = o.light.vector;
    const bool finite = std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    require(finite, kSdfOp,
            std::string("the light's ") + (o.light.directional ? "direction" : "centre") + " is not finite");
    if (o.light.directional) require(length(v) > 0.0, kSdfOp, "the light's direction is zero");
}

void check_receivers(const Image& positions, const Image* normals, const SdfOptions& o)
{
    require(!positions.empty(), kSdfOp, "the positions image is empty (0 pixels)");
    require(positions.channels() == 3, kSdfOp,
            "positions must have 3 channels (x, y, z), got " + std::to_string(positions.channels()));
    if (o.normal_offset > 0.0f) require(normals != nullptr, kSdfOp, "normal_offset > 0 needs the receivers' normals");
    if (!normals) return;
    require(normals->channels() == 3 && normals->width() == positions.width() &&
                normals->height() == positions.height(),
            kSdfOp, "normals must have 3 channels and the positions' size (" + std::to_string(positions.width()) + "x" +
                     std::to_string(positions.height()) + ")");
}

void check_output(const Image& positions, const Image& out)
{
    require((out.channels() == 1 || out.channels() == 2) && out.width() == positions.width() &&
                out.height() == positions.height(),
            kSdfOp,
            "the output must have 1 or 2 channels and the receivers' size (" + std::to_string(positions.width()) + "x" +
                std::to_string(positions.height()) + ")");
}

void check_grid(const DistanceGrid& grid)
{
    require(!grid.empty(), kSdfOp, "the distance grid is empty; construct it with its size, origin and voxel size");
    const float* d = grid.data();
    for (std::size_t i = 0; i < grid.size(); ++i) {
        if (std::isfinite(d[i])) continue;
        const std::size_t row = std::size_t(grid.nx()) * grid.ny();
        throw Error(ErrorCategory::InvalidData, kSdfOp,
                    "the distance grid's node (" + std::to_string(i % grid.nx()) + ", " +
                        std::to_string(i / grid.nx() % grid.ny()) + ", " + std::to_string(i / row) + ") is " +
                        std::to_string(d[i]) + "; distances must be finite");
    }
}

// Everything but the source's fields and the normals (see run()).
SdfParams base_params(const Image& positions, const Image& out, const SdfOptions& o)
{
    SdfParams p{};
    p.receivers = detail::dims_of(positions);
    p.out = detail::dims_of(out);
    p.max_steps = o.max_steps;
    p.estimate = o.estimate == SdfEstimate::Improved        ? PN_SDF_IMPROVED
                 : o.estimate == SdfEstimate::InnerPenumbra ? PN_SDF_INNER
                                                            : PN_SDF_CLASSIC;
    p.write_steps = out.channels() == 2;
    SdfVec3 light = o.light.vector;
    if (o.light.directional) {
        const double n = length(light);
        light = {light.x / n, light.y / n, light.z / n};
    }
    p.light_is_direction = o.light.directional;
    p.light_x = float(light.x);
    p.light_y = float(light.y);
    p.light_z = float(light.z);
    p.k = o.k;
    p.k_per_distance = o.light_width > 0.0f ? 2.0f * o.k / o.light_width : 0.0f;
    p.t_min = o.t_min;
    p.t_max = o.t_max;
    p.hit_epsilon = o.hit_epsilon;
    p.normal_offset = o.normal_offset;
    return p;
}

// Reports the first non-finite position or normal once a kernel flagged a row.
void report_bad_receivers(const std::vector<int>& bad_rows, const Image& positions, const Image* normals)
{
    if (std::find(bad_rows.begin(), bad_rows.end(), 1) == bad_rows.end()) return;
    require_finite(positions, kSdfOp, "the receivers' positions");
    if (normals) require_finite(*normals, kSdfOp, "the receivers' normals");
}

template <class Launch>
void run(const Image& positions, const Image* normals, const SdfOptions& o, Image& out, SdfParams p, Launch&& launch)
{
    std::vector<int> bad_rows(std::size_t(positions.height()), 0);
    // The kernel reads the normals only when it offsets along them.
    const Image& n = normals && o.normal_offset > 0.0f ? *normals : positions;
    p.normals = detail::dims_of(n);
    launch(n, p, bad_rows.data());
    report_bad_receivers(bad_rows, positions, o.normal_offset > 0.0f ? normals : nullptr);
}

}  // namespace

Image sdf_shadows(Context& context, const DistanceGrid& grid, const Image& positions, const Image* normals,
                  const SdfOptions& options)
{
    Image out(positions.width(), positions.height(), 1);
    sdf_shadows(context, grid, positions, normals, options, out);
    return out;
}

Image sdf_shadows(Context& context, const AnalyticScene& scene, const Image& positions, const Image* normals,
                  const SdfOptions& options)
{
    Image out(positions.width(), positions.height(), 1);
    sdf_shadows(context, scene, positions, normals, options, out);
    return out;
}

void sdf_shadows(Context& context, const DistanceGrid& grid, const Image& positions, const Image* normals,
                 const SdfOptions& options, Image& out)
{
    check_options(options);
    check_receivers(positions, normals, options);
    check_output(positions, out);
    check_grid(grid);
    SdfParams p = base_params(positions, out, options);
    p.grid_nx = grid.nx();
    p.grid_ny = grid.ny();
    p.grid_nz = grid.nz();
    p.grid_x = float(grid.origin().x);
    p.grid_y = float(grid.origin().y);
    p.grid_z = float(grid.origin().z);
    p.voxel = float(grid.voxel_size());
    p.inv_voxel = 1.0f / p.voxel;
    run(positions, normals, options, out, p, [&](const Image& n, const SdfParams& params, int* bad_rows) {
        context.impl().sdf_grid(grid.data(), grid.size(), positions, n, params, out, bad_rows);
    });
}

void sdf_shadows(Context& context, const AnalyticScene& scene, const Image& positions, const Image* normals,
                 const SdfOptions& options, Image& out)
{
    check_options(options);
    check_receivers(positions, normals, options);
    check_output(positions, out);
    SdfParams p = base_params(positions, out, options);
    p.planes = scene.planes();
    p.spheres = scene.spheres();
    p.boxes = scene.boxes();
    p.capsules = scene.capsules();
    run(positions, normals, options, out, p, [&](const Image& n, const SdfParams& params, int* bad_rows) {
        context.impl().sdf_analytic(scene.records().data(), scene.records().size(), positions, n, params, out,
                                    bad_rows);
    });
}

LaneUtilisation lane_utilisation(const Image& steps, int channel, int tile_width, int tile_height)
{
    const std::string op = "lane_utilisation";
    require(channel >= 0 && channel < steps.channels(), op, "channel " + std::to_string(channel) + " does not exist");
    require(tile_width >= 1 && tile_height >= 1, op, "tiles must be at least 1x1");
    LaneUtilisation u;
    const double lanes = double(tile_width) * tile_height;
    for (int ty = 0; ty < steps.height(); ty += tile_height)
        for (int tx = 0; tx < steps.width(); tx += tile_width) {
            double most = 0.0;
            for (int y = ty; y < std::min(ty + tile_height, steps.height()); ++y)
                for (int x = tx; x < std::min(tx + tile_width, steps.width()); ++x) {
                    const double s = steps.at(channel, x, y);
                    u.active += s;
                    most = std::max(most, s);
                }
            u.total += lanes * most;
        }
    return u;
}

double sdf_hardness(double light_width, double distance, double fit)
{
    const std::string op = "sdf_hardness";
    require(std::isfinite(light_width) && light_width > 0.0, op, "the light's width must be > 0");
    require(std::isfinite(distance) && distance > 0.0, op, "the distance to the light must be > 0");
    require(std::isfinite(fit) && fit > 0.0, op, "fit must be > 0");
    return fit * 2.0 * distance / light_width;
}

}  // namespace penumbra
