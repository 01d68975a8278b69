// Host operations of the moment family: validate, fill the parameters,
// dispatch, and report the first bad value a kernel flagged.
#include "penumbra/moments.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "backend.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

using detail::BackendImpl;

bool any_flagged(const std::vector<int>& rows) { return std::find(rows.begin(), rows.end(), 1) != rows.end(); }

std::string number(float v) { return std::to_string(v); }

// ---- tables ------------------------------------------------------------------

void check_depth_map(const std::string& op, const Image& depth)
{
    require(!depth.empty(), op, "the shadow map is empty (0 pixels)");
    require(depth.channels() == 1, op,
            "the shadow map must have one channel (depth), got " + std::to_string(depth.channels()));
}

void report_bad_depth(const std::string& op, const Image& depth)
{
    require_finite(depth, op, "the shadow map");
    for (int y = 0; y < depth.height(); ++y)
        for (int x = 0; x < depth.width(); ++x) {
            const float z = depth.at(0, x, y);
            if (z < 0.0f || z > 1.0f)
                throw Error(ErrorCategory::InvalidData, op,
                            "shadow-map depth " + number(z) + " at (" + std::to_string(x) + ", " + std::to_string(y) +
                                ") is outside [0, 1]; store linear light depth normalised to [0, 1]");
        }
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
                          Precision precision)
{
    MomentTable table(depth.width(), depth.height(), p.channels, precision, 1);
    p.depth = detail::dims_of(depth);
    p.table = detail::dims_of(table);
    std::vector<int> bad_rows(std::size_t(depth.height()), 0);
    context.impl().build_encoded_table(depth, p, table, bad_rows.data());
    if (any_flagged(bad_rows)) report_bad_depth(op, depth);
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
        const std::string text = e.what();
        const std::size_t prefix = e.operation().size() + 2;  // "operation: "
        throw Error(e.category(), op, text.size() > prefix ? text.substr(prefix) : text);
    }
}

float max_exponent(Quantization q)
{
    if (q == Quantization::None) return kEvsmMaxExponentExact;
    return q == Quantization::Bits16 ? kEvsmMaxExponent16 : kEvsmMaxExponent32;
}

float checked_exponent(const std::string& op, std::optional<float> value, Quantization q, bool positive)
{
    const float c = value.value_or(default_evsm_exponent(q, positive));
    const std::string name = positive ? "positive exponent" : "negative exponent";
    require(std::isfinite(c) && c > 0.0f, op, name + " must be > 0 (got " + number(c) + ")");
    require(c <= max_exponent(q), op,
            name + " " + number(c) + " exceeds " + number(max_exponent(q)) + ", the largest the " +
                (q == Quantization::None ? "exact 48-bit storage keeps within 2e-4 of the method (docs/moments.md)"
                 : q == Quantization::Bits16 ? "16-bit storage holds (its squared warp e^(-2c) would round to 0)"
                                             : "float storage holds (its squared warp e^(-2c) would leave the normal "
                                               "float range)") +
                "; use a smaller exponent");
    return c;
}

// ---- lookups -----------------------------------------------------------------

void check_receivers(const std::string& op, const Image& receivers, const Image& out)
{
    require(!receivers.empty(), op, "the receivers image is empty (0 pixels)");
    require(receivers.channels() == 3, op,
            "receivers must have 3 channels (u, v, z), got " + std::to_string(receivers.channels()));
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

void check_radius(const std::string& op, int radius, Precision precision)
{
    require(radius >= 0, op, "radius must be >= 0 (got " + std::to_string(radius) + ")");
    if (precision == Precision::Exact)
        require(radius <= kExactMaxRadius, op,
                "radius " + std::to_string(radius) + " exceeds " + std::to_string(kExactMaxRadius) +
                    ", the largest window (255x255 texels) whose sums an exact table keeps exact; use precision "
                    "float or a smaller radius");
}

// A bias is a share of the depth range or of the window: [0, 1).
float checked_bias(const std::string& op, const std::string& name, float value)
{
    require(std::isfinite(value) && value >= 0.0f && value < 1.0f, op,
            name + " must be in [0, 1) (got " + number(value) + ")");
    return value;
}

MomentParams base_params(const MomentTable& sums, const Image& receivers, const Image& out)
{
    MomentParams p{};
    p.table = detail::dims_of(sums);
    p.receivers = detail::dims_of(receivers);
    p.out = detail::dims_of(out);
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
    p.moment_bias = checked_bias(op, "moment-bias", moment_bias.value_or(default_moment_bias(q)));
    p.depth_bias = checked_bias(op, "depth-bias", depth_bias.value_or(default_depth_bias(q)));
    p.pivot_floor = pivot_floor(q);
}

void run_checked(Context& context, BackendImpl::MomentMethod method, const std::string& op, const MomentTable& sums,
                 const Image& receivers, const MomentParams& p, Image& out)
{
    std::vector<int> bad_rows(std::size_t(receivers.height()), 0);
    context.impl().moment_lookup(method, sums, receivers, p, out, bad_rows.data());
    if (any_flagged(bad_rows)) require_finite(receivers, op, "the receivers image");
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

MsmTable build_msm_table(Context& context, const Image& depth, Quantization quantization, Precision precision)
{
    const std::string op = "build_msm_table";
    check_depth_map(op, depth);
    check_storage(op, quantization, precision);
    if (quantization != Quantization::Bits16) return {moment_table_as(context, op, depth, 4, precision), quantization};
    EncodedSatParams p{};
    p.channels = 4;
    p.encoding = PN_ENCODE_MSM;
    p.quantize = 1;
    return {build_encoded(context, op, depth, p, precision), quantization};
}

EvsmTable build_evsm_table(Context& context, const Image& depth, const EvsmWarp& warp, Precision precision)
{
    const std::string op = "build_evsm_table";
    check_depth_map(op, depth);
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
                                     TableValues{PN_TABLE_EVSM, table.positive, table.negative});
        return table;
    }
    EncodedSatParams p{};
    p.channels = warp.channels;
    p.encoding = PN_ENCODE_EVSM;
    p.quantize = warp.quantization == Quantization::Bits16;
    p.exponent_positive = table.positive;
    p.exponent_negative = table.negative;
    table.sums = build_encoded(context, op, depth, p, precision);
    return table;
}

