// Bounds of the solids and the construction of PreparedScene's hierarchy.
#include <algorithm>
#include <cmath>

#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

Vec3 min3(Vec3 a, Vec3 b) { return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)}; }
Vec3 max3(Vec3 a, Vec3 b) { return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)}; }

double component(Vec3 v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

}  // namespace

void Bounds::grow(const Bounds& other)
{
    lo = min3(lo, other.lo);
    hi = max3(hi, other.hi);
}

Bounds bounds_of(const Sphere& sphere)
{
    const Vec3 r{sphere.radius, sphere.radius, sphere.radius};
    return {sphere.center - r, sphere.center + r};
}

Bounds bounds_of(const OrientedBox& box)
{
    // The half-extent along world axis k is sum_i |axis_i[k]| h_i: the largest
    // reach of the corners c + sum_i +-h_i axis_i.
    const Rotation& r = box.rotation;
    const Vec3 h = abs(r.x) * box.half_size.x + abs(r.y) * box.half_size.y + abs(r.z) * box.half_size.z;
    return {box.center - h, box.center + h};
}

Bounds bounds_of(const Capsule& capsule)
{
    const Vec3 r{capsule.radius, capsule.radius, capsule.radius};
    return {min3(capsule.a, capsule.b) - r, max3(capsule.a, capsule.b) + r};
}

int PreparedScene::build(int begin, int end)
{
    const int node_index = int(nodes_.size());
    nodes_.emplace_back();
    Bounds bounds, centres;
    for (int i = begin; i < end; ++i) {
        bounds.grow(solids_[i].bounds);
        const Vec3 c = solids_[i].bounds.centre();
        centres.grow({c, c});
    }
    nodes_[node_index].bounds = bounds;
    if (end - begin <= kLeafSize) {
        nodes_[node_index].first = begin;
        nodes_[node_index].count = end - begin;
        return node_index;
    }
    const Vec3 spread = centres.hi - centres.lo;
    const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : spread.y >= spread.z ? 1 : 2;
    // Median split: balanced depth whatever the layout; the scenes are small
    // enough that a surface-area heuristic would not pay for its code.
    const int middle = (begin + end) / 2;
    std::nth_element(solids_.begin() + begin, solids_.begin() + middle, solids_.begin() + end,
                     [axis](const Solid& a, const Solid& b) {
                         return component(a.bounds.centre(), axis) < component(b.bounds.centre(), axis);
                     });
    build(begin, middle);
    const int right = build(middle, end);
    nodes_[node_index].first = right;
    nodes_[node_index].axis = axis;
    return node_index;
}

}  // namespace penumbra::reference
