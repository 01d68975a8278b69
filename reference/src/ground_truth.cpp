// The ground-truth image: light_visibility for every receiver, rows in parallel.
#include <string>
#include <vector>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "penumbra/error.h"
#include "penumbra/reference/ground_truth.h"

namespace penumbra::reference {
namespace {

Vec3 load3(const Image& image, int x, int y)
{
    return {image.at(0, x, y), image.at(1, x, y), image.at(2, x, y)};
}

void require_receivers(const Receivers& r)
{
    const int w = r.hit.width(), h = r.hit.height();
    auto fits = [&](const Image& image, int channels) {
        return image.width() == w && image.height() == h && image.channels() == channels;
    };
    require(w > 0 && h > 0, "ground_truth", "the receivers are empty");
    require(fits(r.world_position, 3) && fits(r.normal, 3) && fits(r.hit, 1), "ground_truth",
            "receivers must hold a 3-channel world_position and normal and a 1-channel hit image of one size");
}

// A stream name per (seed, pixel). light_visibility hashes it before use, so
// neighbouring names give unrelated sample sequences.
std::uint64_t pixel_stream(std::uint64_t seed, int x, int y, int width)
{
    const std::uint64_t index = std::uint64_t(y) * std::uint64_t(width) + std::uint64_t(x);
    return seed ^ (index * 0x9e3779b97f4a7c15ull);
}

}  // namespace

Image ground_truth(const Scene& scene, const Receivers& receivers, const GroundTruthOptions& options)
{
    require(options.strata >= 1 && options.strata <= 4096, "ground_truth",
            "strata must be in [1, 4096] (got " + std::to_string(options.strata) + ")");
    validate_scene(scene, "ground_truth");
    require_receivers(receivers);
    const PreparedScene prepared(scene);
    const std::vector<bool> opaque = opaque_surfaces(scene);
    const int width = receivers.hit.width(), height = receivers.hit.height();
    Image truth(width, height, 1);
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < width; ++x) {
                if (receivers.hit.at(0, x, y) == 0) {
                    truth.at(0, x, y) = 1;
                    continue;
                }
                const double visible = light_visibility(
                    prepared, scene.light, load3(receivers.world_position, x, y),
                    load3(receivers.normal, x, y), options.strata, pixel_stream(options.seed, x, y, width),
                    receiver_own_surface(receivers, opaque, x, y));
                truth.at(0, x, y) = float(visible);
            }
    });
    return truth;
}

}  // namespace penumbra::reference
