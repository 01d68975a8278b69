// The reference scene model: analytic primitives, an area light, the light's
// camera (which renders the shadow map) and the view camera (which sees the
// receivers). docs/reference.md gives the conventions with figures.
//
// Every primitive is a solid: a plane is the half-space below it, a box, sphere
// or capsule its inside. Rays and the signed distance treat them alike.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "penumbra/reference/geometry.h"

namespace penumbra::reference {

// The half-space dot(p - point, normal) <= 0; its surface faces `normal`.
struct Plane {
    Vec3 point;
    Vec3 normal{0, 1, 0};
};

struct Sphere {
    Vec3 center;
    double radius = 1;
};

// An oriented box: full side lengths `size` along its local axes, turned by
// rotation_from_euler_degrees(rotation_degrees) about its centre. A thin slat
// is a box with one small side.
struct Box {
    Vec3 center;
    Vec3 size{1, 1, 1};
    Vec3 rotation_degrees;
};

// The points within `radius` of the segment [a, b].
struct Capsule {
    Vec3 a, b{0, 1, 0};
    double radius = 0.5;
};

using Primitive = std::variant<Plane, Sphere, Box, Capsule>;

enum class LightShape { Rectangle, Disk };

// A one-sided area light centred on `center`, emitting towards `normal`. Its
// frame is basis_looking_along(normal, up): the rectangle spans `width` along
// s and `height` along t; a disk has diameter `width` (and height == width).
struct AreaLight {
    LightShape shape = LightShape::Rectangle;
    Vec3 center{0, 10, 0};
    Vec3 normal{0, -1, 0};
    Vec3 up{0, 1, 0};
    double width = 1, height = 1;
};

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
    AreaLight light;
    LightCamera light_camera;
    ViewCamera view;
    // The shadow-map side the scene is designed for (texel-size claims in the
    // scene's description refer to it). Every render works at any size.
    int map_size = 1024;
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

// The built-in scenes, each named for the failure it provokes: contact,
// overlap, fence, grazing, large. An unknown name throws Error(InvalidArgument)
// listing the valid ones.
std::vector<std::string> builtin_scene_names();
Scene builtin_scene(std::string_view name);

}  // namespace penumbra::reference
