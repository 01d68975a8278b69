// Sphere-traced signed-distance-field soft shadows (kernels/sdf.h).
//
// For each receiver (a world-space point), a ray is marched from it towards
// the light through a signed distance field, keeping the narrowest "safe
// angle" seen (Quilez): visibility in [0, 1]. Two sources of distance: a
// DistanceGrid (sampled trilinearly, what engines bake) and an AnalyticScene
// (planes, spheres, boxes, capsules evaluated in the kernel).
// The types here are the library's own, so that this API depends on nothing
// of the ground-truth side: penumbra::reference (its own target,
// penumbra/reference/sdf_scene.h) converts its scenes to them, bakes grids
// from them and derives k from their lights; docs/sdf.md has the conventions
// and measured figures.
#pragma once

#include <cstddef>
#include <string>
#include <variant>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/image.h"

namespace penumbra {

// A world-space point or direction. Double, as a renderer's scene usually
// is; the kernels receive float (each record field is rounded once).
struct SdfVec3 {
    double x = 0, y = 0, z = 0;
    friend bool operator==(const SdfVec3&, const SdfVec3&) = default;
};

// The solids the analytic kernel evaluates (kernels/sdf.h), each by its exact
// signed distance, negative inside.
struct SdfPlane {  // the half-space dot(p - point, normal) <= 0 (normal non-zero, normalised on use)
    SdfVec3 point;
    SdfVec3 normal{0, 1, 0};
};
struct SdfSphere {
    SdfVec3 center;
    double radius = 1;
};
// An oriented box: half side lengths along its own axes, which are the
// world images of the local x, y and z axes (the columns of its rotation;
// orthonormal within 1e-5). An engine's transform gives them directly.
struct SdfBox {
    SdfVec3 center;
    SdfVec3 half_size{0.5, 0.5, 0.5};
    SdfVec3 axis_x{1, 0, 0}, axis_y{0, 1, 0}, axis_z{0, 0, 1};
};
struct SdfCapsule {  // the points within `radius` of the segment [a, b]
    SdfVec3 a, b{0, 1, 0};
    double radius = 0.5;
};
using SdfPrimitive = std::variant<SdfPlane, SdfSphere, SdfBox, SdfCapsule>;

// A node-centred grid of signed distances (world units, negative inside):
// node (i, j, k) lies at origin + voxel_size * (i, j, k); nodes are stored x
// fastest, then y, then z. Values are sampled trilinearly inside the box of
// nodes; outside it the world is empty but for what the grid holds
// (kernels/sdf.h gives the bound used there). Origin and voxel size are
// stored as float, as the kernels use them.
class DistanceGrid {
public:
    DistanceGrid() = default;
    // Zero-filled. Throws Error(InvalidArgument) for fewer than 2 nodes on an
    // axis, more than 2^31 - 1 nodes, a voxel size that is not finite and > 0,
    // or an origin that is not finite.
    DistanceGrid(int nx, int ny, int nz, SdfVec3 origin, double voxel_size);

    int nx() const noexcept { return nx_; }
    int ny() const noexcept { return ny_; }
    int nz() const noexcept { return nz_; }
    std::size_t size() const noexcept { return std::size_t(nx_) * ny_ * nz_; }
    bool empty() const noexcept { return size() == 0; }
    SdfVec3 origin() const noexcept { return {origin_[0], origin_[1], origin_[2]}; }
    // The last node: origin + voxel_size * (nx - 1, ny - 1, nz - 1).
    SdfVec3 upper() const noexcept;
    double voxel_size() const noexcept { return voxel_; }

    float* data() noexcept { return reinterpret_cast<float*>(storage_.data()); }
    const float* data() const noexcept { return reinterpret_cast<const float*>(storage_.data()); }
    std::size_t index(int i, int j, int k) const noexcept { return (std::size_t(k) * ny_ + j) * nx_ + i; }
    float& at(int i, int j, int k) noexcept { return data()[index(i, j, k)]; }
    float at(int i, int j, int k) const noexcept { return data()[index(i, j, k)]; }

private:
    int nx_ = 0, ny_ = 0, nz_ = 0;
    float origin_[3] = {0, 0, 0};
    float voxel_ = 0;
    AlignedBuffer storage_;
};

// The primitives of a scene packed for the kernel (the record layout is in
// kernels/params.h, SdfParams), grouped by kind. Immutable once built.
class AnalyticScene {
public:
    AnalyticScene() = default;  // no primitives: every receiver is lit
    // Throws Error(InvalidArgument) naming primitives[i] and the field for a
    // non-finite value, a zero normal, a radius or half side that is not > 0,
    // or box axes that are not orthonormal.
    explicit AnalyticScene(const std::vector<SdfPrimitive>& primitives);

    int planes() const noexcept { return counts_[0]; }
    int spheres() const noexcept { return counts_[1]; }
    int boxes() const noexcept { return counts_[2]; }
    int capsules() const noexcept { return counts_[3]; }
    const std::vector<float>& records() const noexcept { return records_; }

private:
    int counts_[4] = {0, 0, 0, 0};
    std::vector<float> records_;
};

// Where the rays go: to a light's centre (each ray ends there, or at t_max if
// nearer), or along one direction towards a distant light (rays end at t_max).
struct SdfLight {
    bool directional = false;
    SdfVec3 vector{0, 10, 0};  // the centre, or the direction (normalised on use)

