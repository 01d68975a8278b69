// Finite differences of the receivers for the receiver-plane depth bias
// (Isidoro, "Receiver plane depth bias", GDC 2006), computed on the host once
// per call, before the lookup: a kernel reading its neighbours' receivers
// would gather three planes at four neighbours per receiver, for a plane that
// every method of the family needs and that stays the same across taps.
//
// On the receivers' grid (screen x, y) the chain rule gives
//     dz/dx = dz/du du/dx + dz/dv dv/dx,   dz/dy = dz/du du/dy + dz/dv dv/dy,
// so (dz/du, dz/dv) = J^-T (dz/dx, dz/dy) with J = [du/dx du/dy; dv/dx dv/dy]:
//     dz/du = (dz/dx dv/dy - dz/dy dv/dx) / det J,
//     dz/dv = (dz/dy du/dx - dz/dx du/dy) / det J.
// Each screen derivative is the central difference where both neighbours
// exist and pass the planar test (receiver_plane.h), the one-sided one at the
// grid's edge (no test is possible there). A grid one pixel wide or high, a
// failed test, a singular J (the surface seen edge-on from the light) or a
// non-finite value gives the plane flag 0: the constant bias.
#include "receiver_plane.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "kernels/params.h"

namespace penumbra::detail {
namespace {

// u, v, z of one receiver, in double (the differences are taken in double).
struct Texel {
    double c[3];
};

struct Axis {
    double u, v, z;
    bool ok;
};

bool planar(double minus, double plus)
{
    return std::abs(plus - minus) <= kPlanarTolerance * std::max(std::abs(plus), std::abs(minus)) + kPlanarFloor;
}

// The derivatives of (u, v, z) at `here` along one axis, one pixel a step,
// from its neighbours on that axis (null where the grid ends).
Axis axis_derivative(const Texel& here, const Texel* minus_side, const Texel* plus_side)
{
    Axis a{0.0, 0.0, 0.0, minus_side || plus_side};
    double* out[3] = {&a.u, &a.v, &a.z};
    for (int c = 0; c < 3; ++c) {
        const double minus = minus_side ? here.c[c] - minus_side->c[c] : 0.0;
        const double plus = plus_side ? plus_side->c[c] - here.c[c] : 0.0;
        if (minus_side && plus_side) {
            a.ok = a.ok && planar(minus, plus);
            *out[c] = 0.5 * (minus + plus);
        } else {
            *out[c] = minus_side ? minus : plus;
        }
    }
    a.ok = a.ok && std::isfinite(a.u) && std::isfinite(a.v) && std::isfinite(a.z);
    return a;
}

// The plane (dz/du, dz/dv, flag) from the two screen axes' derivatives.
void solve_plane(const Axis& ax, const Axis& ay, float& dzdu_out, float& dzdv_out, float& ok_out)
{
    const double det = ax.u * ay.v - ay.u * ax.v;
    const double scale = (std::abs(ax.u) + std::abs(ax.v)) * (std::abs(ay.u) + std::abs(ay.v));
    double dzdu = 0.0, dzdv = 0.0;
    bool ok = ax.ok && ay.ok && std::abs(det) > 1e-9 * scale && det != 0.0;
    if (ok) {
        dzdu = (ax.z * ay.v - ay.z * ax.v) / det;
        dzdv = (ay.z * ax.u - ax.z * ay.u) / det;
        ok = std::isfinite(float(dzdu)) && std::isfinite(float(dzdv));
    }
    dzdu_out = ok ? float(dzdu) : 0.0f;
    dzdv_out = ok ? float(dzdv) : 0.0f;
    ok_out = ok ? 1.0f : 0.0f;
}

// One grid row's u, v, z, through row pointers: Image::at goes through the
// library's exported Image::plane (a PLT call per read), which with six
// reads per channel and axis made up most of this pass (perf: 1080p took
// 60-85 ms idle, axis_derivative and Image::plane@plt 60% of it).
struct Row {
    const float* c[3];
    Texel at(int x) const { return Texel{{c[0][x], c[1][x], c[2][x]}}; }
};

Row row_of(const Image& rx, int y) { return Row{{rx.row(0, y), rx.row(1, y), rx.row(2, y)}}; }

// Writes dz/du, dz/dv and the flag of row y into planes 3, 4, 5.
void solve_row(const Image& rx, Image& out, int y)
{
    const int w = rx.width(), h = rx.height();
    const Row here = row_of(rx, y);
    const Row above = row_of(rx, y > 0 ? y - 1 : y), below = row_of(rx, y + 1 < h ? y + 1 : y);
    float* dzdu = out.row(PN_PCF_PLANE_DZDU, y);
    float* dzdv = out.row(PN_PCF_PLANE_DZDV, y);
    float* ok = out.row(PN_PCF_PLANE_OK, y);
    for (int x = 0; x < w; ++x) {
        const Texel t = here.at(x);
        const Texel left = here.at(x > 0 ? x - 1 : x), right = here.at(x + 1 < w ? x + 1 : x);
        const Texel up = above.at(x), down = below.at(x);
        const Axis ax = axis_derivative(t, x > 0 ? &left : nullptr, x + 1 < w ? &right : nullptr);
        const Axis ay = axis_derivative(t, y > 0 ? &up : nullptr, y + 1 < h ? &down : nullptr);
        solve_plane(ax, ay, dzdu[x], dzdv[x], ok[x]);
    }
}

// Every pixel of the result is written (planes 0 .. `planes` - 1 copied, the
// rest by the caller), so the storage starts uninitialised (penumbra/image.h).
Image with_first_planes(const Image& receivers, int planes)
{
    Image out(receivers.width(), receivers.height(), PN_PCF_PLANES_WITH_DERIVATIVES, Image::Uninitialized{});
    tbb::parallel_for(tbb::blocked_range<int>(0, receivers.height(), 64), [&](const tbb::blocked_range<int>& rows) {
        for (int c = 0; c < planes; ++c)
            for (int y = rows.begin(); y < rows.end(); ++y)
                std::copy(receivers.row(c, y), receivers.row(c, y) + receivers.width(), out.row(c, y));
    });
    return out;
}

}  // namespace

Image receivers_with_differences(const Image& receivers)
{
    Image out = with_first_planes(receivers, 3);
    tbb::parallel_for(tbb::blocked_range<int>(0, receivers.height(), 16), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) solve_row(receivers, out, y);
    });
    return out;
}

Image receivers_with_channels(const Image& receivers)
{
    Image out = with_first_planes(receivers, 5);
    out.fill(PN_PCF_PLANE_OK, 1.0f);
    return out;
}

}  // namespace penumbra::detail
