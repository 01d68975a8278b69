// The shadow map of a reference scene, by ray casting from the light camera.
#include <algorithm>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "penumbra/error.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/tracer.h"

namespace penumbra::reference {

Image render_shadow_map(const Scene& scene, int width, int height)
{
    require(width > 0 && height > 0, "render_shadow_map",
            "size must be positive (got " + std::to_string(width) + "x" + std::to_string(height) + ")");
    validate_scene(scene, "render_shadow_map");
    const LightProjection projection(scene);
    const PreparedScene prepared(scene.primitives);
    const double near = scene.light_camera.near, far = scene.light_camera.far;
    Image map(width, height, 1);
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int j = rows.begin(); j != rows.end(); ++j) {
            float* out = map.row(0, j);
            for (int i = 0; i < width; ++i) {
                // The ray parameter is the depth along the axis (ray_through's contract),
                // so casting in (near, far) clips exactly at the two planes.
                const Ray ray = projection.ray_through((i + 0.5) / width, (j + 0.5) / height);
                const auto hit = prepared.closest_hit(ray, near, far);
                out[i] = hit ? float(std::clamp(projection.z_of(hit->t), 0.0, 1.0)) : 1.0f;
            }
        }
    });
    return map;
}

}  // namespace penumbra::reference
