#include "support/fidelity_reference.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace penumbra::testing::fidelity {

namespace {

constexpr real kPerturbation = 0x1p-20L;  // the rule's relative move of each raw moment
// A pivot below this share of its terms is zero: long double rounding of the
// directly summed moments is ~2^-64 of them, the cancellations of a 3 x 3
// Hankel factorisation on moments about the mean cost at most ~2^10 of that.
constexpr real kSingular = 0x1p-48L;
constexpr real kVssmNoBlocker = 1e-4L;    // kernels/vssm.h: 1 - p below this is no blocker
constexpr real kVssmMinOccluder = 1e-4L;  // z_occ floor as a share of z
constexpr real kMsmNoBlocker = 1e-4L;     // kernels/msm_soft.h: blocker weight beyond alpha

real binomial(int n, int k)
{
    real r = 1;
    for (int i = 1; i <= k; ++i) r = r * real(n - k + i) / real(i);
    return r;
}

real clampr(real x, real lo, real hi) { return std::min(std::max(x, lo), hi); }

// Accumulates a weighted distribution: the values once (a warp may be
// costly), then the mean, then the central sums about it.
template <class Visit>
Moments accumulate(Visit visit)
{
    thread_local std::vector<std::pair<real, real>> values;
    values.clear();
    real total = 0, first = 0;
    visit([&](real value, real weight) {
        values.emplace_back(value, weight);
        total += weight;
        first += weight * value;
    });
    Moments m;
    m.centre = first / total;
    std::array<real, 5> sums{0, 0, 0, 0, 0};
    for (auto [value, weight] : values) {
        const real d = value - m.centre;
        real power = weight;
        for (int k = 0; k <= 4; ++k) {
            sums[k] += power;
            power *= d;
        }
    }
    for (int k = 0; k <= 4; ++k) m.central[k] = sums[k] / total;
    return m;
}

}  // namespace

std::string method_name(Method m)
{
    switch (m) {
    case Method::Vsm: return "vsm";
    case Method::Vssm: return "vssm";
    case Method::Msm: return "msm";
    case Method::MsmSoft: return "msm-soft";
    case Method::Evsm2: return "evsm2";
    case Method::Evsm4: return "evsm4";
    }
    return "?";
}

double tolerance(Method m) { return (m == Method::Msm || m == Method::MsmSoft) ? 1e-3 : 2e-4; }

Box texel_box(int width, int height, float u, float v, int rx, int ry)
{
    // floor(u W) of the clamped float u, in double: exact (24 + 15 bits).
    const int tx = std::clamp(int(std::floor(double(std::clamp(u, 0.0f, 1.0f)) * width)), 0, width - 1);
    const int ty = std::clamp(int(std::floor(double(std::clamp(v, 0.0f, 1.0f)) * height)), 0, height - 1);
    return {std::max(tx - rx, 0), std::min(tx + rx + 1, width), std::max(ty - ry, 0), std::min(ty + ry + 1, height)};
}

Box texel_window(int width, int height, float u, float v, int radius)
{
    return texel_box(width, height, u, v, radius, radius);
}

Span clip_span(int width, int height, real cx, real cy, real half_x, real half_y)
{
    return {clampr(cx - half_x, 0, width), clampr(cx + half_x, 0, width), clampr(cy - half_y, 0, height),
            clampr(cy + half_y, 0, height)};
}

real Moments::raw(int k) const
{
    real s = 0;
    for (int j = 0; j <= k; ++j) s += binomial(k, j) * central[j] * std::pow(centre, real(k - j));
    return s;
}

Moments from_raw(const std::array<real, 5>& raw)
{
    Moments m;
    m.centre = raw[1];
    for (int k = 0; k <= 4; ++k) {
        real s = 0;
        for (int j = 0; j <= k; ++j) s += binomial(k, j) * raw[j] * std::pow(-m.centre, real(k - j));
        m.central[k] = s;
    }
    m.central[0] = 1;
    return m;
}

Moments perturbed(const Moments& m, int count, unsigned signs, real eps)
{
    std::array<real, 5> raw{1, 0, 0, 0, 0};
    for (int k = 1; k <= 4; ++k) raw[k] = m.raw(k);
    for (int k = 1; k <= count; ++k) raw[k] *= 1 + ((signs >> (k - 1)) & 1u ? eps : -eps);
    return from_raw(raw);
}