    static SdfLight at(SdfVec3 centre) { return {false, centre}; }
    static SdfLight towards(SdfVec3 direction) { return {true, direction}; }
};

enum class SdfEstimate {
    Classic,        // res = min(res, k h / t), 0 once the ray hits
    Improved,       // the closest approach triangulated from two consecutive distances
    InnerPenumbra,  // signed k h / t through solids, [-1, 1] smoothstepped: both halves of a penumbra
};

struct SdfOptions {
    SdfLight light;
    // Hardness, > 0. With light_width == 0: 1/k radians of clearance count as
    // fully lit, for every receiver (sdf_hardness derives it from a light's
    // size at one distance). With light_width = W > 0 (a light at a point):
    // each receiver uses k * 2 D / W, D its own distance to the light's
    // centre, so 1/k is the lit clearance as a fraction of the light's
    // half-angle seen from there (kSdfHardnessFit below).
    float k = 8.0f;
    float light_width = 0.0f;   // world units, >= 0; > 0 only with SdfLight::at
    SdfEstimate estimate = SdfEstimate::InnerPenumbra;  // docs/sdf.md: 3x (contact) and 2.5x (fence) less RMSE than Classic
    float t_min = 1e-3f;        // start of the march along the ray (world units), >= 0
    float t_max = 1e30f;        // end of the march (world units), > t_min
    int max_steps = 128;        // distance evaluations per ray, in [1, 1000000]
    float hit_epsilon = 1e-4f;  // a distance below this is a hit (world units), > 0
    float normal_offset = 0.0f; // lift receivers along their normals (world units), >= 0; needs normals
};

// Visibility of world-space receivers. `positions`: 3 channels (x, y, z);
// `normals`: nullptr, or 3 channels (unit normals) of the same size, required
// when options.normal_offset > 0. Returns 1 channel of visibility in [0, 1].
// Throws Error(InvalidArgument) for bad options or shapes (naming the
// option), Error(InvalidData) for a NaN or infinite receiver, normal or grid
// node (naming the first one).
Image sdf_shadows(Context& context, const DistanceGrid& grid, const Image& positions, const Image* normals,
                  const SdfOptions& options);
Image sdf_shadows(Context& context, const AnalyticScene& scene, const Image& positions, const Image* normals,
                  const SdfOptions& options);

// The same into an existing image of the receivers' size: 1 channel, or 2
// for the visibility and each ray's number of distance evaluations (its
// active steps; a measurement of the march, see lane_utilisation).
void sdf_shadows(Context& context, const DistanceGrid& grid, const Image& positions, const Image* normals,
                 const SdfOptions& options, Image& out);
void sdf_shadows(Context& context, const AnalyticScene& scene, const Image& positions, const Image* normals,
                 const SdfOptions& options, Image& out);

// The light's half-angle from distance D is about W / (2 D) for a light of
// width W (a square's side, a disk's diameter); a ray whose clearance angle
// h / t reaches it sees the whole light. k = fit 2 D / W makes the estimate
// reach 1 at 1 / fit of that angle. The estimate is 0 where the ray to the
// light's centre is blocked (where the truth is still 1/2), so it sees only
// the outer half of a penumbra; fit = 2 minimises the squared error across a
// straight edge's penumbra (docs/sdf.md derives it) and, measured against the
// ground truth, is within 1% of the best fit on contact, overlap and grazing.
// Throws Error(InvalidArgument) for a width, distance or fit not finite and > 0.
inline constexpr double kSdfHardnessFit = 2.0;
// The inner-penumbra estimate (SdfEstimate::InnerPenumbra) maps k h / t from
// [-1, 1] to [0, 1]: it reaches 1 and 0 at +-1/k of clearance, so k = 2 D / W
// (fit 1) spans the light's half-angle on either side of the shadow's edge.
inline constexpr double kSdfInnerHardnessFit = 1.0;
double sdf_hardness(double light_width, double distance, double fit = kSdfHardnessFit);

// How busy the lanes of a SIMD march are: a group of receivers that share a
// strip runs until its slowest member is done, so it costs (lanes x its
// largest step count) lane-steps, of which the sum of its step counts are
// active. Groups are tile_width x tile_height blocks of the steps image
// (tile_width x 1: the backends' rows of strips); a block reaching past the
// image is counted whole, as a masked strip is. ratio = active / total.
struct LaneUtilisation {
    double active = 0, total = 0;
    double ratio() const { return total > 0 ? active / total : 1.0; }
};
// `steps`: channel `channel` of an sdf_shadows output with steps.
LaneUtilisation lane_utilisation(const Image& steps, int channel, int tile_width, int tile_height = 1);

// The grid file format (docs/sdf.md): little-endian, a 36-byte header, magic
// "PNSDFGR1", int32 nx, ny, nz, float32 origin x, y, z, float32 voxel size,
// then nx * ny * nz float32 distances, x fastest. Reading throws Error(Io) for
// a file that cannot be read or is not such a grid (magic, size), and
// Error(InvalidData) naming the file and the field or node for bad values.
// Writing is atomic (a temporary file renamed over the target).
void write_distance_grid(const std::string& path, const DistanceGrid& grid);
DistanceGrid read_distance_grid(const std::string& path);

}  // namespace penumbra
