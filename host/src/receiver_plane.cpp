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

struct Axis {
    double u, v, z;
    bool ok;
};

bool planar(double minus, double plus)
{
    return std::abs(plus - minus) <= kPlanarTolerance * std::max(std::abs(plus), std::abs(minus)) + kPlanarFloor;
}

// The derivatives of (u, v, z) at (x, y) along (dx, dy), one pixel a step.
Axis axis_derivative(const Image& rx, int x, int y, int dx, int dy)
{
    const bool has_minus = x - dx >= 0 && y - dy >= 0;
    const bool has_plus = x + dx < rx.width() && y + dy < rx.height();
    Axis a{0.0, 0.0, 0.0, has_minus || has_plus};
    double* out[3] = {&a.u, &a.v, &a.z};
    for (int c = 0; c < 3; ++c) {
        const double here = rx.at(c, x, y);
        const double minus = has_minus ? here - rx.at(c, x - dx, y - dy) : 0.0;
        const double plus = has_plus ? rx.at(c, x + dx, y + dy) - here : 0.0;
        if (has_minus && has_plus) {
            a.ok = a.ok && planar(minus, plus);
            *out[c] = 0.5 * (minus + plus);
        } else {
            *out[c] = has_minus ? minus : plus;
        }
    }
    a.ok = a.ok && std::isfinite(a.u) && std::isfinite(a.v) && std::isfinite(a.z);
    return a;
}

// Writes dz/du, dz/dv and the flag of pixel (x, y) into planes 3, 4, 5.
void solve_plane(const Image& rx, Image& out, int x, int y)
{
    const Axis ax = axis_derivative(rx, x, y, 1, 0), ay = axis_derivative(rx, x, y, 0, 1);
    const double det = ax.u * ay.v - ay.u * ax.v;
    const double scale = (std::abs(ax.u) + std::abs(ax.v)) * (std::abs(ay.u) + std::abs(ay.v));
    double dzdu = 0.0, dzdv = 0.0;
    bool ok = ax.ok && ay.ok && std::abs(det) > 1e-9 * scale && det != 0.0;
    if (ok) {
        dzdu = (ax.z * ay.v - ay.z * ax.v) / det;
        dzdv = (ay.z * ax.u - ax.z * ay.u) / det;
        ok = std::isfinite(float(dzdu)) && std::isfinite(float(dzdv));
    }
    out.at(PN_PCF_PLANE_DZDU, x, y) = ok ? float(dzdu) : 0.0f;
    out.at(PN_PCF_PLANE_DZDV, x, y) = ok ? float(dzdv) : 0.0f;
    out.at(PN_PCF_PLANE_OK, x, y) = ok ? 1.0f : 0.0f;
}

Image with_first_planes(const Image& receivers, int planes)
{
    Image out(receivers.width(), receivers.height(), PN_PCF_PLANES_WITH_DERIVATIVES);
    for (int c = 0; c < planes; ++c)
        for (int y = 0; y < receivers.height(); ++y)
            std::copy(receivers.row(c, y), receivers.row(c, y) + receivers.width(), out.row(c, y));
    return out;
}

}  // namespace

Image receivers_with_differences(const Image& receivers)
{
    Image out = with_first_planes(receivers, 3);
    tbb::parallel_for(tbb::blocked_range<int>(0, receivers.height(), 16), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < receivers.width(); ++x) solve_plane(receivers, out, x, y);
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
