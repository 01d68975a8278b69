// Host operations vsm() and vssm(): validate, fill ChebyshevParams, dispatch.
#include "penumbra/chebyshev.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "backend.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

void check_receivers(const std::string& op, const MomentTable& table, const Image& receivers)
{
    require(!table.empty(), op, "the moment table is empty; build it with build_moment_table()");
    require(!receivers.empty(), op, "the receivers image is empty (0 pixels)");
    require(receivers.channels() == 3, op,
            "receivers must have 3 channels (u, v, z), got " + std::to_string(receivers.channels()));
}

// Runs a lookup; the kernel flags rows with NaN or infinite receivers, and the
// first one is then reported (the output is left unspecified).
void run_checked(Context& context, detail::ChebyshevMethod method, const std::string& op, const MomentTable& table,
                 const Image& receivers, const ChebyshevParams& p, Image& out)
{
    std::vector<int> bad_rows(std::size_t(receivers.height()), 0);
    context.impl().chebyshev(method, table, receivers, p, out, bad_rows.data());
    if (std::find(bad_rows.begin(), bad_rows.end(), 1) != bad_rows.end())
        require_finite(receivers, op, "the receivers image");
}

void check_filter(const std::string& op, float min_variance, float bleed)
{
    require(std::isfinite(min_variance) && min_variance >= 0.0f, op,
            "min-variance must be a finite value >= 0 (got " + std::to_string(min_variance) + ")");
    require(std::isfinite(bleed) && bleed >= 0.0f && bleed < 1.0f, op,
            "bleed must be in [0, 1) (got " + std::to_string(bleed) + ")");
}

ChebyshevParams base_params(const MomentTable& table, const Image& receivers, const Image& out,
                            float min_variance, float bleed)
{
    ChebyshevParams p{};
    p.table = detail::dims_of(table);
    p.receivers = detail::dims_of(receivers);
    p.out = detail::dims_of(out);
    p.min_variance = min_variance;
    p.bleed = bleed;
    p.limbs = table.limbs();
    return p;
}

void check_output(const std::string& op, const Image& receivers, const Image& out)
{
    require(out.channels() == 1 && out.width() == receivers.width() && out.height() == receivers.height(), op,
            "the output must be a 1-channel image of the receivers' size (" + std::to_string(receivers.width()) +
                "x" + std::to_string(receivers.height()) + ")");
}

}  // namespace

Image vsm(Context& context, const MomentTable& table, const Image& receivers, const VsmOptions& options)
{
    Image out(receivers.width(), receivers.height(), 1);
    vsm(context, table, receivers, options, out);
    return out;
}

Image vssm(Context& context, const MomentTable& table, const Image& receivers, const VssmOptions& options)
{
    Image out(receivers.width(), receivers.height(), 1);
    vssm(context, table, receivers, options, out);
    return out;
}

void vsm(Context& context, const MomentTable& table, const Image& receivers, const VsmOptions& options, Image& out)
{
    const std::string op = "vsm";
    check_receivers(op, table, receivers);
    check_filter(op, options.min_variance, options.bleed);
    require(options.radius >= 0, op, "radius must be >= 0 (got " + std::to_string(options.radius) + ")");
    if (table.precision() == Precision::Exact)
        require(options.radius <= kExactMaxRadius, op,
                "radius " + std::to_string(options.radius) + " exceeds " + std::to_string(kExactMaxRadius) +
                    ", the largest window (255x255 texels) whose sums an exact table keeps exact; use "
                    "--precision float or a smaller radius");
    check_output(op, receivers, out);
    ChebyshevParams p = base_params(table, receivers, out, options.min_variance, options.bleed);
    p.radius = options.radius;
    run_checked(context, detail::ChebyshevMethod::Vsm, op, table, receivers, p, out);
}

void vssm(Context& context, const MomentTable& table, const Image& receivers, const VssmOptions& options, Image& out)
{
    const std::string op = "vssm";
    check_receivers(op, table, receivers);
    check_filter(op, options.min_variance, options.bleed);
    require(std::isfinite(options.light_size) && options.light_size > 0.0f, op,
            "light-size must be > 0 (got " + std::to_string(options.light_size) + ")");
    // The filter window is clamped to max_radius; an exact table needs the
    // window plus its one-texel interpolation slivers within 255 texels.
    const int map_extent = std::max(table.width(), table.height());
    const int max_radius = table.precision() == Precision::Exact ? kExactMaxRadius - 1 : map_extent;
    if (table.precision() == Precision::Exact) {
        const float search_half = options.light_size * 0.5f * float(map_extent);
        require(search_half <= float(max_radius), op,
                "light-size " + std::to_string(options.light_size) + " needs a blocker search of " +
                    std::to_string(int(std::ceil(2 * search_half))) +
                    " texels, more than an exact table keeps exact (253); use --precision float or a "
                    "smaller light");
    }
    check_output(op, receivers, out);
    ChebyshevParams p = base_params(table, receivers, out, options.min_variance, options.bleed);
    p.light_size = options.light_size;
    p.max_radius = max_radius;
    run_checked(context, detail::ChebyshevMethod::Vssm, op, table, receivers, p, out);
}

}  // namespace penumbra
