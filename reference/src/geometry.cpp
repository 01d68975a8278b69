#include "penumbra/reference/geometry.h"

#include <numbers>

namespace penumbra::reference {

Basis basis_looking_along(Vec3 forward, Vec3 up)
{
    const Vec3 n = normalize(forward);
    // Gram-Schmidt: remove the forward part of `up`; fall back to a world axis
    // when too little is left for a stable direction.
    Vec3 up_orthogonal = up - n * dot(up, n);
    if (length(up_orthogonal) < 1e-6 * (length(up) + 1e-300)) {
        const Vec3 fallback = std::fabs(n.z) < 0.9 ? Vec3{0, 0, -1} : Vec3{0, 1, 0};
        up_orthogonal = fallback - n * dot(fallback, n);
    }
    const Vec3 t = -normalize(up_orthogonal);
    // s = t x n makes (s, t, n) right-handed: (t x n) x t = n (t.t) - t (n.t) = n.
    const Vec3 s = cross(t, n);
    return {s, t, n};
}

Rotation rotation_from_euler_degrees(Vec3 degrees)
{
    constexpr double to_radians = std::numbers::pi / 180.0;
    const double ca = std::cos(degrees.x * to_radians), sa = std::sin(degrees.x * to_radians);
    const double cb = std::cos(degrees.y * to_radians), sb = std::sin(degrees.y * to_radians);
    const double cc = std::cos(degrees.z * to_radians), sc = std::sin(degrees.z * to_radians);
    // Columns of Rz * Ry * Rx, written out.
    Rotation r;
    r.x = {cc * cb, sc * cb, -sb};
    r.y = {cc * sb * sa - sc * ca, sc * sb * sa + cc * ca, cb * sa};
    r.z = {cc * sb * ca + sc * sa, sc * sb * ca - cc * sa, cb * ca};
    return r;
}

}  // namespace penumbra::reference
