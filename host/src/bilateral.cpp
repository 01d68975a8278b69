// Host operation cross_bilateral(): validate, fill BilateralParams and the
// spatial weights, dispatch, and report any non-finite input the kernels flag.
#include "penumbra/bilateral.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "bilateral_setup.h"
#include "host/backend/backend.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

const std::string kBilateralOp = "cross_bilateral";

// Largest scale the kernel multiplies a difference by (PN_BILATERAL_MAX_SCALE):
// keeps 0 * scale at 0 for the tiniest sigmas.
constexpr double kMaxScale = 1e30;

std::string size_text(const Image& image)
{
    return std::to_string(image.width()) + "x" + std::to_string(image.height());
}

void check_images(const Image& mask, const Image& guide, const Image* normals)
{
    require(!mask.empty(), kBilateralOp, "the mask is empty (0 pixels)");
    require(mask.channels() <= kBilateralMaxChannels, kBilateralOp,
            "the mask has " + std::to_string(mask.channels()) +
                " channels; the filter takes 1 to 4 (filter the others in a second call)");
    require(guide.channels() == 1, kBilateralOp,
            "the guide depth must have 1 channel, got " + std::to_string(guide.channels()));
    require(guide.width() == mask.width() && guide.height() == mask.height(), kBilateralOp,
            "the guide depth is " + size_text(guide) + " but the mask is " + size_text(mask) +
                "; they must have the same size");
    if (!normals) return;
    require(normals->channels() == 3, kBilateralOp,
            "the guide normals must have 3 channels (x, y, z), got " + std::to_string(normals->channels()));
    require(normals->width() == mask.width() && normals->height() == mask.height(), kBilateralOp,
            "the guide normals are " + size_text(*normals) + " but the mask is " + size_text(mask) +
                "; they must have the same size");
}

void check_positive(float value, const std::string& name)
{
    require(std::isfinite(value) && value > 0.0f, kBilateralOp,
            name + " must be a finite value > 0 (got " + std::to_string(value) + ")");
}

void check_options(const BilateralOptions& o)
{
    require(o.radius >= 0 && o.radius <= kBilateralMaxRadius, kBilateralOp,
            "radius must be in [0, " + std::to_string(kBilateralMaxRadius) + "] (got " + std::to_string(o.radius) +
                "); for a wider blur, filter a downsampled mask");
    check_positive(o.spatial_sigma, "spatial_sigma");
    check_positive(o.depth_sigma, "depth_sigma");
    check_positive(o.normal_sigma, "normal_sigma");
    require(std::isfinite(o.depth_threshold) && o.depth_threshold >= 0.0f, kBilateralOp,
            "depth_threshold must be a finite value >= 0 (got " + std::to_string(o.depth_threshold) + ")");
    require(!(o.separable && o.window == BilateralWindow::Disk), kBilateralOp,
            "the separable schedule filters a square window; use window = Square or separable = false");
}

void check_output(const Image& mask, const Image& guide, const Image* normals, const Image& out)
{
    require(out.width() == mask.width() && out.height() == mask.height() && out.channels() == mask.channels(),
            kBilateralOp,
            "the output must be a " + std::to_string(mask.channels()) + "-channel image of the mask's size (" +
                size_text(mask) + ")");
    const bool aliased = out.plane(0) == mask.plane(0) || out.plane(0) == guide.plane(0) ||
                         (normals && out.plane(0) == normals->plane(0));
    require(!aliased, kBilateralOp,
            "the output must not be the mask or a guide image (the filter reads its neighbours)");
}

BilateralParams make_params(pn_dims mask, int channels, pn_dims guide, const pn_dims* normals, pn_dims out,
                            const BilateralOptions& o)
{
    BilateralParams p{};
    p.mask = mask;
    p.guide = guide;
    p.normals = normals ? *normals : guide;
    p.out = out;
    p.pass = p.out;
    p.channels = channels;
    p.radius = o.radius;
    p.threshold = o.range == BilateralRange::Threshold;
    p.relative = o.relative;
    p.use_normals = normals != nullptr;
    // exp(-d^2 / (2 sigma^2)) = 2^-(d sqrt(log2(e) / 2) / sigma)^2: the kernel
    // squares one scaled difference and takes a base-2 exponential.
    const double log2e = 1.0 / std::log(2.0);
    p.depth_scale = float(std::min(std::sqrt(log2e / 2.0) / o.depth_sigma, kMaxScale));
    p.depth_threshold = o.depth_threshold;
    p.normal_scale = float(std::min(log2e / (2.0 * double(o.normal_sigma) * o.normal_sigma), kMaxScale));
    return p;
}

// After a flagged run: names the first non-finite value, guide first.
void report_non_finite(const Image& mask, const Image& guide, const Image* normals)
{
    require_finite(guide, kBilateralOp, "the guide depth");
    if (normals) require_finite(*normals, kBilateralOp, "the guide normals");
    require_finite(mask, kBilateralOp, "the mask");
}

// The window as the kernels read it: offsets (dx, dy), and per tap the
// spatial weight exp(-(dx^2 + dy^2) / (2 sigma^2)) and its base-2 exponent
// (dx^2 + dy^2) log2(e) / (2 sigma^2), in double rounded to float. Taps whose
// weight is below 2^-60 are left out, as the kernel floors its weights there
// (PN_BILATERAL_CUT). The centre tap (weight 1) is always in. Separable: the
// 1D taps as (d, d).
struct Window {
    std::vector<int> taps;
    std::vector<float> weights;