real identity(real z, const Params&) { return z; }
real positive_warp(real z, const Params& p) { return std::exp(real(p.positive) * (z - 1)); }
real negative_warp(real z, const Params& p) { return -std::exp(-real(p.negative) * z); }

const std::vector<real>* WarpedMap::of(Transform f) const
{
    return f == positive_warp ? &positive : (f == negative_warp ? &negative : nullptr);
}

WarpedMap warp_map(const Image& depth, const Params& p)
{
    WarpedMap w;
    for (int y = 0; y < depth.height(); ++y)
        for (int x = 0; x < depth.width(); ++x) {
            w.positive.push_back(positive_warp(real(depth.at(0, x, y)), p));
            w.negative.push_back(negative_warp(real(depth.at(0, x, y)), p));
        }
    return w;
}

namespace {

// Calls visit(x, y, weight) for every texel a span covers, weighted by the
// overlap of [x, x + 1) x [y, y + 1) with it.
template <class Visit>
void for_span_texels(int width, int height, Span s, Visit visit)
{
    const auto overlap = [](int i, real lo, real hi) {
        return std::max<real>(0, std::min<real>(i + 1, hi) - std::max<real>(i, lo));
    };
    const int x0 = int(std::floor(s.x0)), x1 = std::min(int(std::ceil(s.x1)), width);
    const int y0 = int(std::floor(s.y0)), y1 = std::min(int(std::ceil(s.y1)), height);
    for (int y = y0; y < y1; ++y) {
        const real wy = overlap(y, s.y0, s.y1);
        if (wy <= 0) continue;
        for (int x = x0; x < x1; ++x) {
            const real wx = overlap(x, s.x0, s.x1);
            if (wx > 0) visit(x, y, wx * wy);
        }
    }
}

// The weighted mean of stored per-texel raw moments.
template <class Texels>
Moments stored_moments(const StoredMoments& stored, Texels texels)
{
    std::array<real, 5> raw{0, 0, 0, 0, 0};
    texels([&](int x, int y, real weight) {
        const auto& t = stored.texel[std::size_t(y) * std::size_t(stored.width) + std::size_t(x)];
        raw[0] += weight;
        for (int k = 1; k <= 4; ++k) raw[k] += weight * t[std::size_t(k - 1)];
    });
    for (int k = 1; k <= 4; ++k) raw[k] /= raw[0];
    raw[0] = 1;
    return from_raw(raw);
}

}  // namespace

Moments box_moments(const Image& depth, Box b, Transform f, const Params& p)
{
    if (p.stored)
        return stored_moments(*p.stored, [&](auto&& add) {
            for (int y = b.y0; y < b.y1; ++y)
                for (int x = b.x0; x < b.x1; ++x) add(x, y, real(1));
        });
    if (f == identity)
        return accumulate([&](auto&& add) {
            for (int y = b.y0; y < b.y1; ++y)
                for (int x = b.x0; x < b.x1; ++x) add(real(depth.at(0, x, y)), 1);
        });
    const std::vector<real>* warped = p.warped ? p.warped->of(f) : nullptr;
    if (!warped)
        return accumulate([&](auto&& add) {
            for (int y = b.y0; y < b.y1; ++y)
                for (int x = b.x0; x < b.x1; ++x) add(f(real(depth.at(0, x, y)), p), 1);
        });
    const std::vector<real>& values = *warped;
    return accumulate([&](auto&& add) {
        for (int y = b.y0; y < b.y1; ++y)
            for (int x = b.x0; x < b.x1; ++x) add(values[std::size_t(y) * std::size_t(depth.width()) + std::size_t(x)], 1);
    });
}

Moments span_moments(const Image& depth, Span s, Transform f, const Params& p)
{
    if (p.stored)
        return stored_moments(*p.stored, [&](auto&& add) { for_span_texels(p.stored->width, p.stored->height, s, add); });
    return accumulate([&](auto&& add) {
        for_span_texels(depth.width(), depth.height(), s,
                        [&](int x, int y, real weight) { add(f(real(depth.at(0, x, y)), p), weight); });
    });
}

// ---- Chebyshev (VSM, VSSM, EVSM) ------------------------------------------

real chebyshev_upper(const Moments& m, real z, real min_variance)
{
    const real mean = m.centre + m.central[1];
    const real variance = std::max(m.central[2] - m.central[1] * m.central[1], min_variance);
    if (z <= mean) return 1;
    const real d = z - mean;
    const real denominator = variance + d * d;
    return denominator > 0 ? variance / denominator : 0;
}

