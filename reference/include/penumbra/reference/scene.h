// The reference scene model: analytic primitives, an area or point light, the
// light's camera (which renders the shadow map) and the view camera (which
// sees the receivers); for deep shadows also surface opacity, participating
// media and hair. docs/reference.md gives the conventions with figures.
//
// Every primitive is a solid: a plane is the half-space below it, a box, sphere
// or capsule its inside. Rays and the signed distance treat them alike.
//
// Opacity: every primitive is one layer that transmits 1 - opacity of the
// light crossing it, once per ray however many of its faces the ray crosses
// (a slab, a strand, a sheet; every primitive is convex, so a line meets it in
// one interval). 1, the default, is opaque: scenes without the field are what
// they always were. A surface of opacity 0 is not there at all.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "penumbra/reference/ambient_json.h"
#include "penumbra/reference/geometry.h"

namespace penumbra::reference {

// The half-space dot(p - point, normal) <= 0; its surface faces `normal`.
struct Plane {
    Vec3 point;
    Vec3 normal{0, 1, 0};
    double opacity = 1;
};

struct Sphere {
    Vec3 center;
    double radius = 1;
    double opacity = 1;
};

// An oriented box: full side lengths `size` along its local axes, turned by
// rotation_from_euler_degrees(rotation_degrees) about its centre. A thin slat
// is a box with one small side.
struct Box {
    Vec3 center;
    Vec3 size{1, 1, 1};
    Vec3 rotation_degrees;
    double opacity = 1;
};

// The points within `radius` of the segment [a, b].
struct Capsule {
    Vec3 a, b{0, 1, 0};
    double radius = 0.5;
    double opacity = 1;
};

using Primitive = std::variant<Plane, Sphere, Box, Capsule>;

double opacity_of(const Primitive& primitive);

// A region of participating medium (fog): a sphere or an oriented box whose
// extinction coefficient (per unit length) is linear in position,
//   k(p) = extinction + dot(gradient, p - centre of the region),
// homogeneous when the gradient is zero. Linear because the integral of a
// linear function along a chord is the chord's length times k at its midpoint,
// so the transmittance exp(-integral of k ds) has a closed form. k must be >= 0
// everywhere in the region (validate_scene checks its lowest point). Media add
// where they overlap. A medium is not a surface: it is no shadow-map depth and
// the view camera sees through it. The region's own opacity has no meaning
// here and must stay 1.
struct Medium {
    std::variant<Sphere, Box> region;
    double extinction = 1;  // k at the region's centre
    Vec3 gradient;          // dk/dp, per unit length squared
};

// Hair: `strands` strands rooted uniformly (by area) on the cap of the sphere
// (center, scalp_radius) within cap_degrees of `axis`. A strand is a chain of
// `segments` capsules of radius `radius`, `length` long in all; it leaves the
// scalp along its normal, and each segment's direction is the previous one
// plus droop / segments of a unit step down (-y) plus a random vector with
// components in [-curl, curl], normalised. hair_strands() generates the
// capsules from `seed` through SplitMix64 (no std:: distributions, whose
// output differs between standard libraries): the same seed, the same
// strands. Each capsule is a layer of the hair's opacity (where a ray crosses
// a joint it crosses two capsules: exact for opaque hair, a double step for a
// translucent one). Meant to be thinner than a shadow-map texel.
struct Hair {
    Vec3 center{0, 1, 0};
    double scalp_radius = 0.5;
    Vec3 axis{0, 1, 0};
    double cap_degrees = 90;
    int strands = 1000;
    int segments = 4;
    double length = 0.3;
    double radius = 0.0004;
    double droop = 0;
    double curl = 0;
    double opacity = 1;
    std::uint64_t seed = 1;
};

// At most this many capsules per Hair (strands x segments): 1 Mi, about
// 100 MB of hierarchy.
inline constexpr long long kMaxHairCapsules = 1 << 20;

// The capsules of one Hair, strand after strand, root first.
std::vector<Capsule> hair_strands(const Hair& hair);

enum class LightShape { Rectangle, Disk, Point };

// A one-sided light centred on `center`, emitting towards `normal` (into the
// half-space in front of it). Its frame is basis_looking_along(normal, up):
// the rectangle spans `width` along s and `height` along t; a disk has
// diameter `width` (and height == width); a point light (a spot, with the
// light camera's frustum for its cone) has width == height == 0.
struct AreaLight {
    LightShape shape = LightShape::Rectangle;
    Vec3 center{0, 10, 0};
    Vec3 normal{0, -1, 0};
    Vec3 up{0, 1, 0};
    double width = 1, height = 1;
};

// A light at infinity (the sun): parallel rays travelling along `direction`.
// Its frame is basis_looking_along(direction, up), as an area light's is
// along its normal; cascaded shadow maps (cascades.h) are orthographic maps
// in that frame, fitted to the view, so the light needs no camera of its own.
// A scene's first directional light is its world light (the sun), the second
// its character light (Toy Story 3's second shadow channel; docs/cascades.md).
struct DirectionalLight {
    Vec3 direction{0, -1, 0};
    Vec3 up{0, 0, -1};
};

// A scene holds at most this many (the world light and a character light).
inline constexpr int kMaxDirectionalLights = 2;

enum class Projection { Perspective, Orthographic };

// The camera that renders the shadow map. It sits at the light's centre and
// looks along the light's normal, in the light's frame (s right, t down).
// Depth d is the distance along that axis; the map stores the linear depth
// z = (d - near) / (far - near). Perspective: fov_degrees is the full angle
// across u and across v. Orthographic: `extent` is the full side of the
// square the map covers, in world units.
struct LightCamera {
    Projection projection = Projection::Perspective;
    double near = 0.1, far = 20;
    double fov_degrees = 60;
    double extent = 10;
};

// The perspective camera that sees the receivers. fov_degrees is the full
// vertical angle; the horizontal one follows from the image's aspect ratio.
struct ViewCamera {
    Vec3 position{0, 5, 10};
    Vec3 target{0, 0, 0};
    Vec3 up{0, 1, 0};
    double fov_degrees = 45;
};

struct Scene {
    std::string name;
    std::string description;
    std::vector<Primitive> primitives;
    std::vector<Medium> media;
    std::vector<Hair> hair;
    AreaLight light;
    LightCamera light_camera;
    // Optional: the sun and a character light, for cascaded shadow maps.
    std::vector<DirectionalLight> directional_lights;
    ViewCamera view;
    // The shadow-map side the scene is designed for (texel-size claims in the
    // scene's description refer to it). Every render works at any size.
    int map_size = 1024;
    // Optional ambient lighting: rigs and volumes (docs/ambient.md).
    std::optional<SceneAmbient> ambient;
};

// Throws Error(InvalidArgument, operation, "<context><field path>: <what is
// wrong>"), e.g. "primitives[2].radius: must be > 0", for the first invalid
// field. `context` (a file name and ": ", say) is put before the path.
void validate_scene(const Scene& scene, std::string_view operation, std::string_view context = {});

// JSON form (docs/reference.md lists the fields). Loading throws Error(Io)
// when the file cannot be read or is not JSON, and Error(InvalidArgument)
// naming the field when a field is missing, of the wrong type or out of range.
Scene load_scene(const std::filesystem::path& path);
Scene scene_from_json(std::string_view text, std::string_view source_name = "<string>");
std::string scene_to_json(const Scene& scene);
void save_scene(const Scene& scene, const std::filesystem::path& path);

// What a ray meets: the primitives, then every Hair's capsules in order
// (hair_strands). Hit::primitive and RayEvent::index count in this list.
std::vector<Primitive> scene_surfaces(const Scene& scene);

// The built-in scenes, each named for the failure it provokes. Opaque: the
// shadow-map scenes under area lights (contact, overlap, fence, grazing,
// large), which the demo runs. Deep: the deep-shadow scenes under point
// lights (hair, fog, layers), whose shadows are fractions: thin strands,
// fog, semi-transparent layers. An unknown name throws Error(InvalidArgument)
// listing the valid ones.
enum class SceneSet { Opaque, Deep, All };
std::vector<std::string> builtin_scene_names(SceneSet set = SceneSet::Opaque);
Scene builtin_scene(std::string_view name);

}  // namespace penumbra::reference
