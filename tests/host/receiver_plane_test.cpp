// The receivers' derivative planes (host/src/receiver_plane.cpp): exact on a
// plane seen through an affine map, the plane flag at a depth step, at the
// grid's edges and one-pixel grids, and the channels' path.
#include "receiver_plane.h"

#include <gtest/gtest.h>

#include "kernels/params.h"

namespace penumbra {
namespace {

// Receivers of the plane z = z0 + a u + b v seen through u = u0 + p x + q y,
// v = v0 + r x + s y: every finite difference is exact (up to rounding).
Image affine_plane(int width, int height, double a, double b)
{
    Image rx(width, height, 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double u = 0.1 + 0.01 * x + 0.002 * y, v = 0.2 - 0.003 * x + 0.015 * y;
            rx.at(0, x, y) = float(u);
            rx.at(1, x, y) = float(v);
            rx.at(2, x, y) = float(0.3 + a * u + b * v);
        }
    return rx;
}

TEST(ReceiverPlane, FiniteDifferencesRecoverThePlanesSlopes)
{
    for (const auto& [w, h] : {std::pair{7, 3}, std::pair{2, 2}, std::pair{33, 17}}) {
        const Image out = detail::receivers_with_differences(affine_plane(w, h, 0.4, -0.25));
        ASSERT_EQ(out.channels(), PN_PCF_PLANES_WITH_DERIVATIVES);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                EXPECT_EQ(out.at(PN_PCF_PLANE_OK, x, y), 1.0f) << x << "," << y;
                EXPECT_NEAR(out.at(PN_PCF_PLANE_DZDU, x, y), 0.4, 2e-4) << x << "," << y;
                EXPECT_NEAR(out.at(PN_PCF_PLANE_DZDV, x, y), -0.25, 2e-4) << x << "," << y;
            }
    }
}

// A step in depth between columns 3 and 4: the receivers on either side of it
// (whose central differences straddle it) fall back; the others keep the plane.
TEST(ReceiverPlane, ADepthStepFallsBackToTheConstantBias)
{
    Image rx = affine_plane(9, 5, 0.4, -0.25);
    for (int y = 0; y < 5; ++y)
        for (int x = 4; x < 9; ++x) rx.at(2, x, y) += 0.2f;
    const Image out = detail::receivers_with_differences(rx);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 9; ++x) {
            const bool straddles = x == 3 || x == 4;
            EXPECT_EQ(out.at(PN_PCF_PLANE_OK, x, y), straddles ? 0.0f : 1.0f) << x << "," << y;
        }
}

TEST(ReceiverPlane, AOnePixelGridHasNoPlane)
{
    for (const auto& [w, h] : {std::pair{1, 1}, std::pair{1, 5}, std::pair{6, 1}}) {
        const Image out = detail::receivers_with_differences(affine_plane(w, h, 0.4, -0.25));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                EXPECT_EQ(out.at(PN_PCF_PLANE_OK, x, y), 0.0f);
                EXPECT_EQ(out.at(PN_PCF_PLANE_DZDU, x, y), 0.0f);
            }
    }
}

// All receivers at one (u, v): J is singular (the surface edge-on to the light).
TEST(ReceiverPlane, ASingularJacobianHasNoPlane)
{
    Image rx(4, 4, 3);
    rx.fill(0, 0.5f);
    rx.fill(1, 0.5f);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) rx.at(2, x, y) = 0.1f * float(x + y);
    const Image out = detail::receivers_with_differences(rx);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) EXPECT_EQ(out.at(PN_PCF_PLANE_OK, x, y), 0.0f);
}

TEST(ReceiverPlane, ChannelsAreCopiedWithTheFlagSet)
{
    Image rx(3, 2, 5);
    for (int c = 0; c < 5; ++c) rx.fill(c, 0.1f * float(c + 1));
    const Image out = detail::receivers_with_channels(rx);
    for (int c = 0; c < 5; ++c) EXPECT_EQ(out.at(c, 2, 1), 0.1f * float(c + 1));
    EXPECT_EQ(out.at(PN_PCF_PLANE_OK, 2, 1), 1.0f);
}

}  // namespace
}  // namespace penumbra
