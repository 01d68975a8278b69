// Scene validation: one place that knows what a well-formed scene is, so that
// scenes loaded from JSON and scenes built in code fail with the same message.
#include <cmath>
#include <string>

#include "penumbra/error.h"
#include "penumbra/reference/scene.h"

namespace penumbra::reference {
namespace {

class FieldChecker {
public:
    FieldChecker(std::string_view operation, std::string_view context)
        : operation_(operation), context_(context)
    {
    }

    void require(bool ok, const std::string& field, std::string_view what) const
    {
        if (!ok)
            throw Error(ErrorCategory::InvalidArgument, operation_,
                        std::string(context_) + field + ": " + std::string(what));
    }
    void finite(double value, const std::string& field) const
    {
        require(std::isfinite(value), field, "must be a finite number");
    }
    void positive(double value, const std::string& field) const
    {
        finite(value, field);
        require(value > 0, field, "must be > 0");
    }
    void finite(Vec3 v, const std::string& field) const
    {
        require(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z), field,
                "must have finite components");
    }
    void direction(Vec3 v, const std::string& field) const
    {
        finite(v, field);
        require(length(v) > 1e-12, field, "must be a non-zero vector");
    }
    void fraction(double value, const std::string& field) const
    {
        finite(value, field);
        require(value >= 0 && value <= 1, field, "must be in [0, 1] (got " + std::to_string(value) + ")");
    }
    void non_negative(double value, const std::string& field) const
    {
        finite(value, field);
        require(value >= 0, field, "must be >= 0 (got " + std::to_string(value) + ")");
    }

private:
    std::string_view operation_, context_;
};

void check(const FieldChecker& c, const Plane& p, const std::string& at)
{
    c.finite(p.point, at + ".point");
    c.direction(p.normal, at + ".normal");
    c.fraction(p.opacity, at + ".opacity");
}

void check(const FieldChecker& c, const Sphere& s, const std::string& at)
{
    c.finite(s.center, at + ".center");
    c.positive(s.radius, at + ".radius");
    c.fraction(s.opacity, at + ".opacity");
}

void check(const FieldChecker& c, const Box& b, const std::string& at)
{
    c.finite(b.center, at + ".center");
    c.finite(b.rotation_degrees, at + ".rotation_degrees");
    c.positive(b.size.x, at + ".size[0]");
    c.positive(b.size.y, at + ".size[1]");
    c.positive(b.size.z, at + ".size[2]");
    c.fraction(b.opacity, at + ".opacity");
}

void check(const FieldChecker& c, const Capsule& k, const std::string& at)
{
    c.finite(k.a, at + ".a");
    c.finite(k.b, at + ".b");
    c.positive(k.radius, at + ".radius");
    c.fraction(k.opacity, at + ".opacity");
}

// The lowest k in the region, where the gradient points most against:
// extinction - |g| r for a sphere, extinction - sum_i |g . axis_i| h_i for a box.
double lowest_extinction(const Medium& m)
{
    if (const auto* sphere = std::get_if<Sphere>(&m.region)) return m.extinction - length(m.gradient) * sphere->radius;
    const Box& box = std::get<Box>(m.region);
    const Rotation r = rotation_from_euler_degrees(box.rotation_degrees);
    const Vec3 h = box.size * 0.5;
    return m.extinction - std::fabs(dot(m.gradient, r.x)) * h.x - std::fabs(dot(m.gradient, r.y)) * h.y -
           std::fabs(dot(m.gradient, r.z)) * h.z;
}

void check_medium(const FieldChecker& c, const Medium& m, const std::string& at)
{
    std::visit([&](const auto& region) { check(c, region, at); }, m.region);
    const double region_opacity = std::visit([](const auto& region) { return region.opacity; }, m.region);
    c.require(region_opacity == 1, at + ".opacity", "a medium has no surface opacity (leave it 1)");
    c.non_negative(m.extinction, at + ".extinction");
    c.finite(m.gradient, at + ".gradient");
    const double lowest = lowest_extinction(m);
    c.require(lowest >= 0, at + ".gradient",
              "makes the extinction negative inside the region (its lowest value is " + std::to_string(lowest) +
                  "); raise extinction or shrink the gradient");
}

void check_hair(const FieldChecker& c, const Hair& h, const std::string& at)
{
    c.finite(h.center, at + ".center");
    c.positive(h.scalp_radius, at + ".scalp_radius");
    c.direction(h.axis, at + ".axis");
    c.finite(h.cap_degrees, at + ".cap_degrees");
    c.require(h.cap_degrees > 0 && h.cap_degrees <= 180, at + ".cap_degrees", "must be in (0, 180]");
    c.require(h.strands >= 1, at + ".strands", "must be >= 1");
    c.require(h.segments >= 1 && h.segments <= 64, at + ".segments", "must be in [1, 64]");
    c.require(static_cast<long long>(h.strands) * h.segments <= kMaxHairCapsules, at + ".strands",
              "strands x segments must be <= " + std::to_string(kMaxHairCapsules));
    c.positive(h.length, at + ".length");
    c.positive(h.radius, at + ".radius");
    c.non_negative(h.droop, at + ".droop");
    c.non_negative(h.curl, at + ".curl");
    c.fraction(h.opacity, at + ".opacity");
}

void check_light(const FieldChecker& c, const AreaLight& light)
{
    c.finite(light.center, "light.center");
    c.direction(light.normal, "light.normal");
    c.finite(light.up, "light.up");
    // Named as in the JSON form: a rectangle's "size": [width, height], a disk's "diameter".
    if (light.shape == LightShape::Point) {
        c.require(light.width == 0 && light.height == 0, "light.size", "must be 0 x 0 for a point light");
    } else if (light.shape == LightShape::Disk) {
        c.positive(light.width, "light.diameter");
        c.require(light.height == light.width, "light.height", "must equal the width (the diameter) for a disk");
    } else {
        c.positive(light.width, "light.size[0]");
        c.positive(light.height, "light.size[1]");
    }
}

void check_light_camera(const FieldChecker& c, const LightCamera& camera)
{
    c.positive(camera.near, "light_camera.near");
    c.finite(camera.far, "light_camera.far");
    c.require(camera.far > camera.near, "light_camera.far", "must be > light_camera.near");
    if (camera.projection == Projection::Perspective) {
        c.finite(camera.fov_degrees, "light_camera.fov_degrees");
        c.require(camera.fov_degrees > 0 && camera.fov_degrees < 179, "light_camera.fov_degrees",
                  "must be in (0, 179)");
    } else {
        c.positive(camera.extent, "light_camera.extent");
    }
}

void check_view(const FieldChecker& c, const ViewCamera& view)
{
    c.finite(view.position, "view.position");
    c.finite(view.target, "view.target");
    c.require(length(view.target - view.position) > 1e-12, "view.target", "must differ from view.position");
    c.direction(view.up, "view.up");
    c.finite(view.fov_degrees, "view.fov_degrees");
    c.require(view.fov_degrees > 0 && view.fov_degrees < 179, "view.fov_degrees", "must be in (0, 179)");
}

void check_directional_lights(const FieldChecker& c, const std::vector<DirectionalLight>& lights)
{
    c.require(int(lights.size()) <= kMaxDirectionalLights, "directional_lights",
              "must hold at most " + std::to_string(kMaxDirectionalLights) +
                  " lights (the world light and a character light)");
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const std::string at = "directional_lights[" + std::to_string(i) + "]";
        c.direction(lights[i].direction, at + ".direction");
        c.direction(lights[i].up, at + ".up");
        c.require(length(cross(normalize(lights[i].direction), normalize(lights[i].up))) > 1e-6, at + ".up",
                  "must not be parallel to the direction");
    }
}

}  // namespace

void validate_scene(const Scene& scene, std::string_view operation, std::string_view context)
{
    const FieldChecker checker(operation, context);
    checker.require(!scene.primitives.empty(), "primitives", "must hold at least one primitive");
    for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
        const std::string at = "primitives[" + std::to_string(i) + "]";
        std::visit([&](const auto& primitive) { check(checker, primitive, at); }, scene.primitives[i]);
    }
    for (std::size_t i = 0; i < scene.media.size(); ++i)
        check_medium(checker, scene.media[i], "media[" + std::to_string(i) + "]");
    for (std::size_t i = 0; i < scene.hair.size(); ++i)
        check_hair(checker, scene.hair[i], "hair[" + std::to_string(i) + "]");
    check_light(checker, scene.light);
    check_light_camera(checker, scene.light_camera);
    check_view(checker, scene.view);
    check_directional_lights(checker, scene.directional_lights);
    checker.require(scene.map_size >= 1, "map_size", "must be >= 1");
}

}  // namespace penumbra::reference
