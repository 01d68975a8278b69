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

private:
    std::string_view operation_, context_;
};

void check(const FieldChecker& c, const Plane& p, const std::string& at)
{
    c.finite(p.point, at + ".point");
    c.direction(p.normal, at + ".normal");
}

void check(const FieldChecker& c, const Sphere& s, const std::string& at)
{
    c.finite(s.center, at + ".center");
    c.positive(s.radius, at + ".radius");
}

void check(const FieldChecker& c, const Box& b, const std::string& at)
{
    c.finite(b.center, at + ".center");
    c.finite(b.rotation_degrees, at + ".rotation_degrees");
    c.positive(b.size.x, at + ".size[0]");
    c.positive(b.size.y, at + ".size[1]");
    c.positive(b.size.z, at + ".size[2]");
}

void check(const FieldChecker& c, const Capsule& k, const std::string& at)
{
    c.finite(k.a, at + ".a");
    c.finite(k.b, at + ".b");
    c.positive(k.radius, at + ".radius");
}

void check_light(const FieldChecker& c, const AreaLight& light)
{
    c.finite(light.center, "light.center");
    c.direction(light.normal, "light.normal");
    c.finite(light.up, "light.up");
    // Named as in the JSON form: a rectangle's "size": [width, height], a disk's "diameter".
    if (light.shape == LightShape::Disk) {
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

}  // namespace

void validate_scene(const Scene& scene, std::string_view operation, std::string_view context)
{
    const FieldChecker checker(operation, context);
    checker.require(!scene.primitives.empty(), "primitives", "must hold at least one primitive");
    for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
        const std::string at = "primitives[" + std::to_string(i) + "]";
        std::visit([&](const auto& primitive) { check(checker, primitive, at); }, scene.primitives[i]);
    }
    check_light(checker, scene.light);
    check_light_camera(checker, scene.light_camera);
    check_view(checker, scene.view);
    checker.require(scene.map_size >= 1, "map_size", "must be >= 1");
}

}  // namespace penumbra::reference