real linstep(real lo, real hi, real x) { return clampr((x - lo) / (hi - lo), 0, 1); }

// ---- MSM (Peters & Klein 2015, with the Hausdorff fallback) ---------------

namespace {

// The biased distribution (1 - alpha) window + alpha/2 at 0 + alpha/2 at 1,
// as moments about the window's centre c: B[k] = E'[(Z - c)^k].
struct Biased {
    real c;
    std::array<real, 5> B;
};

Biased bias(const Moments& m, real alpha)
{
    Biased b{m.centre, {}};
    for (int k = 0; k <= 4; ++k)
        b.B[k] = (1 - alpha) * m.central[k] + alpha / 2 * (std::pow(-m.centre, real(k)) + std::pow(1 - m.centre, real(k)));
    return b;
}

// E'[prod_i (Z - q_i)] for points q_i in depth units.
real expect_product(const Biased& b, const std::vector<real>& q)
{
    std::vector<real> poly{1};  // coefficients in y = Z - c, lowest first
    for (real point : q) {
        const real root = point - b.c;
        std::vector<real> next(poly.size() + 1, 0);
        for (std::size_t i = 0; i < poly.size(); ++i) {
            next[i + 1] += poly[i];
            next[i] -= root * poly[i];
        }
        poly = next;
    }
    real e = 0;
    for (std::size_t i = 0; i < poly.size(); ++i) e += poly[i] * b.B[i];
    return e;
}

// The weight of `at` in the distribution supported on {at} + others with
// these moments (Lagrange interpolation: exact when the support is right).
real lagrange_weight(const Biased& b, real at, const std::vector<real>& others)
{
    real denominator = 1;
    for (real q : others) denominator *= at - q;
    return expect_product(b, others) / denominator;
}

// The distribution of at most two points with moments (1, B1, B2, B3):
// returns its P(Z < z) (and the points and weights for the blockers).
struct TwoPoint {
    real x1, x2, w1, w2;
};

TwoPoint two_points(const Biased& b)
{
    const real d2 = b.B[2] - b.B[1] * b.B[1];
    const real mean = b.c + b.B[1];
    if (d2 <= kSingular * std::max<real>(b.B[2], 1e-300L)) return {mean, mean, 1, 0};
    // Points y are the roots of y^2 - s y + p in y = Z - c.
    const real e = b.B[3] - b.B[1] * b.B[2];
    const real s = e / d2;
    const real pr = (b.B[1] * b.B[3] - b.B[2] * b.B[2]) / d2;
    const real spread = std::sqrt(std::max<real>(s * s / 4 - pr, 0));
    const real y1 = s / 2 - spread, y2 = s / 2 + spread;
    const real w2 = clampr((b.B[1] - y1) / (y2 - y1), 0, 1);
    return {y1 + b.c, y2 + b.c, 1 - w2, w2};
}

real two_point_intensity(const TwoPoint& t, real z)
{
    return (t.x1 < z ? t.w1 : 0) + (t.x2 < z ? t.w2 : 0);
}

// The Hankel factors of the biased moments about c.
struct Hankel {
    real d2, e, d3;
    bool definite;
};

Hankel factor(const Biased& b)
{
    Hankel h;
    h.d2 = b.B[2] - b.B[1] * b.B[1];
    h.e = b.B[3] - b.B[1] * b.B[2];
    h.d3 = h.d2 > 0 ? (b.B[4] - b.B[2] * b.B[2]) - h.e * h.e / h.d2 : 0;
    h.definite = h.d2 > kSingular * std::max<real>(b.B[2], 1e-300L) && h.d3 > kSingular * std::max<real>(b.B[4], 1e-300L);
    return h;
}

// The kernel polynomial q(y) = q0 + q1 y + q2 y^2, q = B^-1 (1, y, y^2), in
// y = Z - c, and its two roots (depth units), for a definite Hankel matrix.
struct Canonical {
    std::array<real, 3> q;
    real lo, hi;
};

Canonical canonical(const Biased& b, const Hankel& h, real z)
{
    const real y = z - b.c;
    // L D L^T: L = [1; B1 1; B2 e/d2 1], D = (1, d2, d3).
    const real l31 = b.B[2], l32 = h.e / h.d2;
    const real f1 = 1, f2 = y - b.B[1] * f1, f3 = y * y - l31 * f1 - l32 * f2;
    Canonical c;
    c.q[2] = f3 / h.d3;
    c.q[1] = f2 / h.d2 - l32 * c.q[2];
    c.q[0] = f1 - b.B[1] * c.q[1] - l31 * c.q[2];
    // The roots of q0 + q1 x + q2 x^2, by the cancellation-free pair t / q2 and q0 / t.
    const real disc = std::sqrt(std::max<real>(c.q[1] * c.q[1] - 4 * c.q[0] * c.q[2], 0));
    const real t = c.q[1] < 0 ? (disc - c.q[1]) / 2 : -(c.q[1] + disc) / 2;
    const real ra = t / c.q[2], rb = c.q[0] / t;
    c.lo = std::min(ra, rb) + b.c;
    c.hi = std::max(ra, rb) + b.c;
    return c;
}

real christoffel_weight(const Biased& b, const Canonical& c, real z)
{
    const real y = z - b.c;
    return 1 / (c.q[0] + (c.q[1] + c.q[2] * y) * y);
}

// Support {0, z, r, 1}: r makes E'[Z (Z - 1)(Z - z)(Z - r)] = 0.
real hausdorff(const Biased& b, real z_receiver)
{
    const real z = clampr(z_receiver, 0x1p-40L, 1 - 0x1p-40L);
    const real a = expect_product(b, {0, 1, z});
    const real n = expect_product(b, {0, 0, 1, z});  // E'[Z^2 (Z - 1)(Z - z)]
    const real r = clampr(n / a, 0, 1);
    if (r < z) return 1 - lagrange_weight(b, z, {0, r, 1}) - lagrange_weight(b, 1, {0, z, r});
    return lagrange_weight(b, 0, {z, r, 1});
}

}  // namespace

