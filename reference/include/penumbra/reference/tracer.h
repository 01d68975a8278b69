// Ray casting and signed distance against the analytic primitives.
//
// Each primitive is a solid (scene.h). An intersection is the first
// parameter t in (t_min, t_max) at which a ray crosses the primitive's
// surface, entering or leaving: a ray that starts inside a solid hits it on
// the way out, so a shadow ray from inside an occluder is occluded, as it
// should be. Everything is in double precision.
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include "penumbra/reference/scene.h"

namespace penumbra::reference {

struct Hit {
    double t = 0;
    Vec3 normal;        // unit, outward from the solid
    int primitive = -1;  // index into the scene's primitive list
};

// A box with its rotation evaluated once (Box keeps the Euler angles it was
// written with, so that a JSON round trip is exact).
struct OrientedBox {
    Vec3 center, half_size;
    Rotation rotation;

    static OrientedBox from(const Box& box);
};

// One primitive each. A plane's normal must be of unit length here.
std::optional<Hit> intersect(const Ray& ray, const Plane& plane, double t_min, double t_max);
std::optional<Hit> intersect(const Ray& ray, const Sphere& sphere, double t_min, double t_max);
std::optional<Hit> intersect(const Ray& ray, const OrientedBox& box, double t_min, double t_max);
std::optional<Hit> intersect(const Ray& ray, const Capsule& capsule, double t_min, double t_max);

// Exact signed distances (negative inside), the closed forms of Quilez's
// catalogue (iquilezles.org/articles/distfunctions), derived in reference/src/signed_distance.cpp.
double signed_distance(Vec3 p, const Plane& plane);
double signed_distance(Vec3 p, const Sphere& sphere);
double signed_distance(Vec3 p, const OrientedBox& box);
double signed_distance(Vec3 p, const Capsule& capsule);

// An axis-aligned box in world space.
struct Bounds {
    Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};

    void grow(const Bounds& other);
    Vec3 centre() const { return (lo + hi) * 0.5; }
};
Bounds bounds_of(const Sphere& sphere);
Bounds bounds_of(const OrientedBox& box);
Bounds bounds_of(const Capsule& capsule);

// A scene's primitives laid out for casting many rays: planes normalised and
// tested one by one (they are unbounded, and scenes hold one or two), the
// bounded solids in a bounding-volume hierarchy (median split on the longest
// centroid axis, up to kLeafSize solids a leaf). The fence's 44 primitives
// and the large scene's 81 would otherwise cost a test each per shadow ray.
class PreparedScene {
public:
    explicit PreparedScene(const std::vector<Primitive>& primitives);

    std::size_t size() const noexcept { return count_; }
    std::optional<Hit> closest_hit(const Ray& ray, double t_min, double t_max) const;
    // True when any surface crosses the ray in (t_min, t_max).
    bool occluded(const Ray& ray, double t_min, double t_max) const;
    // The scene's signed distance: the minimum over primitives. Exact outside
    // every solid; inside overlapping solids it is a bound (|d| is at most the
    // distance to the union's surface), the usual property of a min of SDFs.
    // +infinity for a scene without primitives.
    double signed_distance(Vec3 p) const;

    static constexpr int kLeafSize = 2;

private:
    using Shape = std::variant<Sphere, OrientedBox, Capsule>;
    struct Solid {
        Shape shape;
        Bounds bounds;
        int index;  // in the scene's primitive list
    };
    // Leaves hold solids_[first, first + count); an inner node (count == 0)
    // has its left child next to it and its right child at `first`.
    struct Node {
        Bounds bounds;
        int first = 0, count = 0;
        int axis = 0;  // split axis, to visit the nearer child first
    };
    int build(int begin, int end);
    template <class Visit>
    void traverse(const Ray& ray, double t_min, const double& t_max, Visit&& visit) const;

    std::vector<Plane> planes_;
    std::vector<int> plane_indices_;
    std::vector<Solid> solids_;
    std::vector<Node> nodes_;
    std::size_t count_ = 0;
};

// Convenience: the analytic signed distance of a scene at a world point.
// Prepares the scene on every call; hold a PreparedScene for many points.
double signed_distance(const Scene& scene, Vec3 p);

}  // namespace penumbra::reference
