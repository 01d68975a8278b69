// Error metrics (definitions in penumbra/reference/metrics.h).
#include "penumbra/reference/metrics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "penumbra/error.h"

namespace penumbra::reference {
namespace {

std::string size_of(const Image& image)
{
    return std::to_string(image.width()) + "x" + std::to_string(image.height()) + "x" +
           std::to_string(image.channels());
}

void require_plane(const Image& image, const Image& reference, const char* operation, const char* what)
{
    require(!image.empty(), operation, std::string(what) + " is empty");
    require(image.channels() == 1, operation,
            std::string(what) + " must have 1 channel (got " + std::to_string(image.channels()) + ")");
    require(image.width() == reference.width() && image.height() == reference.height(), operation,
            std::string(what) + " is " + size_of(image) + " but the truth is " + size_of(reference) +
                "; pass images of one size");
    require_finite(image, operation, what);
}

void require_inputs(const Image& estimate, const Image& truth, const Image* mask, const char* operation)
{
    require_plane(truth, truth, operation, "truth");
    require_plane(estimate, truth, operation, "estimate");
    if (mask) require_plane(*mask, truth, operation, "mask");
}

bool counted(const Image* mask, int x, int y) { return !mask || mask->at(0, x, y) > 0.5f; }

// Calls f(estimate, truth) for every counted pixel.
template <class F>
void for_each_pixel(const Image& estimate, const Image& truth, const Image* mask, F&& f)
{
    for (int y = 0; y < truth.height(); ++y) {
        const float* e = estimate.row(0, y);
        const float* t = truth.row(0, y);
        for (int x = 0; x < truth.width(); ++x)
            if (counted(mask, x, y)) f(double(e[x]), double(t[x]));
    }
}

struct Mean {
    double sum = 0;
    long long count = 0;

    void add(double v) { sum += v, ++count; }
    double value() const { return count ? sum / double(count) : 0.0; }
};

}  // namespace

double rmse(const Image& estimate, const Image& truth, const Image* mask)
{
    require_inputs(estimate, truth, mask, "rmse");
    Mean squared;
    for_each_pixel(estimate, truth, mask, [&](double e, double t) { squared.add((e - t) * (e - t)); });
    return std::sqrt(squared.value());
}

double p99_abs_error(const Image& estimate, const Image& truth, const Image* mask)
{
    require_inputs(estimate, truth, mask, "p99_abs_error");
    std::vector<double> errors;
    for_each_pixel(estimate, truth, mask, [&](double e, double t) { errors.push_back(std::fabs(e - t)); });
    if (errors.empty()) return 0;
    // Nearest rank: the ceil(0.99 N)-th smallest, index ceil(0.99 N) - 1. N * 99
    // is exact in integers, so the rank is too.
    const std::size_t rank = (errors.size() * 99 + 99) / 100;
    const auto nth = errors.begin() + std::ptrdiff_t(rank - 1);
    std::nth_element(errors.begin(), nth, errors.end());
    return *nth;
}

double light_leaking(const Image& estimate, const Image& truth, const Image* mask)
{
    require_inputs(estimate, truth, mask, "light_leaking");
    Mean leak;
    for_each_pixel(estimate, truth, mask, [&](double e, double t) {
        if (t < kLeakingTruthBelow) leak.add(std::fmax(e - t, 0.0));
    });
    return leak.value();
}

double over_darkening(const Image& estimate, const Image& truth, const Image* mask)
{
    require_inputs(estimate, truth, mask, "over_darkening");
    Mean dark;
    for_each_pixel(estimate, truth, mask, [&](double e, double t) {
        if (t > kOverDarkeningTruthAbove) dark.add(std::fmax(t - e, 0.0));
    });
    return dark.value();
}

double flicker(const std::vector<Image>& estimates, const std::vector<Image>& truths, const Image* mask)
{
    require(estimates.size() == truths.size(), "flicker",
            "need one truth per estimate (got " + std::to_string(estimates.size()) + " estimates and " +
                std::to_string(truths.size()) + " truths)");
    require(estimates.size() >= 2, "flicker",
            "need at least 2 frames (got " + std::to_string(estimates.size()) + ")");
    for (std::size_t k = 0; k < estimates.size(); ++k) {
        require_inputs(estimates[k], truths[k], nullptr, "flicker");
        require_plane(truths[k], truths[0], "flicker", "a frame's truth");
    }
    if (mask) require_plane(*mask, truths[0], "flicker", "mask");
    const double frames = double(estimates.size());
    Mean deviation;
    for (int y = 0; y < truths[0].height(); ++y)
        for (int x = 0; x < truths[0].width(); ++x) {
            if (!counted(mask, x, y)) continue;
            // Two-pass (mean, then squared deviations): no cancellation in double.
            double mean = 0;
            for (std::size_t k = 0; k < estimates.size(); ++k)
                mean += double(estimates[k].at(0, x, y)) - double(truths[k].at(0, x, y));
            mean /= frames;
            double variance = 0;
            for (std::size_t k = 0; k < estimates.size(); ++k) {
                const double d = double(estimates[k].at(0, x, y)) - double(truths[k].at(0, x, y)) - mean;
                variance += d * d;
            }
            deviation.add(std::sqrt(variance / frames));
        }
    return deviation.value();
}

}  // namespace penumbra::reference