namespace {

// Cantelli's two-sided bounds on P(Z < z) from the biased mean and variance.
struct Cantelli {
    real lower, upper;
};

Cantelli cantelli(const Biased& b, real z)
{
    Moments two;
    two.centre = b.c;
    two.central = {1, b.B[1], b.B[2], 0, 0};
    Moments mirrored = two;
    mirrored.centre = -b.c;
    mirrored.central[1] = -b.B[1];
    return {1 - chebyshev_upper(two, z, 0), chebyshev_upper(mirrored, -z, 0)};
}

// A biased Hankel matrix that is singular (or, for moments that no
// distribution has, indefinite): the window's own one or two depths from
// its raw moments, plus the bias atoms (kernels/msm.h's rule; exact where
// the biased distribution has at most two points). A two-point fit outside
// [-0.01, 1.01] is no distribution of depths: Cantelli's lower bound.
real singular_intensity(const Moments& raw, const Biased& b, real z_f, real alpha)
{
    const TwoPoint t = two_points(bias(raw, 0));
    real window = t.x1 < z_f ? 1 : 0;
    if (t.w2 > 0)
        window = t.x1 >= -0.01L && t.x2 <= 1.01L ? two_point_intensity(t, z_f) : cantelli(b, z_f).lower;
    return (1 - alpha) * window + (z_f > 0 ? alpha / 2 : 0) + (z_f > 1 ? alpha / 2 : 0);
}

}  // namespace

real msm_intensity(const Moments& raw, real z_f, real alpha)
{
    if (z_f <= 0) return 0;
    if (z_f > 1) return 1;
    const Biased b = bias(raw, alpha);
    const Hankel h = factor(b);
    real g;
    if (!h.definite) g = singular_intensity(raw, b, z_f, alpha);
    else {
        const Canonical c = canonical(b, h, z_f);
        if (!(c.lo >= 0 && c.hi <= 1 && std::isfinite(c.lo) && std::isfinite(c.hi))) g = hausdorff(b, z_f);
        else if (z_f <= c.lo) g = 0;
        else if (z_f <= c.hi) g = lagrange_weight(b, c.lo, {z_f, c.hi});
        else g = 1 - christoffel_weight(b, c, z_f);
    }
    // Part of the method (kernels/msm.h): four moments can only sharpen
    // Cantelli's two-moment bounds, so this clamp changes nothing for the
    // moments of a distribution on [0, 1]; it decides for moment vectors
    // that no such distribution has (the 16-bit quantization makes them).
    const Cantelli bounds = cantelli(b, z_f);
    return clampr(clampr(g, bounds.lower, bounds.upper), 0, 1);
}

