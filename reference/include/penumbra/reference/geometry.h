// Double-precision vectors, bases and rotations for the reference scenes.
//
// The reference side (scenes, ray casting, ground truth) works in double
// precision throughout: its answers are the truth that float kernels are
// measured against, so its own rounding must stay far below theirs.
//
// World frame: right-handed, y up, units are metres by convention only.
#pragma once

#include <cmath>

namespace penumbra::reference {

struct Vec3 {
    double x = 0, y = 0, z = 0;
    friend bool operator==(const Vec3&, const Vec3&) = default;
};

constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(Vec3 a, double k) { return {a.x * k, a.y * k, a.z * k}; }
constexpr Vec3 operator*(double k, Vec3 a) { return a * k; }
constexpr Vec3 operator/(Vec3 a, double k) { return {a.x / k, a.y / k, a.z / k}; }

constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
// Callers guarantee a non-zero vector (scene validation rejects zero normals).
inline Vec3 normalize(Vec3 a) { return a / length(a); }
inline Vec3 abs(Vec3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
inline double max_component(Vec3 a) { return std::fmax(a.x, std::fmax(a.y, a.z)); }
inline double max_abs_component(Vec3 a) { return max_component(abs(a)); }

// A ray o + t * d. The direction need not be of unit length: intersection
// routines report t in units of |d|, which lets a caller choose what t means
// (a depth along an axis, or the fraction of a segment).
struct Ray {
    Vec3 origin, direction;

    Vec3 at(double t) const { return origin + direction * t; }
};

// A right-handed orthonormal basis (s, t, n) with s x t = n. It is the frame
// of the light and of the view camera: s points right, t points down and n
// forward, the image convention (columns grow along s, rows along t).
struct Basis {
    Vec3 s, t, n;

    Vec3 to_local(Vec3 v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3 to_world(Vec3 local) const { return s * local.x + t * local.y + n * local.z; }
};

// The basis looking along `forward` whose "down" axis t is opposite to the
// part of `up` orthogonal to `forward`. When `up` is (nearly) parallel to
// `forward`, world -z (or +y, when forward is along z) stands in, so the result
// is always defined for a non-zero `forward`.
Basis basis_looking_along(Vec3 forward, Vec3 up);

// A rotation given by the images of the local axes (the columns of its matrix).
struct Rotation {
    Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};

    Vec3 apply(Vec3 local) const { return x * local.x + y * local.y + z * local.z; }
    Vec3 apply_inverse(Vec3 world) const { return {dot(world, x), dot(world, y), dot(world, z)}; }
};

// R = Rz(c) * Ry(b) * Rx(a) for angles (a, b, c) in degrees: a local point is
// turned about the world x axis first, then y, then z.
Rotation rotation_from_euler_degrees(Vec3 degrees);

}  // namespace penumbra::reference