    void add(int dx, int dy, int r2, double coeff)
    {
        const double exponent = -r2 * coeff / std::log(2.0);
        if (exponent > 60.0) return;
        taps.push_back(dx);
        taps.push_back(dy);
        weights.push_back(float(std::exp2(-exponent)));
        weights.push_back(float(exponent));
    }
};

Window window_of(const BilateralOptions& o)
{
    const int r = o.radius;
    const double coeff = -0.5 / (double(o.spatial_sigma) * o.spatial_sigma);
    Window window;
    if (o.separable) {
        for (int d = -r; d <= r; ++d) window.add(d, d, d * d, coeff);
        return window;
    }
    for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
            const int r2 = dx * dx + dy * dy;
            if (o.window == BilateralWindow::Square || r2 <= r * r) window.add(dx, dy, r2, coeff);
        }
    return window;
}

// The kernels sum w m over the window in float: with |m| near FLT_MAX (a
// finite mask of 3e38) the sums overflow to Inf although the weighted mean,
// which lies between the mask's extremes, is finite. Masks whose largest
// magnitude exceeds 2^100 are therefore filtered scaled by 2^-k, which is exact
// (a power of two), so that the peak is at most 2^100 and a sum of up to 2^27
// taps with weights <= 1 stays below FLT_MAX; the result is scaled back by 2^k.
// Float rounding can put a mean an ulp beyond the peak, so the scaled-back
// result is clamped to +-FLT_MAX. (Magnitudes below 2^-149 * 2^k are lost in
// such a mask: its dynamic range exceeds float's anyway.)
constexpr int kSafePeakExponent = 100;

int overflow_guard_exponent(const Image& mask)
{
    float peak = 0.0f;
    for (int c = 0; c < mask.channels(); ++c)
        for (int y = 0; y < mask.height(); ++y) {
            const float* row = mask.row(c, y);
            for (int x = 0; x < mask.width(); ++x) peak = std::max(peak, std::abs(row[x]));
        }
    if (!(peak > std::ldexp(1.0f, kSafePeakExponent)) || !std::isfinite(peak)) return 0;
    return std::ilogb(peak) - kSafePeakExponent + 1;
}

void scale_image(Image& image, int exponent, bool clamp)
{
    for (int c = 0; c < image.channels(); ++c)
        for (int y = 0; y < image.height(); ++y) {
            float* row = image.row(c, y);
            for (int x = 0; x < image.width(); ++x) {
                const float v = std::ldexp(row[x], exponent);
                row[x] = clamp ? std::clamp(v, -FLT_MAX, FLT_MAX) : v;
            }
        }
}

}  // namespace

namespace detail {

BilateralSetup bilateral_setup(const BilateralOptions& options, pn_dims mask, int channels, pn_dims guide,
                               const pn_dims* normals, pn_dims out)
{
    check_options(options);
    Window window = window_of(options);
    BilateralSetup setup{std::move(window.taps), std::move(window.weights),
                         make_params(mask, channels, guide, normals, out, options)};
    setup.params.taps = int(setup.weights.size() / 2);
    return setup;
}

bool needs_overflow_guard(const Image& mask) { return overflow_guard_exponent(mask) > 0; }

}  // namespace detail

Image cross_bilateral(Context& context, const Image& mask, const Image& guide_depth, const BilateralOptions& options,
                      const Image* guide_normals)
{
    check_images(mask, guide_depth, guide_normals);
    Image out(mask.width(), mask.height(), mask.channels());
    cross_bilateral(context, mask, guide_depth, options, out, guide_normals);
    return out;
}

void cross_bilateral(Context& context, const Image& mask, const Image& guide_depth, const BilateralOptions& options,
                     Image& out, const Image* guide_normals)
{
    check_images(mask, guide_depth, guide_normals);
    check_options(options);
    check_output(mask, guide_depth, guide_normals, out);
    if (const int k = overflow_guard_exponent(mask); k > 0) {
        Image scaled = mask;
        scale_image(scaled, -k, false);
        cross_bilateral(context, scaled, guide_depth, options, out, guide_normals);
        scale_image(out, k, true);
        return;
    }
    const pn_dims normals = detail::dims_of(guide_normals ? *guide_normals : guide_depth);
    const detail::BilateralSetup setup =
        detail::bilateral_setup(options, detail::dims_of(mask), mask.channels(), detail::dims_of(guide_depth),
                                guide_normals ? &normals : nullptr, detail::dims_of(out));
    std::vector<int> bad_rows(std::size_t(mask.height()), 0);
    context.impl().cross_bilateral(mask, guide_depth, guide_normals, setup.taps, setup.weights, options.separable,
                                   setup.params, out, bad_rows.data());
    if (std::find(bad_rows.begin(), bad_rows.end(), 1) != bad_rows.end())
        report_non_finite(mask, guide_depth, guide_normals);
}

void cross_bilateral(Context& context, const ImageView& mask, const ImageView& guide_depth,
                     const BilateralOptions& options, const MutableImageView& out, const ImageView* guide_normals)
{
    const InputImage m(mask, kBilateralOp, "mask"), g(guide_depth, kBilateralOp, "guide-depth");
    const std::optional<InputImage> n =
        guide_normals ? std::optional<InputImage>(std::in_place, *guide_normals, kBilateralOp, "guide-normals")
                      : std::nullopt;
    OutputImage o(out, kBilateralOp, "out");
    for (const ImageView* input : {&mask, &guide_depth, guide_normals})
        if (input) require_disjoint(*input, out, kBilateralOp, "out");
    cross_bilateral(context, m.image(), g.image(), options, o.image(), n ? &n->image() : nullptr);
    o.commit();
}

}  // namespace penumbra