Blockers msm_blockers(const Moments& raw, real z_f, real alpha)
{
    const Biased b = bias(raw, alpha);
    const Hankel h = factor(b);
    Blockers k{0, 0};
    if (h.definite) {
        const Canonical c = canonical(b, h, z_f);
        const real weight_z = clampr(christoffel_weight(b, c, z_f), 0, 1);
        const bool one_root = std::isfinite(c.lo) && !std::isfinite(c.hi);
        if (z_f <= c.lo) k = {0, c.lo};
        else if (z_f > c.hi || one_root)
            k = {1 - weight_z, (b.c + b.B[1] - weight_z * z_f) / std::max<real>(1 - weight_z, 1e-300L)};
        else k = {lagrange_weight(b, c.lo, {z_f, c.hi}), c.lo};
        if (!std::isfinite(k.weight) || !std::isfinite(k.depth)) k.weight = 0;
    } else {
        // The window's own one or two depths in front of z_f (not the bias atoms).
        const TwoPoint t = two_points(bias(raw, 0));
        if (t.w2 == 0) k = {t.x1 < z_f ? real(1) : real(0), t.x1};
        else if (z_f <= t.x1) k = {0, t.x1};
        else if (z_f <= t.x2) k = {t.w1, t.x1};
        else k = {1, raw.centre + raw.central[1]};
    }
    k.weight = clampr(k.weight, 0, 1);
    k.depth = clampr(k.depth, 0, std::max<real>(z_f, 0));
    return k;
}

// ---- the methods on one receiver ------------------------------------------

