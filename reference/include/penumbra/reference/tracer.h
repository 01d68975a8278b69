// Ray casting, transmittance and signed distance against the analytic
// primitives and media.
//
// Each primitive is a solid (scene.h). An intersection is the first
// parameter t in (t_min, t_max) at which a ray crosses the primitive's
// surface, entering or leaving: a ray that starts inside a solid hits it on
// the way out, so a shadow ray from inside an occluder is occluded, as it
// should be. Everything is in double precision.
//
// Ray parameters are in units of |direction| (Ray's contract); extinction is
// per unit of world length, so an optical depth is the integral of k |d| dt.
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>
#include <variant>
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

// The interval of t in which the whole line o + t d lies inside the solid
// (entry <= exit), if the line meets it.
struct Chord {
    double entry = 0, exit = 0;
};
std::optional<Chord> chord(const Ray& ray, const Sphere& sphere);
std::optional<Chord> chord(const Ray& ray, const OrientedBox& box);

// A medium with its box's rotation evaluated once.
struct PreparedMedium {
    std::variant<Sphere, OrientedBox> region;
    Vec3 center;
    double extinction = 0;
    Vec3 gradient;

    static PreparedMedium from(const Medium& medium);
    // k at a point: the linear function inside the region, 0 outside.
    double extinction_at(Vec3 p) const;
    // The linear function itself, for a point known to lie in the region
    // (on its boundary, say, where a containment test could round either way).
    double extinction_within(Vec3 p) const;
    // The integral of k ds over (t0, t1) and the region, in closed form:
    // the clipped chord's world length times k at its midpoint.
    double optical_depth(const Ray& ray, double t0, double t1) const;
    std::optional<Chord> chord(const Ray& ray) const;
};

// One event along a ray, for building a transmittance function of depth
// (deep shadow maps, Lokovic and Veach 2000): a surface crossing, where the
// transmittance steps down by the factor 1 - opacity, or a medium's entry or
// exit, between which it falls as exp(-integral of k ds).
struct RayEvent {
    enum class Kind { Surface, MediumEntry, MediumExit };
    Kind kind = Kind::Surface;
    double t = 0;
    int index = -1;          // Surface: into scene_surfaces(scene); media: into scene.media
    double opacity = 0;      // Surface: the layer's opacity, in (0, 1]
    double extinction = 0;   // MediumEntry/Exit: that medium's k at the event's point
};

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
// Surfaces of opacity 0 are left out: they are not there. Media are few and
// tested one by one.
class PreparedScene {
public:
    // scene_surfaces(scene) and scene.media.
    explicit PreparedScene(const Scene& scene);
    explicit PreparedScene(const std::vector<Primitive>& surfaces, const std::vector<Medium>& media = {});

    std::size_t size() const noexcept { return count_; }
    // The first crossing of any surface (of opacity > 0), whatever its opacity.
    std::optional<Hit> closest_hit(const Ray& ray, double t_min, double t_max) const;
    // True when any surface crosses the ray in (t_min, t_max).
    bool occluded(const Ray& ray, double t_min, double t_max) const;

    // The fraction of light that crosses the open segment (t_min, t_max):
    // the product of 1 - opacity over the surfaces crossing it (each once)
    // times exp(-optical_depth). Exactly 0 or 1 in a scene of opaque surfaces
    // and no media. `skip`: the index of a surface left out (the receiver's
    // own convex solid, which no ray leaving it above its tangent plane
    // crosses; ground_truth.h), -1 for none.
    double transmittance(const Ray& ray, double t_min, double t_max, int skip = -1) const;
    // The events in (t_min, t_max) in increasing t: each surface's first
    // crossing, each medium's entry and exit (clipped to the segment: a
    // segment that starts inside a medium enters it at t_min). They end at
    // the first opaque surface, where the transmittance is 0; a medium still
    // open there exits at it, so entries and exits pair up.
    std::vector<RayEvent> events(const Ray& ray, double t_min, double t_max) const;
    // The sum of the media's extinction at a point (0 outside every medium).
    double extinction_at(Vec3 p) const;
    // The integral of the media's extinction along (t_min, t_max), closed form.
    double optical_depth(const Ray& ray, double t_min, double t_max) const;
    const std::vector<PreparedMedium>& media() const noexcept { return media_; }

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
        int index;  // in the scene's surface list
        double opacity;
    };
    struct FlatSurface {  // a plane: unbounded, so outside the hierarchy
        Plane plane;
        int index;
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

    std::vector<FlatSurface> planes_;
    std::vector<Solid> solids_;
    std::vector<PreparedMedium> media_;
    std::vector<Node> nodes_;
    std::size_t count_ = 0;
};

// Convenience: the analytic signed distance of a scene at a world point.
// Prepares the scene on every call; hold a PreparedScene for many points.
double signed_distance(const Scene& scene, Vec3 p);

}  // namespace penumbra::reference
