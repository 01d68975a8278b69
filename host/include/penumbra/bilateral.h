// Cross (joint) bilateral blur of shadow and occlusion masks, guided by depth
// and optionally normals: a blur that stops at depth edges instead of bleeding
// across them (kernels/bilateral.h has the formulas; docs/bilateral.md the
// measured accuracy and speed).
//
// mask: 1 to 4 channels, all filtered with the same weights (e.g. a shadow
// mask, a character shadow and SSAO together, as the Toy Story 3 game did).
// guide_depth: 1 channel of the mask's size, finite depths in any unit.
// guide_normals (optional): 3 channels (x, y, z) of unit normals, same size.
// Output: the mask's size and channels. Taps outside the image are clamped to
// the border. Bad input throws penumbra::Error naming the parameter.
#pragma once

#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/image_view.h"

namespace penumbra {

enum class BilateralRange {
    Gaussian,   // exp(-d^2 / (2 depth_sigma^2)): OpenCV's jointBilateralFilter when absolute
    Threshold,  // keep |d| <= depth_threshold, drop the rest: the Toy Story 3 filter
};

enum class BilateralWindow {
    Square,  // every tap with |dx|, |dy| <= radius
    Disk,    // dx^2 + dy^2 <= radius^2, as OpenCV's jointBilateralFilter
};

inline constexpr int kBilateralMaxRadius = 32;   // a 65x65 window; blur a smaller mip for more
inline constexpr int kBilateralMaxChannels = 4;

struct BilateralOptions {
    int radius = 2;                                  // in [0, 32]; 2 is the 5x5 filter
    float spatial_sigma = 1.5f;                      // pixels, > 0
    BilateralRange range = BilateralRange::Gaussian;
    // The depth difference d: relative = (z_q - z_p) / |z_p|, a fraction of
    // the centre depth, right for perspective (view-space) depth; absolute =
    // z_q - z_p, in the guide's units (OpenCV's definition).
    bool relative = true;
    float depth_sigma = 0.05f;                       // Gaussian range, > 0 (units of d)
    float depth_threshold = 0.05f;                   // Threshold range, >= 0 (units of d)
    BilateralWindow window = BilateralWindow::Square;
    // Horizontal then vertical pass, each with its own depth test: 2(2r+1)
    // taps instead of (2r+1)^2, exact on flat depth, approximate across edges
    // (docs/bilateral.md). Square window only.
    bool separable = false;
    float normal_sigma = 0.5f;                       // with normals: exp(-|n_q - n_p|^2 / (2 sigma^2)), > 0
};

Image cross_bilateral(Context& context, const Image& mask, const Image& guide_depth,
                      const BilateralOptions& options = {}, const Image* guide_normals = nullptr);

// The same into an existing image of the mask's size and channels (not the
// mask itself): no allocation, for per-frame use.
void cross_bilateral(Context& context, const Image& mask, const Image& guide_depth, const BilateralOptions& options,
                     Image& out, const Image* guide_normals = nullptr);

// The same on views of the caller's memory (penumbra/image_view.h): read and
// written in place where the layout allows (planar float32), else one copy
// in and one out (an interleaved RGBA mask, say). `out` must not overlap an
// input. Errors name the parameters "mask", "guide-depth", "guide-normals", "out".
void cross_bilateral(Context& context, const ImageView& mask, const ImageView& guide_depth,
                     const BilateralOptions& options, const MutableImageView& out,
                     const ImageView* guide_normals = nullptr);

}  // namespace penumbra