namespace {

struct Receiver64 {
    real u, v, z;      // u, v clamped into [0, 1]; z (msm-soft: z_f = z - depth_bias)
    float geometry_z;  // the float32 depth the window geometry uses (msm-soft: z - depth_bias in float32)
};

Receiver64 widen(Receiver r)
{
    return {real(std::clamp(r.u, 0.0f, 1.0f)), real(std::clamp(r.v, 0.0f, 1.0f)), real(r.z), r.z};
}

// Chebyshev visibility of one warp (EVSM): floor min_variance x slope^2.
real warp_visibility(const Moments& m, real receiver, real slope, const Params& p)
{
    return linstep(p.bleed, 1, chebyshev_upper(m, receiver, real(p.min_variance) * slope * slope));
}

struct BoxInputs {
    Moments a, b;  // VSM, MSM: a; EVSM: a = w+, b = w-
};

int raw_count(Method m) { return m == Method::Msm || m == Method::MsmSoft ? 4 : 2; }

real box_answer(Method m, const BoxInputs& in, real z, const Params& p)
{
    switch (m) {
    case Method::Vsm: return linstep(p.bleed, 1, chebyshev_upper(in.a, z, p.min_variance));
    case Method::Msm: return 1 - msm_intensity(in.a, z - real(p.msm_depth_bias), p.moment_bias);
    default: break;
    }
    const real zr = clampr(z - real(p.evsm_depth_bias), 0, 1);
    const real wp = positive_warp(zr, p);
    real visibility = warp_visibility(in.a, wp, real(p.positive) * wp, p);
    if (m == Method::Evsm4) {
        const real wn = negative_warp(zr, p);
        visibility = std::min(visibility, warp_visibility(in.b, wn, -real(p.negative) * wn, p));
    }
    return visibility;
}

BoxInputs box_inputs(Method m, const Image& depth, Box w, const Params& p)
{
    if (m == Method::Vsm || m == Method::Msm) return {box_moments(depth, w, identity, p), {}};
    BoxInputs in{box_moments(depth, w, positive_warp, p), {}};
    if (m == Method::Evsm4) in.b = box_moments(depth, w, negative_warp, p);
    return in;
}

Answer box_method(Method m, const Image& depth, Receiver r, const Params& p, bool with_movement)
{
    const Box w = texel_window(depth.width(), depth.height(), r.u, r.v, p.radius);
    const BoxInputs in = box_inputs(m, depth, w, p);
    const real z = real(r.z);
    Answer a{box_answer(m, in, z, p)};
    if (!with_movement) return a;
    const int count = raw_count(m);
    const unsigned patterns = m == Method::Evsm4 ? 16u : (1u << count);
    a.movement = 0;
    for (unsigned s = 0; s < patterns; ++s) {
        BoxInputs moved{perturbed(in.a, count, s & ((1u << count) - 1u), kPerturbation), {}};
        if (m == Method::Evsm4) moved.b = perturbed(in.b, 2, s >> 2, kPerturbation);
        a.movement = std::max(a.movement, std::fabs(box_answer(m, moved, z, p) - a.visibility));
    }
    return a;
}

// ---- VSSM and MSM-soft: blocker search, penumbra, filter -----------------

// The windows' geometry in float32, as the window contract states it
// (kernels/vssm.h, docs/fidelity.md): centre (u W, v H), the
// half-widths and the clipped corners are float32 values, and so is the
// blocker depth the filter width is computed from. Geometry decides which
// texels a window holds (a corner a float rounding away from a texel edge
// adds or drops a 1e-7 sliver of it); the arithmetic on the moments is
// what the reference checks.
Span float_span(const Image& depth, const Receiver64& r, float half_x, float half_y)
{
    const float W = float(depth.width()), H = float(depth.height());
    const float cx = float(r.u) * W, cy = float(r.v) * H;
    return {real(std::clamp(cx - half_x, 0.0f, W)), real(std::clamp(cx + half_x, 0.0f, W)),
            real(std::clamp(cy - half_y, 0.0f, H)), real(std::clamp(cy + half_y, 0.0f, H))};
}

// The light's half-width in texels along an axis (float32, as the library's geometry).
float search_half(int texels, const Params& p) { return std::max(p.light_size * 0.5f * float(texels), 0.5f); }

// MSM-soft's first search: fractional, centred at (u W, v H).
Span search_span(const Image& depth, const Receiver64& r, const Params& p)
{
    return float_span(depth, r, search_half(depth.width(), p), search_half(depth.height(), p));
}

// VSSM's search: the receiver's texel grown by R = floor(half-width) per axis,
// clipped (kernels/vssm.h, docs/moments.md "VSSM's search window").
Moments search_moments(Method m, const Image& depth, const Receiver64& r, const Params& p)
{
    if (m != Method::Vssm) return span_moments(depth, search_span(depth, r, p), identity, p);
    const int rx = int(std::floor(search_half(depth.width(), p)));
    const int ry = int(std::floor(search_half(depth.height(), p)));
    return box_moments(depth, texel_box(depth.width(), depth.height(), float(r.u), float(r.v), rx, ry), identity, p);
}

// PCSS: w = L (z - z_occ) / z_occ, a half-width of w W / 2 texels in [0.5, max_radius + 0.5].
Span filter_span(const Image& depth, const Receiver64& r, real z_occ, const Params& p)
{
    const float zg = r.geometry_z;
    const float occluder = std::max(float(z_occ), zg * float(kVssmMinOccluder));
    const float w = p.light_size * (zg - occluder) / occluder;
    const auto half = [&](int texels) {
        return std::clamp(w * (0.5f * float(texels)), 0.5f, float(p.max_radius) + 0.5f);
    };
    return float_span(depth, r, half(depth.width()), half(depth.height()));
}

// The filter window's depth (z_occ) from the search moments, or lit.
struct Search {
    bool lit;
    real z_occ;
};

Search soft_search(Method m, const Moments& search, const Receiver64& r, const Params& p)
{
    if (m == Method::Vssm) {
        const real pl = chebyshev_upper(search, r.z, p.min_variance);
        const real blocked = 1 - pl;
        const real mean = search.centre + search.central[1];
        return {blocked < kVssmNoBlocker, (mean - pl * r.z) / std::max(blocked, kVssmNoBlocker)};
    }
    const Blockers k = msm_blockers(search, r.z, p.moment_bias);
    return {k.weight < real(p.moment_bias) + kMsmNoBlocker || r.geometry_z <= 0, k.depth};
}

// msm-soft's reconstruction depth over the filter window: z_f lowered by
// plane_bias times the receiver plane's lowest point in the window (at a
// corner), at most plane_bias_max.
real plane_biased_depth(const Image& depth, const Span& window, const Receiver64& r, const Params& p)
{
    const real du0 = r.u - window.x0 / depth.width(), du1 = r.u - window.x1 / depth.width();
    const real dv0 = r.v - window.y0 / depth.height(), dv1 = r.v - window.y1 / depth.height();
    const real drop = std::max(p.plane_dzdu * du0, p.plane_dzdu * du1) + std::max(p.plane_dzdv * dv0, p.plane_dzdv * dv1);
    return r.z - std::min(real(p.plane_bias) * std::max(drop, real(0)), real(p.plane_bias_max));
}

real soft_filter_answer(Method m, const Moments& filter, real z, const Params& p)
{
    if (m == Method::Vssm) return linstep(p.bleed, 1, chebyshev_upper(filter, z, p.min_variance));
    return 1 - msm_intensity(filter, z, p.moment_bias);
}

// kernels/msm_soft.h: MSM-soft searches again for blockers over each filter
// window it found (PN_MSM_SOFT_SEARCHES windows in all, the light's first); VSSM once.
constexpr int kMsmSoftSearches = 3;

// The filter window from the first search's moments, or nothing for a lit
// receiver (no blocker in any of the searches).
std::optional<Span> refined_filter_span(Method m, const Image& depth, const Moments& first, const Receiver64& r,
                                        const Params& p)
{
    Search found = soft_search(m, first, r, p);
    const int searches = m == Method::MsmSoft ? kMsmSoftSearches : 1;
    for (int pass = 1; !found.lit && pass < searches; ++pass)
        found = soft_search(m, span_moments(depth, filter_span(depth, r, found.z_occ, p), identity, p), r, p);
    if (found.lit) return std::nullopt;
    return filter_span(depth, r, found.z_occ, p);
}

Answer soft_method(Method m, const Image& depth, Receiver rf, const Params& p, bool with_movement)
{
    Receiver64 r = widen(rf);
    if (m == Method::MsmSoft) {
        r.z -= real(p.msm_depth_bias);  // z_f for the reconstruction
        r.geometry_z = rf.z - p.msm_depth_bias;
    }
    const Moments search = search_moments(m, depth, r, p);
    const auto answer_from = [&](const Moments& s, unsigned filter_signs, bool perturb_filter) {
        const std::optional<Span> span = refined_filter_span(m, depth, s, r, p);
        if (!span) return real(1);
        Moments filter = span_moments(depth, *span, identity, p);
        if (perturb_filter) filter = perturbed(filter, raw_count(m), filter_signs, kPerturbation);
        return soft_filter_answer(m, filter, plane_biased_depth(depth, *span, r, p), p);
    };
    Answer a{answer_from(search, 0, false)};
    if (!with_movement) return a;
    const int count = raw_count(m);
    a.movement = 0;
    for (unsigned s = 0; s < (1u << count); ++s) {
        const Moments moved = perturbed(search, count, s, kPerturbation);
        const std::optional<Span> span = refined_filter_span(m, depth, moved, r, p);
        if (!span) {
            a.movement = std::max(a.movement, std::fabs(1 - a.visibility));
            continue;
        }
        const Moments filter = span_moments(depth, *span, identity, p);
        const real z = plane_biased_depth(depth, *span, r, p);
        for (unsigned f = 0; f < (1u << count); ++f) {
            const real v = soft_filter_answer(m, perturbed(filter, count, f, kPerturbation), z, p);
            a.movement = std::max(a.movement, std::fabs(v - a.visibility));
        }
    }
    return a;
}

}  // namespace

Answer evaluate(Method m, const Image& depth, Receiver r, const Params& p, bool with_movement)
{
    if (m == Method::Vssm || m == Method::MsmSoft) return soft_method(m, depth, r, p, with_movement);
    return box_method(m, depth, r, p, with_movement);
}

Verdict judge(Method m, const Image& depth, Receiver r, const Params& p, float library, const double* reference)
{
    const double tol = tolerance(m);
    Verdict v{};
    v.reference = reference ? *reference : double(evaluate(m, depth, r, p, false).visibility);
    v.deviation = std::isfinite(library) ? std::fabs(double(library) - v.reference) : INFINITY;
    v.bound = tol;
    v.movement = 0;
    const bool in_range = std::isfinite(library) && library >= 0.0f && library <= 1.0f;
    if (in_range && v.deviation <= tol) {
        v.pass = true;
        return v;
    }
    v.movement = double(evaluate(m, depth, r, p, true).movement);
    v.ill_conditioned = v.movement > tol;
    if (v.ill_conditioned) v.bound = tol + 2 * v.movement;
    v.pass = in_range && v.deviation <= v.bound;
    return v;
}

}  // namespace penumbra::testing::fidelity
