// Host operations vsm() and vssm(): validate, fill ChebyshevParams, dispatch.
#include "penumbra/chebyshev.h"

#include <cmath>
#include <string>

#include "checked_lookup.h"
#include "chebyshev_params.h"
#include "depth_conversion.h"
#include "visibility_output.h"
#include "window_limits.h"
#include "penumbra/error.h"
#include "penumbra/parameter_range.h"

namespace penumbra {
namespace {

void check_receivers(const std::string& op, const Image& receivers)
{
    require(!receivers.empty(), op, "receivers", "the receivers image is empty (0 pixels)");
    require(receivers.channels() == 3, op,
            "receivers must have 3 channels (u, v, z), got " + std::to_string(receivers.channels()));
}

using detail::KernelId;

void check_filter(const std::string& op, float min_variance, float bleed)
{
    check(kMinVarianceRange, min_variance, op);
    check(kBleedRange, bleed, op);
}

void check_table(const std::string& op, const MomentTable& table)
{
    require(!table.empty(), op, "the moment table is empty; build it with build_moment_table()");
}

// `table` set by the caller: the table's dims, or the map's (direct sums).
ChebyshevParams base_params(pn_dims receivers, pn_dims out, float min_variance, float bleed)
{
    ChebyshevParams p{};
    p.receivers = receivers;
    p.out = out;
    p.min_variance = min_variance;
    p.bleed = bleed;
    return p;
}
ChebyshevParams base_params(const Image& receivers, const Image& out, float min_variance, float bleed)
{
    return base_params(detail::dims_of(receivers), detail::dims_of(out), min_variance, bleed);
}

void check_output(const std::string& op, const Image& receivers, const Image& out)
{
    require(out.channels() == 1 && out.width() == receivers.width() && out.height() == receivers.height(), op,
            "the output must be a 1-channel image of the receivers' size (" + std::to_string(receivers.width()) +
                "x" + std::to_string(receivers.height()) + ")");
}

}  // namespace

namespace detail {

ChebyshevParams vsm_table_params(const std::string& op, pn_dims table, Precision precision, int limbs,
                                 pn_dims receivers, pn_dims out, const VsmOptions& options)
{
    check_filter(op, options.min_variance, options.bleed);
    detail::check_radius(op, options.radius, precision);
    ChebyshevParams p = base_params(receivers, out, options.min_variance, options.bleed);
    p.table = table;
    p.limbs = limbs;
    p.radius = options.radius;
    return p;
}

ChebyshevParams vssm_table_params(const std::string& op, pn_dims table, Precision precision, int limbs,
                                  pn_dims receivers, pn_dims out, const VssmOptions& options)
{
    check_filter(op, options.min_variance, options.bleed);
    ChebyshevParams p = base_params(receivers, out, options.min_variance, options.bleed);
    p.table = table;
    p.limbs = limbs;
    p.light_size = options.light_size;
    p.max_radius = detail::checked_search_radius(op, options.light_size, table.width, table.height, precision);
    return p;
}

}  // namespace detail

PN_ALLOCATING_VISIBILITY(vsm, MomentTable, VsmOptions)
PN_ALLOCATING_VISIBILITY(vsm, Image, VsmOptions)
PN_ALLOCATING_VISIBILITY(vssm, MomentTable, VssmOptions)

void vsm(Context& context, const MomentTable& table, const Image& receivers, const VsmOptions& options, Image& out)
{
    const std::string op = "vsm";
    check_table(op, table);
    check_receivers(op, receivers);
    ChebyshevParams p = detail::vsm_table_params(op, detail::dims_of(table), table.precision(), table.limbs(),
                                                 detail::dims_of(receivers), detail::dims_of(out), options);
    p.convention = detail::receivers_conversion(op, table.values().depth, options.depth_convention);
    check_output(op, receivers, out);
    detail::checked_table_lookup<KernelId::vsm_float, KernelId::vsm_exact>(context.impl(), op, table, receivers, p,
                                                                           out);
}

void vsm(Context& context, const Image& depth, const Image& receivers, const VsmOptions& options, Image& out)
{
    const std::string op = "vsm";
    check_receivers(op, receivers);
    check_filter(op, options.min_variance, options.bleed);
    detail::check_radius(op, options.radius, Precision::Exact);
    check_output(op, receivers, out);
    ChebyshevParams p = base_params(receivers, out, options.min_variance, options.bleed);
    p.radius = options.radius;
    p.convention = detail::kernel_conversion(options.depth_convention);
    detail::checked_direct_lookup<KernelId::vsm_direct>(context.impl(), op, depth, receivers,
                                                 options.depth_convention, p, out);
}

void vssm(Context& context, const MomentTable& table, const Image& receivers, const VssmOptions& options, Image& out)
{
    const std::string op = "vssm";
    check_table(op, table);
    check_receivers(op, receivers);
    check_filter(op, options.min_variance, options.bleed);
    check_output(op, receivers, out);
    ChebyshevParams p = detail::vssm_table_params(op, detail::dims_of(table), table.precision(), table.limbs(),
                                                  detail::dims_of(receivers), detail::dims_of(out), options);
    p.convention = detail::receivers_conversion(op, table.values().depth, options.depth_convention);
    detail::checked_table_lookup<KernelId::vssm_float, KernelId::vssm_exact>(context.impl(), op, table, receivers, p,
                                                                             out);
}

}  // namespace penumbra
