// The receivers: what the view camera sees, in world and in light space.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "penumbra/error.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

void store3(Image& image, int x, int y, Vec3 v)
{
    image.at(0, x, y) = float(v.x);
    image.at(1, x, y) = float(v.y);
    image.at(2, x, y) = float(v.z);
}

bool in_unit_cube(Vec3 uvz)
{
    auto unit = [](double a) { return a >= 0 && a <= 1; };
    return unit(uvz.x) && unit(uvz.y) && unit(uvz.z);
}

Vec3 clamp_to_unit_cube(Vec3 uvz)
{
    return {std::clamp(uvz.x, 0.0, 1.0), std::clamp(uvz.y, 0.0, 1.0), std::clamp(uvz.z, 0.0, 1.0)};
}

// Pinhole view rays: direction n + a s + b t, so the ray parameter is the
// depth along the view axis.
class ViewRays {
public:
    ViewRays(const ViewCamera& view, int width, int height)
        : basis_(basis_looking_along(view.target - view.position, view.up)),
          origin_(view.position),
          width_(width),
          height_(height),
          tan_half_(std::tan(view.fov_degrees * std::numbers::pi / 360.0))
    {
    }

    Ray through_pixel(int x, int y) const
    {
        const double aspect = double(width_) / height_;
        const double a = (2 * (x + 0.5) / width_ - 1) * tan_half_ * aspect;
        const double b = (2 * (y + 0.5) / height_ - 1) * tan_half_;
        return {origin_, basis_.to_world({a, b, 1})};
    }

private:
    Basis basis_;
    Vec3 origin_;
    int width_, height_;
    double tan_half_;
};

}  // namespace

Receivers Receivers::allocate(int width, int height)
{
    Receivers out{Image(width, height, 3), Image(width, height, 3), Image(width, height, 3),
                  Image(width, height, 1), Image(width, height, 1), Image(width, height, 1), Image(width, height, 1)};
    out.surface.fill(0, -1.0f);
    return out;
}

Image Receivers::positions_normals_and_surface() const
{
    const Image six = positions_and_normals();
    Image out(width(), height(), 7);
    for (int c = 0; c < 7; ++c)
        for (int y = 0; y < height(); ++y) std::copy_n((c < 6 ? six : surface).row(c < 6 ? c : 0, y), width(), out.row(c, y));
    return out;
}

Image Receivers::positions_and_normals() const
{
    Image out(width(), height(), 6);
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < height(); ++y) {
            std::copy_n(world_position.row(c, y), width(), out.row(c, y));
            std::copy_n(normal.row(c, y), width(), out.row(3 + c, y));
        }
    return out;
}

Receivers render_receivers(const Scene& scene, int width, int height)
{
    require(width > 0 && height > 0, "render_receivers",
            "size must be positive (got " + std::to_string(width) + "x" + std::to_string(height) + ")");
    validate_scene(scene, "render_receivers");
    const LightProjection projection(scene);
    const PreparedScene prepared(scene);
    const ViewRays rays(scene.view, width, height);
    Receivers out = Receivers::allocate(width, height);
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < width; ++x) {
                const Ray ray = rays.through_pixel(x, y);
                const auto hit = prepared.closest_hit(ray, 0.0, std::numeric_limits<double>::infinity());
                if (!hit) {
                    store3(out.light_uvz, x, y, {0, 0, 1});
                    continue;
                }
                const Vec3 position = ray.at(hit->t);
                const Vec3 uvz = projection.project(position);
                store3(out.light_uvz, x, y, clamp_to_unit_cube(uvz));
                store3(out.world_position, x, y, position);
                store3(out.normal, x, y, hit->normal);
                out.view_depth.at(0, x, y) = float(hit->t);
                out.hit.at(0, x, y) = 1;
                out.surface.at(0, x, y) = float(hit->primitive);
                out.mask.at(0, x, y) = in_unit_cube(uvz) ? 1.0f : 0.0f;
            }
    });
    return out;
}

}  // namespace penumbra::reference
