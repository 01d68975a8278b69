// Stratified sampling of the area light and the light that reaches one
// receiver: the mean transmittance of the segments to the light samples.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "disk_mapping.h"
#include "penumbra/reference/ground_truth.h"
#include "splitmix64.h"

namespace penumbra::reference {
namespace {

// The light point for a sample (a, b) of the unit square, in the light's frame.
Vec3 light_point(const AreaLight& light, const Basis& frame, double a, double b)
{
    if (light.shape == LightShape::Disk) {
        const Vec3 d = concentric_disk(a, b) * (0.5 * light.width);
        return light.center + frame.s * d.x + frame.t * d.y;
    }
    return light.center + frame.s * ((a - 0.5) * light.width) + frame.t * ((b - 0.5) * light.height);
}

}  // namespace

double light_visibility(const PreparedScene& prepared, const AreaLight& light, Vec3 position, Vec3 normal,
                        int strata, std::uint64_t stream, int own_surface)
{
    const Basis frame = basis_looking_along(light.normal, light.up);
    if (dot(position - light.center, frame.n) <= 0) return 0;
    const ReceiverRays rays(position, normal, own_surface);
    // Direction to the light point unnormalised: t in (0, 1) spans the segment.
    auto towards = [&](Vec3 target) { return rays.transmittance(prepared, target - rays.origin, 1.0); };
    if (light.shape == LightShape::Point) return towards(light.center);  // exact: one segment
    // Hash the stream name into the starting state: SplitMix64 walks its state
    // in steps of a fixed constant, so two raw names a multiple of that step
    // apart would give overlapping (shifted) sequences.
    SplitMix64 random(SplitMix64(stream).next());
    // A sum of transmittances; with opaque surfaces and no media each is
    // exactly 0 or 1, so the sum is the count of visible samples.
    double arriving = 0;
    for (int j = 0; j < strata; ++j)
        for (int i = 0; i < strata; ++i) {
            const double a = (i + random.uniform()) / strata, b = (j + random.uniform()) / strata;
            arriving += towards(light_point(light, frame, a, b));
        }
    return arriving / (double(strata) * strata);
}

}  // namespace penumbra::reference
