// The SDF kernels' view of a scene: primitives packed into records
// (kernels/params.h, SdfParams), grids baked from the analytic distance, and
// k from the light's size (docs/sdf.md).
#include "penumbra/sdf_scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

#include "kernels/params.h"
#include "penumbra/error.h"
#include "penumbra/reference_light_space.h"
#include "penumbra/reference_tracer.h"

namespace penumbra {
namespace {

using reference::Vec3;

void push(std::vector<float>& r, Vec3 v)
{
    r.push_back(float(v.x));
    r.push_back(float(v.y));
    r.push_back(float(v.z));
}

void require_positive(double v, int i, const char* field)
{
    require(std::isfinite(v) && v > 0.0, "AnalyticScene",
            "primitives[" + std::to_string(i) + "]." + field + ": must be finite and > 0 (got " + std::to_string(v) +
                ")");
}

void require_finite(Vec3 v, int i, const char* field)
{
    require(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z), "AnalyticScene",
            "primitives[" + std::to_string(i) + "]." + field + ": must be finite");
}

// Each kind's record, as kernels/sdf.h reads it.
struct Packer {
    std::vector<float> kind[4];
    int index = 0;

    void operator()(const reference::Plane& plane)
    {
        require_finite(plane.point, index, "point");
        require_finite(plane.normal, index, "normal");
        require_positive(reference::length(plane.normal), index, "normal (its length)");
        const Vec3 n = reference::normalize(plane.normal);
        push(kind[0], n);
        kind[0].push_back(float(reference::dot(plane.point, n)));
    }
    void operator()(const reference::Sphere& sphere)
    {
        require_finite(sphere.center, index, "center");
        require_positive(sphere.radius, index, "radius");
        push(kind[1], sphere.center);
        kind[1].push_back(float(sphere.radius));
    }
    void operator()(const reference::Box& box)
    {
        require_finite(box.center, index, "center");
        require_finite(box.rotation_degrees, index, "rotation_degrees");
        for (double side : {box.size.x, box.size.y, box.size.z}) require_positive(side, index, "size");
        const reference::OrientedBox b = reference::OrientedBox::from(box);
        push(kind[2], b.center);
        push(kind[2], b.half_size);
        push(kind[2], b.rotation.x);
        push(kind[2], b.rotation.y);
        push(kind[2], b.rotation.z);
        kind[2].push_back(0.0f);
    }
    void operator()(const reference::Capsule& capsule)
    {
        require_finite(capsule.a, index, "a");
        require_finite(capsule.b, index, "b");
        require_positive(capsule.radius, index, "radius");
        const Vec3 ba = capsule.b - capsule.a;
        const double length2 = reference::dot(ba, ba);
        push(kind[3], capsule.a);
        push(kind[3], ba);
        kind[3].push_back(length2 > 0.0 ? float(1.0 / length2) : 0.0f);
        kind[3].push_back(float(capsule.radius));
    }
};

constexpr int kRecordFloats[4] = {PN_SDF_PLANE_FLOATS, PN_SDF_SPHERE_FLOATS, PN_SDF_BOX_FLOATS, PN_SDF_CAPSULE_FLOATS};

// Distance from the light's centre to the scene's reference receiver, which
// lies on the light's axis (reference_depths), so its depth is its distance.
double reference_distance(const reference::Scene& scene)
{
    const reference::LightProjection projection(scene);
    return projection.depth_of(reference::reference_depths(scene).z_receiver);
}

// A light's width for the half-angle: the side of a square, the diameter of a
// disk, the geometric mean of a rectangle's sides.
double light_width(const reference::AreaLight& light) { return std::sqrt(light.width * light.height); }

}  // namespace

AnalyticScene::AnalyticScene(const std::vector<reference::Primitive>& primitives)
{
    Packer packer;
    for (const reference::Primitive& primitive : primitives) {
        std::visit(packer, primitive);
        ++packer.index;
    }
    for (int k = 0; k < 4; ++k) {
        counts_[k] = int(packer.kind[k].size()) / kRecordFloats[k];
        records_.insert(records_.end(), packer.kind[k].begin(), packer.kind[k].end());
    }
}

GridBox distance_grid_box(const reference::Scene& scene, double margin)
{
    reference::validate_scene(scene, "distance_grid_box");
    require(std::isfinite(margin) && margin >= 0.0, "distance_grid_box",
            "margin must be finite and >= 0 (got " + std::to_string(margin) + ")");
    reference::Bounds bounds;
    for (const reference::Primitive& primitive : scene.primitives) {
        if (const auto* s = std::get_if<reference::Sphere>(&primitive)) bounds.grow(reference::bounds_of(*s));
        if (const auto* b = std::get_if<reference::Box>(&primitive))
            bounds.grow(reference::bounds_of(reference::OrientedBox::from(*b)));
        if (const auto* c = std::get_if<reference::Capsule>(&primitive)) bounds.grow(reference::bounds_of(*c));
    }
    if (!(bounds.lo.x <= bounds.hi.x)) {  // planes only: a point on the light's axis
        const Vec3 at = scene.light.center + reference::normalize(scene.light.normal) * reference_distance(scene);
        bounds = {at, at};
    }
    const Vec3 grow{margin, margin, margin};
    return {bounds.lo - grow, bounds.hi + grow};
}

GridBox distance_grid_box(const reference::Scene& scene)
{
    reference::validate_scene(scene, "distance_grid_box");
    return distance_grid_box(scene, 0.02 * reference_distance(scene));
}

DistanceGrid bake_distance_grid(const reference::Scene& scene, const GridBox& box, double voxel_size)
{
    const std::string op = "bake_distance_grid";
    reference::validate_scene(scene, op);
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
    DistanceGrid grid(nodes(extent.x), nodes(extent.y), nodes(extent.z), box.lo, voxel_size);
    const reference::PreparedScene prepared(scene.primitives);
    const Vec3 origin = grid.origin();
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

DistanceGrid bake_distance_grid(const reference::Scene& scene, std::size_t max_nodes)
{
    const std::string op = "bake_distance_grid";
    reference::validate_scene(scene, op);
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

double sdf_hardness(double light_width, double distance, double fit)
{
    const std::string op = "sdf_hardness";
    require(std::isfinite(light_width) && light_width > 0.0, op, "the light's width must be > 0");
    require(std::isfinite(distance) && distance > 0.0, op, "the distance to the light must be > 0");
    require(std::isfinite(fit) && fit > 0.0, op, "fit must be > 0");
    return fit * 2.0 * distance / light_width;
}

double sdf_hardness(const reference::Scene& scene, double fit)
{
    reference::validate_scene(scene, "sdf_hardness");
    return sdf_hardness(light_width(scene.light), reference_distance(scene), fit);
}

SdfOptions sdf_options_for(const reference::Scene& scene, SdfEstimate estimate)
{
    reference::validate_scene(scene, "sdf_options_for");
    const double distance = reference_distance(scene);
    SdfOptions o;
    o.light = SdfLight::at(scene.light.center);
    o.k = float(kSdfHardnessFit);
    o.light_width = float(light_width(scene.light));
    o.estimate = estimate;
    o.hit_epsilon = float(1e-5 * distance);
    o.normal_offset = 4.0f * o.hit_epsilon;
    o.t_min = 4.0f * o.hit_epsilon;
    o.max_steps = 256;
    return o;
}

}  // namespace penumbra
