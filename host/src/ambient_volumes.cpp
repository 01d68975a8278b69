// Ambient volumes validated and packed for kernels/ambient_volumes.h
// (penumbra/ambient.h). The record holds M, the matrix from a world offset to
// the unit shape: row k is the local axis k divided by half_size_k x
// scale_bias, so the kernel does one 3x3 product per pixel and volume.
#include <cmath>
#include <string>

#include "kernels/params.h"
#include "penumbra/ambient.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

const std::string kVolumesOp = "ambient_volumes";

static_assert(AmbientVolumes::kFloats == PN_AMBIENT_VOLUME_FLOATS, "the public record size is the kernel's");

bool all_finite(AmbientVector v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

double dot(AmbientVector a, AmbientVector b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

void check_axes(const AmbientVolume& v, const std::string& name)
{
    const AmbientVector axes[3] = {v.axis_x, v.axis_y, v.axis_z};
    const char* names[3] = {"axis_x", "axis_y", "axis_z"};
    for (int i = 0; i < 3; ++i) {
        require(all_finite(axes[i]), kVolumesOp, "volumes", name + names[i] + " is not finite");
        for (int j = i; j < 3; ++j) {
            const double expected = i == j ? 1.0 : 0.0;
            require(std::abs(dot(axes[i], axes[j]) - expected) <= 1e-5, kVolumesOp, "volumes",
                    name + "axis_x, axis_y and axis_z must be orthonormal (" + names[i] + " . " + names[j] + " = " +
                        std::to_string(dot(axes[i], axes[j])) + ")");
        }
    }
}

void check_volume(const AmbientVolume& v, const std::string& name)
{
    require(all_finite(v.center), kVolumesOp, "volumes", name + "center is not finite");
    const double h[3] = {v.half_size.x, v.half_size.y, v.half_size.z};
    for (double s : h)
        require(std::isfinite(s) && s > 0.0, kVolumesOp, "volumes",
                name + "half_size must be finite and > 0 on every axis (a volume of zero scale darkens nothing)");
    check_axes(v, name);
    require(std::isfinite(v.scale_bias) && v.scale_bias > 0.0, kVolumesOp, "volumes",
            name + "scale_bias must be finite and > 0 (about 1.05 hides tessellation seams)");
    require(std::isfinite(v.falloff_delay) && v.falloff_delay >= 0.0 && v.falloff_delay < 1.0, kVolumesOp, "volumes",
            name + "falloff_delay must be in [0, 1)");
}

void pack(const AmbientVolume& v, std::vector<float>& records)
{
    const AmbientVector axes[3] = {v.axis_x, v.axis_y, v.axis_z};
    const double h[3] = {v.half_size.x, v.half_size.y, v.half_size.z};
    records.push_back(v.shape == AmbientVolume::Shape::Box ? float(PN_AMBIENT_BOX) : float(PN_AMBIENT_SPHERE));
    records.insert(records.end(), {float(v.center.x), float(v.center.y), float(v.center.z)});
    for (int k = 0; k < 3; ++k) {
        const double s = 1.0 / (h[k] * v.scale_bias);
        records.insert(records.end(), {float(axes[k].x * s), float(axes[k].y * s), float(axes[k].z * s)});
    }
    records.insert(records.end(), {float(v.falloff_delay), float(1.0 / (1.0 - v.falloff_delay)), 0.0f});
}

}  // namespace

AmbientVolumes::AmbientVolumes(const std::vector<AmbientVolume>& volumes)
{
    for (std::size_t i = 0; i < volumes.size(); ++i) check_volume(volumes[i], "volumes[" + std::to_string(i) + "].");
    for (const AmbientVolume& v : volumes) pack(v, records_);
}

}  // namespace penumbra
