// The SDF kernels' view of a reference scene: its primitives as the
// library's SDF types, grids baked from the analytic distance, and k from the
// light's size (docs/sdf.md).
#include "penumbra/reference/sdf_scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <variant>

#include "penumbra/error.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

// Distance from the light's centre to the scene's reference receiver, which
// lies on the light's axis (reference_depths), so its depth is its distance.
double reference_distance(const Scene& scene)
{
    const LightProjection projection(scene);
    return projection.depth_of(reference_depths(scene).z_receiver);
}

// A light's width for the half-angle: the side of a square, the diameter of a
// disk, the geometric mean of a rectangle's sides.
double light_width(const AreaLight& light) { return std::sqrt(light.width * light.height); }

// The light's extent across a shadow edge, averaged over the edge's
// directions: its mean breadth (Cauchy: perimeter / pi for a convex shape),
// 2 (w + h) / pi for a rectangle (4 W / pi for a square), the diameter for a
// disk. The inner-penumbra estimate spans it (docs/sdf.md).
double mean_breadth(const AreaLight& light)
{
    return light.shape == LightShape::Disk ? light_width(light) : 2.0 * (light.width + light.height) / std::numbers::pi;
}

}  // namespace

SdfPrimitive to_sdf(const Primitive& primitive)
{
    struct Convert {
        SdfPrimitive operator()(const Plane& p) const { return SdfPlane{to_sdf(p.point), to_sdf(p.normal)}; }
        SdfPrimitive operator()(const Sphere& s) const { return SdfSphere{to_sdf(s.center), s.radius}; }
        SdfPrimitive operator()(const Box& box) const
        {
            const OrientedBox b = OrientedBox::from(box);
            return SdfBox{to_sdf(b.center), to_sdf(b.half_size), to_sdf(b.rotation.x), to_sdf(b.rotation.y),
                          to_sdf(b.rotation.z)};
        }
        SdfPrimitive operator()(const Capsule& c) const { return SdfCapsule{to_sdf(c.a), to_sdf(c.b), c.radius}; }
    };
    return std::visit(Convert{}, primitive);
}

AnalyticScene analytic_scene(const std::vector<Primitive>& primitives)
{
    std::vector<SdfPrimitive> converted;
    converted.reserve(primitives.size());
    for (const Primitive& p : primitives) converted.push_back(to_sdf(p));
    return AnalyticScene(converted);
}

GridBox distance_grid_box(const Scene& scene, double margin)
{
    validate_scene(scene, "distance_grid_box");
    require(std::isfinite(margin) && margin >= 0.0, "distance_grid_box",
            "margin must be finite and >= 0 (got " + std::to_string(margin) + ")");
    Bounds bounds;
    for (const Primitive& primitive : scene.primitives) {
        if (const auto* s = std::get_if<Sphere>(&primitive)) bounds.grow(bounds_of(*s));
        if (const auto* b = std::get_if<Box>(&primitive))
            bounds.grow(bounds_of(OrientedBox::from(*b)));
        if (const auto* c = std::get_if<Capsule>(&primitive)) bounds.grow(bounds_of(*c));
    }
    if (!(bounds.lo.x <= bounds.hi.x)) {  // planes only: a point on the light's axis
        const Vec3 at = scene.light.center + normalize(scene.light.normal) * reference_distance(scene);
        bounds = {at, at};
    }
    const Vec3 grow{margin, margin, margin};
    return {bounds.lo - grow, bounds.hi + grow};
}

GridBox distance_grid_box(const Scene& scene)
{
    validate_scene(scene, "distance_grid_box");
    return distance_grid_box(scene, 0.02 * reference_distance(scene));
}

DistanceGrid bake_distance_grid(const Scene& scene, const GridBox& box, double voxel_size)
{
    const std::string op = "bake_distance_grid";
    validate_scene(scene, op);
    require(std::isfinite(voxel_size) && voxel_size > 0.0, op,
            "voxel size must be finite and > 0 (got " + std::to_string(voxel_size) + ")");
    const Vec3 extent = box.hi - box.lo;
    require(std::isfinite(extent.x) && std::isfinite(extent.y) && std::isfinite(extent.z) && extent.x >= 0 &&
                extent.y >= 0 && extent.z >= 0,
            op, "the box must be finite with lo <= hi on every axis");
    auto nodes = [&](double side) {
        const double n = std::ceil(side / voxel_size - 1e-9) + 1.0;
        require(n <= 2147483647.0, op, "the grid would need more than 2^31 - 1 nodes; use a larger voxel size");
        return std::max(2, int(n));
    };
    DistanceGrid grid(nodes(extent.x), nodes(extent.y), nodes(extent.z), to_sdf(box.lo), voxel_size);
    const PreparedScene prepared(scene.primitives);
    const Vec3 origin = from_sdf(grid.origin());
    const double voxel = grid.voxel_size();  // as stored (float), so nodes sit where the kernel samples
    tbb::parallel_for(tbb::blocked_range<int>(0, grid.nz()), [&](const tbb::blocked_range<int>& slices) {
        for (int k = slices.begin(); k < slices.end(); ++k)
            for (int j = 0; j < grid.ny(); ++j)
                for (int i = 0; i < grid.nx(); ++i) {
                    const Vec3 p = origin + Vec3{double(i), double(j), double(k)} * voxel;
                    grid.at(i, j, k) = float(prepared.signed_distance(p));
                }
    });
    return grid;
}

DistanceGrid bake_distance_grid(const Scene& scene, std::size_t max_nodes)
{
    const std::string op = "bake_distance_grid";
    validate_scene(scene, op);
    require(max_nodes >= 8, op, "max_nodes must be at least 8 (2 x 2 x 2)");
    const GridBox box = distance_grid_box(scene);
    const Vec3 e = box.hi - box.lo;
    auto nodes = [&](double voxel) {
        auto axis = [&](double side) { return std::max(2.0, std::ceil(side / voxel - 1e-9) + 1.0); };
        return axis(e.x) * axis(e.y) * axis(e.z);
    };
    // From the volume's share per node, grown until the +1 node per axis fits.
    double voxel = std::cbrt(std::max(e.x * e.y * e.z, 1e-30) / double(max_nodes));
    voxel = std::max(voxel, std::max(e.x, std::max(e.y, e.z)) * 1e-6);
    while (nodes(voxel) > double(max_nodes)) voxel *= 1.01;
    return bake_distance_grid(scene, box, voxel);
}

double sdf_hardness(const Scene& scene, double fit)
{
    validate_scene(scene, "sdf_hardness");
    return penumbra::sdf_hardness(light_width(scene.light), reference_distance(scene), fit);
}

SdfOptions sdf_options_for(const Scene& scene, SdfEstimate estimate)
{
    validate_scene(scene, "sdf_options_for");
    const double distance = reference_distance(scene);
    SdfOptions o;
    o.light = SdfLight::at(to_sdf(scene.light.center));
    // Inner: k relative to the light's width W, 1 at the mean breadth (pi / 4 for a square).
    o.k = float(estimate == SdfEstimate::InnerPenumbra
                    ? kSdfInnerHardnessFit * light_width(scene.light) / mean_breadth(scene.light)
                    : kSdfHardnessFit);
    o.light_width = float(light_width(scene.light));
    o.estimate = estimate;
    o.hit_epsilon = float(1e-5 * distance);
    o.normal_offset = 4.0f * o.hit_epsilon;
    o.t_min = 4.0f * o.hit_epsilon;
    o.max_steps = 256;
    return o;
}

}  // namespace penumbra::reference
