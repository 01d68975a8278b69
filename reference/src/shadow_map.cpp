// The shadow map of a reference scene, by ray casting from the light camera:
// first-surface, midpoint or second-surface depths (render.h states the rule).
#include <algorithm>
#include <array>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "penumbra/error.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {
namespace {

constexpr std::array<const char*, 3> kDepthNames = {"first", "midpoint", "second"};

// The depth parameter t of the first crossing in (t_min, far), or `far` when
// there is none: the far plane stands in for a missing surface.
double crossing_or_far(const PreparedScene& prepared, const Ray& ray, double t_min, double far)
{
    const auto hit = prepared.closest_hit(ray, t_min, far);
    return hit ? hit->t : far;
}

// The stored depth parameter along one light ray. The ray parameter is the
// axial depth (ray_through's contract), so casting in (near, far) clips
// exactly at the two planes, and t_min = t1 asks for the next crossing
// strictly beyond the first (the tracer's intervals are open).
double texel_depth(const PreparedScene& prepared, const Ray& ray, double near, double far, ShadowDepth depth)
{
    const double t1 = crossing_or_far(prepared, ray, near, far);
    if (depth == ShadowDepth::First || t1 >= far) return t1;
    const double t2 = crossing_or_far(prepared, ray, t1, far);
    return depth == ShadowDepth::Second ? t2 : 0.5 * (t1 + t2);
}

}  // namespace

ShadowDepth shadow_depth_from_name(const std::string& name, const std::string& parameter)
{
    for (std::size_t i = 0; i < kDepthNames.size(); ++i)
        if (name == kDepthNames[i]) return ShadowDepth(i);
    throw Error(ErrorCategory::InvalidArgument, "render_shadow_map", parameter,
                "'" + name + "' is not a shadow-map depth (first, midpoint or second)");
}

const char* shadow_depth_name(ShadowDepth depth) { return kDepthNames[std::size_t(depth)]; }

Image render_shadow_map(const Scene& scene, int width, int height, ShadowDepth depth)
{
    require(width > 0 && height > 0, "render_shadow_map",
            "size must be positive (got " + std::to_string(width) + "x" + std::to_string(height) + ")");
    require(depth == ShadowDepth::First || depth == ShadowDepth::Midpoint || depth == ShadowDepth::Second,
            "render_shadow_map", "depth", "must be ShadowDepth::First, Midpoint or Second");
    validate_scene(scene, "render_shadow_map");
    const LightProjection projection(scene);
    const PreparedScene prepared(scene);
    const double near = scene.light_camera.near, far = scene.light_camera.far;
    Image map(width, height, 1);
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int j = rows.begin(); j != rows.end(); ++j) {
            float* out = map.row(0, j);
            for (int i = 0; i < width; ++i) {
                const Ray ray = projection.ray_through((i + 0.5) / width, (j + 0.5) / height);
                const double t = texel_depth(prepared, ray, near, far, depth);
                out[i] = float(std::clamp(projection.z_of(t), 0.0, 1.0));
            }
        }
    });
    return map;
}

}  // namespace penumbra::reference