// ---- MSM -----------------------------------------------------------------------

Image msm(Context& context, const MsmTable& table, const Image& receivers, const MsmOptions& options)
{
    Image out(receivers.width(), receivers.height(), 1);
    msm(context, table, receivers, options, out);
    return out;
}

Image msm_soft(Context& context, const MsmTable& table, const Image& receivers, const MsmSoftOptions& options)
{
    Image out(receivers.width(), receivers.height(), 1);
    msm_soft(context, table, receivers, options, out);
    return out;
}

void msm(Context& context, const MsmTable& table, const Image& receivers, const MsmOptions& options, Image& out)
{
    const std::string op = "msm";
    check_table(op, table.sums, 4);
    check_receivers(op, receivers, out);
    check_radius(op, options.radius, table.sums.precision());
    MomentParams p = base_params(table.sums, receivers, out);
    set_msm_biases(p, op, table.quantization, options.moment_bias, options.depth_bias);
    p.radius = options.radius;
    run_checked(context, BackendImpl::MomentMethod::Msm, op, table.sums, receivers, p, out);
}

void msm_soft(Context& context, const MsmTable& table, const Image& receivers, const MsmSoftOptions& options,
              Image& out)
{
    const std::string op = "msm_soft";
    check_table(op, table.sums, 4);
    check_receivers(op, receivers, out);
    require(std::isfinite(options.light_size) && options.light_size > 0.0f, op,
            "light-size must be > 0 (got " + number(options.light_size) + ")");
    // As VSSM's (host/src/chebyshev.cpp): the filter window is clamped to
    // max_radius; an exact table needs it and its one-texel slivers within 255.
    const bool exact = table.sums.precision() == Precision::Exact;
    const int extent = std::max(table.sums.width(), table.sums.height());
    const int max_radius = exact ? kExactMaxRadius - 1 : extent;
    if (exact) {
        const float search_half = options.light_size * 0.5f * float(extent);
        require(search_half <= float(max_radius), op,
                "light-size " + number(options.light_size) + " needs a blocker search of " +
                    std::to_string(int(std::ceil(2 * search_half))) +
                    " texels, more than an exact table keeps exact (253); use precision float or a smaller light");
    }
    MomentParams p = base_params(table.sums, receivers, out);
    set_msm_biases(p, op, table.quantization, options.moment_bias, options.depth_bias);
    p.light_size = options.light_size;
    p.max_radius = max_radius;
    run_checked(context, BackendImpl::MomentMethod::MsmSoft, op, table.sums, receivers, p, out);
}

// ---- EVSM ----------------------------------------------------------------------

Image evsm(Context& context, const EvsmTable& table, const Image& receivers, const EvsmOptions& options)
{
    Image out(receivers.width(), receivers.height(), 1);
    evsm(context, table, receivers, options, out);
    return out;
}

void evsm(Context& context, const EvsmTable& table, const Image& receivers, const EvsmOptions& options, Image& out)
{
    const std::string op = "evsm";
    require(table.channels == 2 || table.channels == 4, op,
            "the table's channels must be 2 or 4, got " + std::to_string(table.channels));
    check_table(op, table.sums, table.channels);
    check_receivers(op, receivers, out);
    check_radius(op, options.radius, table.sums.precision());
    require(std::isfinite(options.min_variance) && options.min_variance >= 0.0f, op,
            "min-variance must be a finite value >= 0 (got " + number(options.min_variance) + ")");
    require(std::isfinite(options.bleed) && options.bleed >= 0.0f && options.bleed < 1.0f, op,
            "bleed must be in [0, 1) (got " + number(options.bleed) + ")");
    MomentParams p = base_params(table.sums, receivers, out);
    p.channels = table.channels;
    p.exponent_positive = checked_exponent(op, table.positive, table.quantization, true);
    p.exponent_negative = table.channels == 4 ? checked_exponent(op, table.negative, table.quantization, false) : 0.0f;
    p.radius = options.radius;
    p.min_variance = options.min_variance;
    p.bleed = options.bleed;
    p.depth_bias = checked_bias(op, "depth-bias", options.depth_bias);
    run_checked(context, BackendImpl::MomentMethod::Evsm, op, table.sums, receivers, p, out);
}

}  // namespace penumbra
