// The cross-bilateral filter against OpenCV's cv::ximgproc::jointBilateralFilter
// with identical parameters, on every backend, where OpenCV (contrib) is
// installed; elsewhere the test is skipped and says why.
//
// How OpenCV weighs (opencv_contrib, modules/ximgproc/src/
// joint_bilateral_filter.cpp, 32-bit float images): radius = d / 2; the taps
// are the disk i^2 + j^2 <= radius^2; the spatial weight is
// exp(-r^2 / (2 sigmaSpace^2)) in double; the range weight is
// exp(-delta^2 / (2 sigmaColor^2)) on the L1 guide difference (the absolute
// difference for a 1-channel guide), read from a table of 4096 bins over the
// guide's range with linear interpolation; the border is copyMakeBorder's
// (BORDER_REPLICATE is clamp-to-edge); the result is sum w m / sum w in float.
// Its flat-guide shortcut (max - min < FLT_EPSILON: a square GaussianBlur) is
// avoided here by a guide with structure. So penumbra's options are: radius,
// spatial_sigma = sigmaSpace, absolute Gaussian range with depth_sigma =
// sigmaColor, disk window.
//
// Tolerance: OpenCV's table interpolates exp(-x^2 / (2 s^2)) with a step h =
// range / 4096, an error of at most h^2 / (8 s^2) (the second derivative is
// at most 1 / s^2): 1e-6 for a range of 0.5 and s = 0.05; penumbra's weights
// are within 6e-6 relative (tests/kernels/bilateral_test.cpp); both sum in float.
// The normalised results then differ by less than 2 (1e-6 + 6e-6) plus the
// float sums: 3e-5 for masks in [0, 1].
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "support/bilateral_reference.h"
#include "penumbra/bilateral.h"
#include "support/backends.h"

#ifdef PENUMBRA_HAVE_OPENCV_XIMGPROC
#include <opencv2/core.hpp>
#include <opencv2/ximgproc/edge_filter.hpp>
#endif

namespace penumbra {
namespace {

using testing::backend_names;
using testing::backend_test_name;

class BilateralOpenCvTest : public ::testing::TestWithParam<std::string> {};

#ifdef PENUMBRA_HAVE_OPENCV_XIMGPROC
constexpr double kOpenCvTolerance = 3e-5;

// OpenCV's result for channels [first, first + count) of `mask` (count 1 or 3).
Image opencv_filter(const Image& mask, int first, int count, const Image& guide, int radius, float sigma_space,
                    float sigma_color)
{
    const int w = mask.width(), h = mask.height();
    const cv::Mat joint(h, w, CV_32F, const_cast<float*>(guide.plane(0)), std::size_t(guide.pitch()) * 4);
    std::vector<cv::Mat> planes;
    for (int c = first; c < first + count; ++c)
        planes.emplace_back(h, w, CV_32F, const_cast<float*>(mask.plane(c)), std::size_t(mask.pitch()) * 4);
    cv::Mat src, dst;
    cv::merge(planes, src);
    cv::ximgproc::jointBilateralFilter(joint, src, dst, 2 * radius + 1, sigma_color, sigma_space,
                                       cv::BORDER_REPLICATE);
    std::vector<cv::Mat> out_planes;
    cv::split(dst, out_planes);
    Image out(w, h, count);
    for (int c = 0; c < count; ++c)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) out.at(c, x, y) = out_planes[std::size_t(c)].at<float>(y, x);
    return out;
}
#endif

PN_BACKEND_TEST(BilateralOpenCvTest, MatchesJointBilateralFilter)
{
#ifdef PENUMBRA_HAVE_OPENCV_XIMGPROC
    Context& ctx = PN_CONTEXT_OR_SKIP(backend);
    struct Case {
        int w, h, radius;
        float sigma_space, sigma_color;
    };
    const Case cases[] = {{61, 37, 2, 1.5f, 0.05f}, {45, 29, 1, 1.0f, 0.02f}, {52, 33, 3, 2.0f, 0.1f},
                          {17, 5, 2, 1.5f, 0.05f}};
    for (const Case& k : cases) {
        const Image guide = testing::structured_guide(k.w, k.h, 31);
        const Image mask = testing::random_mask(k.w, k.h, 4, 32);
        BilateralOptions o;
        o.radius = k.radius;
        o.spatial_sigma = k.sigma_space;
        o.depth_sigma = k.sigma_color;
        o.relative = false;
        o.window = BilateralWindow::Disk;
        const Image ours = cross_bilateral(ctx, mask, guide, o);
        // OpenCV takes 1 or 3 channels: channel 0 alone, then channels 1-3 together.
        const Image one = opencv_filter(mask, 0, 1, guide, k.radius, k.sigma_space, k.sigma_color);
        const Image three = opencv_filter(mask, 1, 3, guide, k.radius, k.sigma_space, k.sigma_color);
        double worst = 0.0;
        for (int y = 0; y < k.h; ++y)
            for (int x = 0; x < k.w; ++x) {
                worst = std::max(worst, double(std::fabs(ours.at(0, x, y) - one.at(0, x, y))));
                for (int c = 1; c < 4; ++c)
                    worst = std::max(worst, double(std::fabs(ours.at(c, x, y) - three.at(c - 1, x, y))));
            }
        EXPECT_LE(worst, kOpenCvTolerance) << k.w << "x" << k.h << " radius " << k.radius;
        if (backend == "scalar" && k.radius == 2 && k.w == 61)
            std::cout << "[ opencv   ] largest |penumbra - cv::ximgproc::jointBilateralFilter|: " << worst << "\n";
    }
#else
    GTEST_SKIP() << "OpenCV's ximgproc (Debian libopencv-contrib-dev) is not installed; the comparison with "
                    "cv::ximgproc::jointBilateralFilter does not run here";
#endif
}

INSTANTIATE_TEST_SUITE_P(Backends, BilateralOpenCvTest, ::testing::ValuesIn(backend_names()), backend_test_name);

}  // namespace
}  // namespace penumbra
