// Ambient light rigs in spherical harmonics, and ambient volumes (Toy Story 3:
// Hall, Siggraph 2010 course, "Ambient Lighting"; docs/ambient.md).
//
// A rig is a set of directional lights with colour and signed intensity. It is
// projected on the host (every frame, in microseconds) onto the real SH basis
// to order 2 (9 coefficients per channel) or 1 (4) and convolved with the
// clamped cosine (Ramamoorthi & Hanrahan 2001), which gives irradiance
// coefficients; two rigs blend by interpolating those. The kernel
// (kernels/ambient_sh.h) evaluates them with each pixel's normal, from one rig
// or blended per pixel between a light and a dark rig by a factor in [0, 1]:
// a receiver channel, or the ambient volumes (kernels/ambient_volumes.h) at
// the pixel's world position.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/image.h"

namespace penumbra {

struct AmbientVector {
    double x = 0, y = 0, z = 0;
};

// A directional light of the rig: it shines along -direction, lighting
// normals that face `direction` (normalised on use; not zero).
struct AmbientLight {
    AmbientVector direction{0, 1, 0};
    AmbientVector color{1, 1, 1};  // linear RGB, finite
    double intensity = 1;          // signed: a negative light darkens (the notes' "negative light")
};

struct AmbientRig {
    std::vector<AmbientLight> lights;  // at least one
};

// Windowing of the coefficients against ringing, band l scaled by
// Hanning (1 + cos(pi l / w)) / 2 or Lanczos sin(pi l / w) / (pi l / w), w the
// window's width (Sloan, "Stupid Spherical Harmonics Tricks", 2008).
// docs/ambient.md has what each costs: at order 2 and w = 4 a single light's
// negative lobe shrinks from -3.96% to -2.2% (Hanning) or -1.9% (Lanczos) of
// its peak, and the largest error grows from 9.4% to 17% or 15%.
enum class ShWindow { None, Hanning, Lanczos };

struct ShOptions {
    int order = 2;  // 1 (4 coefficients) or 2 (9)
    ShWindow window = ShWindow::None;
    double window_width = 4.0;  // w, > order (read only with a window)
};

// Irradiance coefficients: E(n) = sum_i coefficients[c][i] Y_i(n) for channel
// c (R, G, B), Y_i the real SH basis in the order l(l + 1) + m (Y00; Y1-1,
// Y10, Y11; Y2-2 .. Y22), the clamped-cosine convolution and any window
// applied. Order 1 keeps indices 4 .. 8 at zero.
struct ShIrradiance {
    int order = 2;
    std::array<std::array<double, 9>, 3> coefficients{};
};

// Throws Error(InvalidArgument, "project_rig", "rig") for a rig with no
// lights, naming lights[i] and the field for a non-finite value or a zero
// direction, and for an order that is not 1 or 2 (parameter "order").
ShIrradiance project_rig(const AmbientRig& rig, const ShOptions& options = {});
// (1 - t) a + t b, coefficient by coefficient (t in [0, 1]; the same order).
ShIrradiance blend_rigs(const ShIrradiance& a, const ShIrradiance& b, double t);
// E(n) in float64 (n not zero; normalised here): the kernel's mathematics.
std::array<double, 3> evaluate_irradiance(const ShIrradiance& sh, AmbientVector normal);
// The exact irradiance of the rig: sum over its lights of colour x intensity x
// max(0, n . l), n and l normalised.
std::array<double, 3> exact_irradiance(const AmbientRig& rig, AmbientVector normal);

// A volume darkening what lies inside it towards the dark rig. Its local
// axes (orthonormal within 1e-5, the columns of its rotation) and half size
// place it; a sphere with unequal half sizes is an ellipsoid. The factor is 1
// at the centre, stays 1 out to `falloff_delay` of the way to the surface,
// then falls linearly to 0 at the surface of the shape scaled by `scale_bias`;
// a box is first mapped onto a sphere (kernels/ambient_volumes.h has the formulas).
struct AmbientVolume {
    enum class Shape { Sphere, Box };
    Shape shape = Shape::Sphere;
    AmbientVector center;
    AmbientVector half_size{1, 1, 1};  // > 0 each
    AmbientVector axis_x{1, 0, 0}, axis_y{0, 1, 0}, axis_z{0, 0, 1};
    double scale_bias = 1.0;     // >= 1 in practice (the notes' 1.05 hides seams); > 0
    double falloff_delay = 0.0;  // in [0, 1)
};

// Volumes validated and packed for the kernel; overlapping volumes combine
// by their maximum factor. Throws Error(InvalidArgument, ..., "volumes")
// naming volumes[i] and the field at fault.
class AmbientVolumes {
public:
    AmbientVolumes() = default;  // no volume: the factor is 0 everywhere
    explicit AmbientVolumes(const std::vector<AmbientVolume>& volumes);
    int count() const noexcept { return int(records_.size() / kFloats); }
    const std::vector<float>& records() const noexcept { return records_; }

    static constexpr std::size_t kFloats = 16;  // PN_AMBIENT_VOLUME_FLOATS (kernels/params.h)

private:
    std::vector<float> records_;
};

enum class ZeroNormals {
    Error,  // a zero normal is an Error naming the pixel
    Black,  // a zero normal (a pixel that sees no surface) gets irradiance 0
};

// What lights the pixels: the light rig alone, or blended towards a dark rig
// by the receivers' factor channel (no volumes) or by the volumes.
struct AmbientLighting {
    ShIrradiance light;
    std::optional<ShIrradiance> dark;
    AmbientVolumes volumes;  // used only with a dark rig
    bool cheap_dark = false; // the notes' cheaper dark: its first 4 coefficients only
    ZeroNormals zero_normals = ZeroNormals::Error;
};

// The receivers' channels the lighting needs: 3 (normal x, y, z) for the
// light rig alone; with a dark rig, 4 (normal, factor in [0, 1]) without
// volumes or 6 (normal, world position x, y, z) with them.
int ambient_receiver_channels(const AmbientLighting& lighting);

// Irradiance R, G, B per pixel (3 channels, the receivers' size). Throws
// Error(InvalidArgument, "ambient", "receivers") for the wrong channel
// count, Error(InvalidData, ..., "receivers") naming the first pixel with a
// non-finite value, a zero normal (unless ZeroNormals::Black) or a factor
// outside [0, 1].
Image ambient_irradiance(Context& context, const Image& receivers, const AmbientLighting& lighting);
void ambient_irradiance(Context& context, const Image& receivers, const AmbientLighting& lighting, Image& out);

// The ambient buffer: the volumes' factor (1 channel) at the world positions
// (3 channels); Error(InvalidData) names a non-finite position.
Image ambient_volume_factor(Context& context, const Image& positions, const AmbientVolumes& volumes);

}  // namespace penumbra
