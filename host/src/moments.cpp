// Host operations of the moment family: validate, fill the parameters,
// dispatch, and report the first bad value a kernel flagged.
#include "penumbra/moments.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "checked_lookup.h"
#include "depth_conversion.h"
#include "visibility_output.h"
#include "window_limits.h"
#include "penumbra/error.h"
#include "penumbra/parameter_range.h"
#include "penumbra/pcf.h"

namespace penumbra {
namespace {

using detail::KernelId;

bool any_flagged(const std::vector<int>& rows) { return std::find(rows.begin(), rows.end(), 1) != rows.end(); }


// ---- tables ------------------------------------------------------------------

void check_depth_map(const std::string& op, const Image& depth)
{
    require(!depth.empty(), op, "depth", "the shadow map is empty (0 pixels)");
    require(depth.channels() == 1, op, "depth",
            "the shadow map must have one channel (depth), got " + std::to_string(depth.channels()));
}

void check_storage(const std::string& op, Quantization quantization, Precision precision)
{
    require(!(quantization == Quantization::Bits32 && precision == Precision::Exact), op,
            "quantization 32 keeps 32-bit floats per texel, which an exact table cannot hold; use precision "
            "float with it, or the default (no quantization: exact limb tables)");
    require(!(quantization == Quantization::None && precision == Precision::Float), op,
            "precision float sums floats: give quantization 32 with it, or use the default exact precision");
}

MomentTable build_encoded(Context& context, const std::string& op, const Image& depth, EncodedSatParams p,
                          Precision precision, const DepthConvention& convention)
{
    const TableValues values{0, 0.0f, 0.0f, convention};  // the kind: unused by the encoded lookups
    MomentTable table(depth.width(), depth.height(), p.channels, precision, 1, values);
    p.depth = detail::dims_of(depth);
    p.table = detail::dims_of(table);
    p.convention = detail::kernel_conversion(convention);
    std::vector<int> bad_rows(std::size_t(depth.height()), 0);
    context.impl().build_encoded_table(depth, p, table, bad_rows.data());
    if (any_flagged(bad_rows)) require_depths_in(depth, values.depth, op);
    return table;
}

// A table built by the moment table's build (kernels/moment_table.h): the
// float table of z..z^4 (Bits32) or an exact limb table (None: z..z^4 or
// EVSM's warps); its errors are reported as this operation's.
MomentTable moment_table_as(Context& context, const std::string& op, const Image& depth, int moments,
                            Precision precision, TableValues values = {})
{
    try {
        MomentTable table(depth.width(), depth.height(), moments, precision, kMomentLimbs, values);
        build_moment_table(context, depth, table);
        return table;
    } catch (const Error& e) {
        throw e.as_operation(op);
    }
}

// The exact storage's range is the declared one; the other storages move its
// upper bound (penumbra/moments.h derives each).
ParameterRange exponent_range(Quantization q, bool positive)
{
    ParameterRange range = positive ? kPositiveExponentRange : kNegativeExponentRange;
    if (q == Quantization::Bits16) {
        range.high = kEvsmMaxExponent16;
        range.why_high = ", the largest the 16-bit storage holds (its squared warp e^(-2c) would round to 0); use a "
                         "smaller exponent";
    } else if (q == Quantization::Bits32) {
        range.high = kEvsmMaxExponent32;
        range.why_high = ", the largest the float storage holds (its squared warp e^(-2c) would leave the normal "
                         "float range); use a smaller exponent";
    }
    return range;
}

float checked_exponent(const std::string& op, std::optional<float> value, Quantization q, bool positive)
{
    const float c = value.value_or(default_evsm_exponent(q, positive));
    check(exponent_range(q, positive), c, op);
    return c;
}

// ---- lookups -----------------------------------------------------------------

// `slopes`: the receivers also hold dzdu, dzdv (msm_soft's plane from channels).
void check_receivers(const std::string& op, const Image& receivers, const Image& out, bool slopes = false)
{
    require(!receivers.empty(), op, "receivers", "the receivers image is empty (0 pixels)");
    const int channels = slopes ? 5 : 3;
    const char* names = slopes ? " channels (u, v, z, dzdu, dzdv), got " : " channels (u, v, z), got ";
    require(receivers.channels() == channels, op,
            "receivers must have " + std::to_string(channels) + names + std::to_string(receivers.channels()));
    require(out.channels() == 1 && out.width() == receivers.width() && out.height() == receivers.height(), op,
            "the output must be a 1-channel image of the receivers' size (" + std::to_string(receivers.width()) +
                "x" + std::to_string(receivers.height()) + ")");
}

void check_table(const std::string& op, const MomentTable& sums, int channels)
{
    require(!sums.empty(), op, "the table is empty; build it with build_msm_table() or build_evsm_table()");
    require(sums.moments() == channels, op,
            "the table has " + std::to_string(sums.moments()) + " channels, this method reads " +
                std::to_string(channels));
}

// A bias is a share of the depth range or of the window: [0, 1).
float checked_bias(const std::string& op, const ParameterRange& range, float value)
{
    check(range, value, op);
    return value;
}

// The parameters of a lookup whose source is the map itself (the direct
// sums: checked_direct_lookup sets `table` to the map's dims).
MomentParams base_params(const Image& receivers, const Image& out)
{
    MomentParams p{};
    p.receivers = detail::dims_of(receivers);
    p.out = detail::dims_of(out);
    return p;
}

MomentParams base_params(const MomentTable& sums, const Image& receivers, const Image& out)
{
    MomentParams p = base_params(receivers, out);
    p.table = detail::dims_of(sums);
    p.limbs = sums.limbs();
    return p;
}

// The Hankel pivot at or below which the matrix is singular (kernels/msm.h):
// None: sixteen steps of the 3-limb table's rounding (2^-49), 2^-45; Bits16:
// 0, the dequantized means are exact (the kernel adds double rounding);
// Bits32: a few roundings of E[z^2] <= 1 in float, 2^-22 (float tables raise
// it where their entries are large).
float pivot_floor(Quantization q)
{
    if (q == Quantization::None) return 0x1p-45f;
    return q == Quantization::Bits16 ? 0.0f : 0x1p-22f;
}

void set_msm_biases(MomentParams& p, const std::string& op, Quantization q, std::optional<float> moment_bias,
                    std::optional<float> depth_bias)
{
    p.storage = q == Quantization::Bits16 ? PN_MOMENTS_OPTIMIZED16 : PN_MOMENTS_POWER;
    p.moment_bias = checked_bias(op, kMomentBiasRange, moment_bias.value_or(default_moment_bias(q)));
    p.depth_bias = checked_bias(op, kDepthBiasRange, depth_bias.value_or(default_depth_bias(q)));
    p.pivot_floor = pivot_floor(q);
}


}  // namespace

// ---- defaults (docs/moments.md derives them) ------------------------------------

float default_moment_bias(Quantization q)
{
    if (q == Quantization::None) return kMsmMomentBiasExact;
    return q == Quantization::Bits16 ? kMsmMomentBias16 : kMsmMomentBias32;
}

float default_depth_bias(Quantization q)
{
    if (q == Quantization::None) return kMsmDepthBiasExact;
    return q == Quantization::Bits16 ? kMsmDepthBias16 : kMsmDepthBias32;
}

float default_evsm_exponent(Quantization q, bool positive)
{
    if (q == Quantization::Bits16) return kEvsmMaxExponent16;
    if (q == Quantization::Bits32) return positive ? kEvsmPositiveExponent32 : kEvsmNegativeExponent32;
    return positive ? kEvsmPositiveExponentExact : kEvsmNegativeExponentExact;
}

std::string to_string(Quantization q)
{
    if (q == Quantization::None) return "none";
    return q == Quantization::Bits16 ? "16" : "32";
}

Quantization parse_quantization(const std::string& bits)
{
    if (bits == "none") return Quantization::None;
    if (bits == "16") return Quantization::Bits16;
    if (bits == "32") return Quantization::Bits32;
    throw Error(ErrorCategory::InvalidArgument, "quantize",
                "'" + bits + "' is not none, 16 or 32 (bits per stored value)");
}

// ---- tables ------------------------------------------------------------------

MsmTable build_msm_table(Context& context, const Image& depth, Quantization quantization, Precision precision,
                         const DepthConvention& convention)
{
    const std::string op = "build_msm_table";
    check_depth_map(op, depth);
    check_storage(op, quantization, precision);
    check_depth_convention(convention, op);
    if (quantization != Quantization::Bits16) {
        const TableValues powers{PN_TABLE_POWERS, 0.0f, 0.0f, convention};
        return {moment_table_as(context, op, depth, 4, precision, powers), quantization};
    }
    EncodedSatParams p{};
    p.channels = 4;
    p.encoding = PN_ENCODE_MSM;
    p.quantize = 1;
    return {build_encoded(context, op, depth, p, precision, convention), quantization};
}

EvsmTable build_evsm_table(Context& context, const Image& depth, const EvsmWarp& warp, Precision precision,
                           const DepthConvention& convention)
{
    const std::string op = "build_evsm_table";
    check_depth_map(op, depth);
    check_depth_convention(convention, op);
    check_storage(op, warp.quantization, precision);
    require(warp.channels == 2 || warp.channels == 4, op,
            "channels must be 2 (EVSM2: positive warp) or 4 (EVSM4: both warps), got " +
                std::to_string(warp.channels));
    EvsmTable table;
    table.channels = warp.channels;
    table.quantization = warp.quantization;
    table.positive = checked_exponent(op, warp.positive, warp.quantization, true);
    table.negative = warp.channels == 4 ? checked_exponent(op, warp.negative, warp.quantization, false) : 0.0f;
    if (warp.quantization == Quantization::None) {
        table.sums = moment_table_as(context, op, depth, warp.channels, precision,
                                     TableValues{PN_TABLE_EVSM, table.positive, table.negative, convention});
        return table;
    }
    EncodedSatParams p{};
    p.channels = warp.channels;
    p.encoding = PN_ENCODE_EVSM;
    p.quantize = warp.quantization == Quantization::Bits16;
    p.exponent_positive = table.positive;
    p.exponent_negative = table.negative;
    table.sums = build_encoded(context, op, depth, p, precision, convention);
    return table;
}

// ---- MSM -----------------------------------------------------------------------

PN_ALLOCATING_VISIBILITY(msm, MsmTable, MsmOptions)
PN_ALLOCATING_VISIBILITY(msm, Image, MsmOptions)
PN_ALLOCATING_VISIBILITY(msm_soft, MsmTable, MsmSoftOptions)

void msm(Context& context, const MsmTable& table, const Image& receivers, const MsmOptions& options, Image& out)
{
    const std::string op = "msm";
    check_table(op, table.sums, 4);
    check_receivers(op, receivers, out);
    detail::check_radius(op, options.radius, table.sums.precision());
    MomentParams p = base_params(table.sums, receivers, out);
    set_msm_biases(p, op, table.quantization, options.moment_bias, options.depth_bias);
    p.radius = options.radius;
    p.convention = detail::receivers_conversion(op, table.sums.values().depth, options.depth_convention);
    detail::checked_table_lookup<KernelId::msm_float, KernelId::msm_exact>(context.impl(), op, table.sums, receivers, p,
                                                                           out);
}

void msm(Context& context, const Image& depth, const Image& receivers, const MsmOptions& options, Image& out)
{
    const std::string op = "msm";
    check_receivers(op, receivers, out);
    detail::check_radius(op, options.radius, Precision::Exact);
    MomentParams p = base_params(receivers, out);
    set_msm_biases(p, op, Quantization::None, options.moment_bias, options.depth_bias);
    p.radius = options.radius;
    p.convention = detail::kernel_conversion(options.depth_convention);
    detail::checked_direct_lookup<KernelId::msm_direct>(context.impl(), op, depth, receivers,
                                                 options.depth_convention, p, out);
}

namespace {

// The receivers with the plane msm_soft's plane bias reads (planes 3-5:
// dz/du, dz/dv, the flag), made as the percentage-closer family makes them.
Image receiver_planes(const std::string& op, const Image& receivers, DerivativeSource derivatives)
{
    DepthBias plane;
    plane.mode = BiasMode::ReceiverPlane;
    plane.derivatives = derivatives;
    return pcf_receivers(receivers, plane, op);
}

}  // namespace

void msm_soft(Context& context, const MsmTable& table, const Image& receivers, const MsmSoftOptions& options,
              Image& out)
{
    const std::string op = "msm_soft";
    check_table(op, table.sums, 4);
    const bool slope_channels = options.plane_bias > 0.0f && options.derivatives == DerivativeSource::Channels;
    check_receivers(op, receivers, out, slope_channels);
    const int max_radius = detail::checked_search_radius(op, options.light_size, table.sums);
    check(kPlaneBiasRange, options.plane_bias, op);
    check(kPlaneBiasMaxRange, options.plane_bias_max, op);
    const Image planes = options.plane_bias > 0.0f ? receiver_planes(op, receivers, options.derivatives) : Image{};
    const Image& rx = options.plane_bias > 0.0f ? planes : receivers;
    MomentParams p = base_params(table.sums, rx, out);
    set_msm_biases(p, op, table.quantization, options.moment_bias, options.depth_bias);
    p.light_size = options.light_size;
    p.max_radius = max_radius;
    p.plane_bias = options.plane_bias;
    p.plane_bias_max = options.plane_bias_max;
    p.convention = detail::receivers_conversion(op, table.sums.values().depth, options.depth_convention);
    detail::checked_table_lookup<KernelId::msm_soft_float, KernelId::msm_soft_exact>(context.impl(), op, table.sums,
                                                                                     rx, p, out);
}

// ---- EVSM ----------------------------------------------------------------------

PN_ALLOCATING_VISIBILITY(evsm, EvsmTable, EvsmOptions)

namespace {

// The lookup options of evsm() and the warp's exponents, both sources alike.
void set_evsm_options(MomentParams& p, const std::string& op, const EvsmOptions& options, int channels,
                      float positive, float negative, Quantization q)
{
    check(kMinVarianceRange, options.min_variance, op);
    check(kBleedRange, options.bleed, op);
    p.channels = channels;
    p.exponent_positive = checked_exponent(op, positive, q, true);
    p.exponent_negative = channels == 4 ? checked_exponent(op, negative, q, false) : 0.0f;
    p.radius = options.radius;
    p.min_variance = options.min_variance;
    p.bleed = options.bleed;
    p.depth_bias = checked_bias(op, kDepthBiasRange, options.depth_bias);
}

void check_evsm_channels(const std::string& op, int channels, const char* what)
{
    require(channels == 2 || channels == 4, op,
            std::string(what) + " channels must be 2 or 4, got " + std::to_string(channels));
}

}  // namespace

void evsm(Context& context, const EvsmTable& table, const Image& receivers, const EvsmOptions& options, Image& out)
{
    const std::string op = "evsm";
    check_evsm_channels(op, table.channels, "the table's");
    check_table(op, table.sums, table.channels);
    check_receivers(op, receivers, out);
    detail::check_radius(op, options.radius, table.sums.precision());
    MomentParams p = base_params(table.sums, receivers, out);
    set_evsm_options(p, op, options, table.channels, table.positive, table.negative, table.quantization);
    p.convention = detail::receivers_conversion(op, table.sums.values().depth, options.depth_convention);
    detail::checked_table_lookup<KernelId::evsm_float, KernelId::evsm_exact>(context.impl(), op, table.sums, receivers,
                                                                             p, out);
}

Image evsm(Context& context, const Image& depth, const EvsmWarp& warp, const Image& receivers,
           const EvsmOptions& options)
{
    return detail::visibility_output(receivers,
                                     [&](Image& out) { evsm(context, depth, warp, receivers, options, out); });
}

void evsm(Context& context, const Image& depth, const EvsmWarp& warp, const Image& receivers,
          const EvsmOptions& options, Image& out)
{
    const std::string op = "evsm";
    check_evsm_channels(op, warp.channels, "the warp's");
    require(warp.quantization == Quantization::None, op,
            "direct window sums take the warps in double (quantization none); a quantized storage needs its table "
            "(build_evsm_table)");
    check_receivers(op, receivers, out);
    detail::check_radius(op, options.radius, Precision::Exact);
    MomentParams p = base_params(receivers, out);
    const float positive = warp.positive.value_or(default_evsm_exponent(Quantization::None, true));
    const float negative = warp.negative.value_or(default_evsm_exponent(Quantization::None, false));
    set_evsm_options(p, op, options, warp.channels, positive, negative, Quantization::None);
    p.convention = detail::kernel_conversion(options.depth_convention);
    detail::checked_direct_lookup<KernelId::evsm_direct>(context.impl(), op, depth, receivers,
                                                 options.depth_convention, p, out);
}

}  // namespace penumbra
