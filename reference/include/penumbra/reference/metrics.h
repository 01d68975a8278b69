// Error metrics of a shadow estimate against the ground truth.
//
// Every metric takes one-channel images of one size: `estimate` (a method's
// visibility in [0, 1]) and `truth` (ground_truth), and an optional
// `mask` of the same size: a pixel counts where mask > 0.5 (the receivers'
// validity mask), every pixel when mask is null. Each throws
// Error(InvalidArgument) for empty images, a channel count other than 1 or a
// size mismatch, and Error(InvalidData) for a NaN or infinite value.
//
// When no pixel qualifies (an all-zero mask, or no pixel under a threshold)
// a metric returns 0: "no error observed", so a scene without dark regions
// reports no leaking rather than failing. Sums are taken in double.
#pragma once

#include <vector>

#include "penumbra/image.h"

namespace penumbra::reference {

// sqrt(mean((estimate - truth)^2)).
double rmse(const Image& estimate, const Image& truth, const Image* mask = nullptr);

// The 99th percentile of |estimate - truth| by the nearest-rank rule: the
// smallest error e such that at least 99% of the counted pixels have error <= e
// (the ceil(0.99 N)-th smallest).
double p99_abs_error(const Image& estimate, const Image& truth, const Image* mask = nullptr);

// Light leaking: mean of max(estimate - truth, 0) over the pixels whose truth
// is below 0.05 (in umbra, or nearly). A shadow that should be dark but is lit.
double light_leaking(const Image& estimate, const Image& truth, const Image* mask = nullptr);

// Over-darkening: mean of max(truth - estimate, 0) over the pixels whose truth
// is above 0.95 (lit, or nearly). Shadow where there should be light.
double over_darkening(const Image& estimate, const Image& truth, const Image* mask = nullptr);

// Flicker: for each pixel, the standard deviation over the K frames of
// e_k = estimate_k - truth_k (population form, divided by K), then the mean
// over pixels. The truth of each frame is rendered with that frame's light
// (flicker_frames), so only changes beyond the true change count.
// Needs K >= 2 frames; all images one size (the mask too).
double flicker(const std::vector<Image>& estimates, const std::vector<Image>& truths, const Image* mask = nullptr);

inline constexpr double kLeakingTruthBelow = 0.05;
inline constexpr double kOverDarkeningTruthAbove = 0.95;

}  // namespace penumbra::reference
