// AnalyticScene: the SDF primitives checked and packed into the records the
// analytic kernel reads (kernels/params.h, SdfParams; kernels/sdf.h), grouped
// by kind. Keep the record layouts in step with kernels/params.h.
#include <cmath>
#include <string>
#include <variant>

#include "kernels/params.h"
#include "penumbra/error.h"
#include "penumbra/sdf.h"

namespace penumbra {
namespace {

const char* const kAnalyticSceneOp = "AnalyticScene";

double dot(SdfVec3 a, SdfVec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
SdfVec3 minus(SdfVec3 a, SdfVec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

void push(std::vector<float>& r, SdfVec3 v)
{
    r.push_back(float(v.x));
    r.push_back(float(v.y));
    r.push_back(float(v.z));
}

std::string field_of(int i, const char* field) { return "primitives[" + std::to_string(i) + "]." + field; }

void require_positive(double v, int i, const char* field)
{
    require(std::isfinite(v) && v > 0.0, kAnalyticSceneOp,
            field_of(i, field) + ": must be finite and > 0 (got " + std::to_string(v) + ")");
}

void require_finite(SdfVec3 v, int i, const char* field)
{
    require(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z), kAnalyticSceneOp, field_of(i, field) + ": must be finite");
}

// The kernel turns a point into the box's frame by three dot products with
// the axes (the inverse of an orthonormal rotation is its transpose), so
// axes that are not orthonormal would give wrong distances, not an error.
// 1e-5 admits axes taken from a float matrix (rounding ~1e-7).
void require_orthonormal(const SdfBox& box, int i)
{
    const SdfVec3 axes[3] = {box.axis_x, box.axis_y, box.axis_z};
    const char* names[3] = {"axis_x", "axis_y", "axis_z"};
    for (int a = 0; a < 3; ++a) require_finite(axes[a], i, names[a]);
    constexpr double kTolerance = 1e-5;
    for (int a = 0; a < 3; ++a)
        for (int b = a; b < 3; ++b)
            require(std::fabs(dot(axes[a], axes[b]) - (a == b ? 1.0 : 0.0)) <= kTolerance, kAnalyticSceneOp,
                    field_of(i, "axis_x, axis_y, axis_z") +
                        ": must be orthonormal (unit length, pairwise perpendicular, within 1e-5)");
}

// Each kind's record, as kernels/sdf.h reads it.
struct Packer {
    std::vector<float> kind[4];
    int index = 0;

    void operator()(const SdfPlane& plane)
    {
        require_finite(plane.point, index, "point");
        require_finite(plane.normal, index, "normal");
        const double length = std::sqrt(dot(plane.normal, plane.normal));
        require_positive(length, index, "normal (its length)");
        const SdfVec3 n{plane.normal.x / length, plane.normal.y / length, plane.normal.z / length};
        push(kind[0], n);
        kind[0].push_back(float(dot(plane.point, n)));
    }
    void operator()(const SdfSphere& sphere)
    {
        require_finite(sphere.center, index, "center");
        require_positive(sphere.radius, index, "radius");
        push(kind[1], sphere.center);
        kind[1].push_back(float(sphere.radius));
    }
    void operator()(const SdfBox& box)
    {
        require_finite(box.center, index, "center");
        for (double half : {box.half_size.x, box.half_size.y, box.half_size.z})
            require_positive(half, index, "half_size");
        require_orthonormal(box, index);
        push(kind[2], box.center);
        push(kind[2], box.half_size);
        push(kind[2], box.axis_x);
        push(kind[2], box.axis_y);
        push(kind[2], box.axis_z);
        kind[2].push_back(0.0f);
    }
    void operator()(const SdfCapsule& capsule)
    {
        require_finite(capsule.a, index, "a");
        require_finite(capsule.b, index, "b");
        require_positive(capsule.radius, index, "radius");
        const SdfVec3 ba = minus(capsule.b, capsule.a);
        const double length2 = dot(ba, ba);
        push(kind[3], capsule.a);
        push(kind[3], ba);
        kind[3].push_back(length2 > 0.0 ? float(1.0 / length2) : 0.0f);
        kind[3].push_back(float(capsule.radius));
    }
};

constexpr int kRecordFloats[4] = {PN_SDF_PLANE_FLOATS, PN_SDF_SPHERE_FLOATS, PN_SDF_BOX_FLOATS, PN_SDF_CAPSULE_FLOATS};

}  // namespace

AnalyticScene::AnalyticScene(const std::vector<SdfPrimitive>& primitives)
{
    Packer packer;
    for (const SdfPrimitive& primitive : primitives) {
        std::visit(packer, primitive);
        ++packer.index;
    }
    for (int k = 0; k < 4; ++k) {
        counts_[k] = int(packer.kind[k].size()) / kRecordFloats[k];
        records_.insert(records_.end(), packer.kind[k].begin(), packer.kind[k].end());
    }
}

}  // namespace penumbra
