// Moving the light by sub-texel steps, for the flicker metric.
#include <string>

#include "penumbra/error.h"
#include "penumbra/reference/light_space.h"

namespace penumbra::reference {

Scene shift_light(const Scene& scene, double du_texels, double dv_texels, int map_width, int map_height)
{
    require(map_width > 0 && map_height > 0, "shift_light",
            "map size must be positive (got " + std::to_string(map_width) + "x" + std::to_string(map_height) + ")");
    validate_scene(scene, "shift_light");
    const LightProjection projection(scene);
    // One texel at the reference receiver depth, in world units along s and t.
    const double unit = projection.texture_unit_length(projection.depth_of(reference_depths(scene).z_receiver));
    const Vec3 offset = projection.basis().s * (du_texels * unit / map_width) +
                        projection.basis().t * (dv_texels * unit / map_height);
    Scene shifted = scene;
    shifted.light.center = scene.light.center + offset;
    return shifted;
}

std::vector<Scene> flicker_frames(const Scene& scene, int frames, int map_width, int map_height)
{
    require(frames >= 1, "flicker_frames", "frame count must be >= 1 (got " + std::to_string(frames) + ")");
    std::vector<Scene> sequence;
    for (int k = 0; k < frames; ++k) {
        const double step = double(k) / frames;
        sequence.push_back(shift_light(scene, step, step, map_width, map_height));
    }
    return sequence;
}

}  // namespace penumbra::reference
