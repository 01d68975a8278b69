// A rig's projection onto spherical harmonics, its blend and evaluation
// (penumbra/ambient.h). A directional light is a delta of radiance, so its
// projection is the basis at its direction: L_i = colour x intensity x Y_i(l);
// the irradiance coefficients are E_i = A_l w_l L_i with the clamped cosine's
// convolution constants A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4 (Ramamoorthi &
// Hanrahan 2001, eq. 8 and 9) and w_l the window (1 without).
#include <cmath>
#include <numbers>
#include <string>

#include "ambient_weights.h"
#include "penumbra/ambient.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

constexpr double kPi = std::numbers::pi;

// The constants of the real SH basis to order 2, in the order l(l + 1) + m:
// sqrt((2l + 1) / 4 pi (l - |m|)! / (l + |m|)!) times the associated
// Legendre factor, for the polynomials of sh_basis.
const std::array<double, 9>& basis_constants()
{
    static const double k1 = std::sqrt(3.0 / (4.0 * kPi)), k2 = 0.5 * std::sqrt(15.0 / kPi);
    static const std::array<double, 9> k = {0.5 * std::sqrt(1.0 / kPi), k1, k1, k1, k2, k2,
                                            0.25 * std::sqrt(5.0 / kPi), k2, 0.25 * std::sqrt(15.0 / kPi)};
    return k;
}

// The basis at the unit vector (x, y, z): constant times (1, y, z, x, xy, yz,
// 3z^2 - 1, xz, x^2 - y^2). Keep in sync with ambient_basis (kernels/ambient_sh.h).
std::array<double, 9> sh_basis(double x, double y, double z)
{
    const std::array<double, 9>& k = basis_constants();
    return {k[0],         k[1] * y,     k[2] * z, k[3] * x, k[4] * x * y, k[5] * y * z, k[6] * (3.0 * z * z - 1.0),
            k[7] * x * z, k[8] * (x * x - y * y)};
}

int band_of(int i) { return i == 0 ? 0 : i < 4 ? 1 : 2; }

double window_weight(ShWindow window, int band, double width)
{
    const double t = double(band) / width;
    switch (window) {
    case ShWindow::Hanning: return 0.5 * (1.0 + std::cos(kPi * t));
    case ShWindow::Lanczos: return band == 0 ? 1.0 : std::sin(kPi * t) / (kPi * t);
    case ShWindow::None: break;
    }
    return 1.0;
}

bool finite(AmbientVector v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

double length(AmbientVector v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

AmbientVector unit(AmbientVector v)
{
    const double n = length(v);
    return {v.x / n, v.y / n, v.z / n};
}

void check_rig(const AmbientRig& rig, const std::string& op)
{
    require(!rig.lights.empty(), op, "rig", "the rig has no lights; give it at least one directional light");
    for (std::size_t i = 0; i < rig.lights.size(); ++i) {
        const AmbientLight& l = rig.lights[i];
        const std::string name = "lights[" + std::to_string(i) + "].";
        require(finite(l.direction), op, "rig", name + "direction is not finite");
        require(length(l.direction) > 0.0, op, "rig", name + "direction is zero; give the direction the light comes from");
        require(finite(l.color), op, "rig", name + "color is not finite");
        require(std::isfinite(l.intensity), op, "rig", name + "intensity is not finite");
    }
}

double channel(AmbientVector v, int c) { return c == 0 ? v.x : c == 1 ? v.y : v.z; }

}  // namespace

ShIrradiance project_rig(const AmbientRig& rig, const ShOptions& options)
{
    const std::string op = "project_rig";
    require(options.order == 1 || options.order == 2, op, "order",
            "the SH order must be 1 (4 coefficients) or 2 (9), got " + std::to_string(options.order));
    require(options.window == ShWindow::None || (std::isfinite(options.window_width) && options.window_width > options.order),
            op, "window_width", "the window's width must be finite and > the order (" + std::to_string(options.order) + ")");
    check_rig(rig, op);
    const int terms = (options.order + 1) * (options.order + 1);
    const double convolution[3] = {kPi, 2.0 * kPi / 3.0, kPi / 4.0};
    ShIrradiance sh;
    sh.order = options.order;
    for (const AmbientLight& light : rig.lights) {
        const AmbientVector d = unit(light.direction);
        const std::array<double, 9> y = sh_basis(d.x, d.y, d.z);
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < terms; ++i) sh.coefficients[c][i] += channel(light.color, c) * light.intensity * y[i];
    }
    for (int i = 0; i < terms; ++i) {
        const int l = band_of(i);
        const double scale = convolution[l] * window_weight(options.window, l, options.window_width);
        for (int c = 0; c < 3; ++c) sh.coefficients[c][i] *= scale;
    }
    return sh;
}

ShIrradiance blend_rigs(const ShIrradiance& a, const ShIrradiance& b, double t)
{
    const std::string op = "blend_rigs";
    require(std::isfinite(t) && t >= 0.0 && t <= 1.0, op, "t", "the blend factor must be in [0, 1]");
    require(a.order == b.order, op, "b", "the rigs have orders " + std::to_string(a.order) + " and " +
                                             std::to_string(b.order) + "; project both to the same order");
    ShIrradiance out;
    out.order = a.order;
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 9; ++i) out.coefficients[c][i] = (1.0 - t) * a.coefficients[c][i] + t * b.coefficients[c][i];
    return out;
}

std::array<double, 3> evaluate_irradiance(const ShIrradiance& sh, AmbientVector normal)
{
    const AmbientVector n = unit(normal);
    const std::array<double, 9> y = sh_basis(n.x, n.y, n.z);
    std::array<double, 3> e{};
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 9; ++i) e[c] += sh.coefficients[c][i] * y[i];
    return e;
}

std::array<double, 3> exact_irradiance(const AmbientRig& rig, AmbientVector normal)
{
    const AmbientVector n = unit(normal);
    std::array<double, 3> e{};
    for (const AmbientLight& light : rig.lights) {
        const AmbientVector d = unit(light.direction);
        const double cosine = std::max(0.0, n.x * d.x + n.y * d.y + n.z * d.z);
        for (int c = 0; c < 3; ++c) e[c] += channel(light.color, c) * light.intensity * cosine;
    }
    return e;
}

namespace detail {

void polynomial_weights(const ShIrradiance& sh, float* weights)
{
    const std::array<double, 9>& k = basis_constants();
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 9; ++i) weights[c * 9 + i] = float(sh.coefficients[c][i] * k[i]);
}

}  // namespace detail

}  // namespace penumbra
