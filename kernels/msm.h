/* Moment shadow mapping (Peters & Klein, "Moment Shadow Mapping", I3D 2015):
 * from the means b = (b1, b2, b3, b4) of z, z^2, z^3, z^4 over a window, the
 * sharpest lower bound on the shadow intensity P(Z < z) over all depth
 * distributions with those moments, in the paper's [0, 1] depth domain.
 *
 * Per receiver (u, v, z): the window is VSM's box (kernels/vsm.h), its
 * moments come from a four-channel table (kernels/encoded_table.h: the
 * optimized 16-bit quantization, decoded; or float sums of z^k), then
 *  1. bias: b' = (1 - alpha) b + alpha (1/2, 1/2, 1/2, 1/2), the moments of
 *     the window mixed with alpha of a distribution half at depth 0 and half
 *     at depth 1 (alpha = moment_bias); z_f = z - depth_bias;
 *  2. Hamburger: the Hankel matrix B = [1 b1 b2; b1 b2 b3; b2 b3 b4] factored
 *     as L D L^T without square roots; c = B^-1 (1, z_f, z_f^2) by forward
 *     substitution, scaling and back substitution; the roots z2 <= z3 of
 *     c1 + c2 x + c3 x^2. With the canonical representation {z2, z_f, z3},
 *     the three cases: z_f <= z2: 0; z2 < z_f <= z3: the weight of z2,
 *     (z_f z3 - b1 (z_f + z3) + b2) / ((z3 - z2)(z_f - z2)); z_f > z3:
 *     1 - (weight of z_f), and that weight is 1 / (c1 + c2 z_f + c3 z_f^2)
 *     (the Christoffel function: the same value as the paper's quotient,
 *     without the roots);
 *  3. Hausdorff fallback when a root leaves [0, 1]: the representation
 *     {0, z_f, r, 1} whose free point r makes E[Z (Z - 1)(Z - z_f)(Z - r)] = 0,
 *     r = E[Z^2 (Z - 1)(Z - z_f)] / E[Z (Z - 1)(Z - z_f)]; the intensity is the
 *     weight of 0, plus that of r when r < z_f (weights by Lagrange
 *     interpolation on the four points);
 *  4. visibility = 1 - clamp(intensity, 0, 1).
 *
 * Where the moments cannot carry a four-moment answer (docs/moments.md):
 *  - one depth: the window's own variance b2 - b1^2 is within the storage's
 *    noise (`noise_variance`, derived by the host from the quantization;
 *    on float tables at least the rounding of the table's entries there,
 *    msm_float_precision): the window is that depth, b1, and the answer is
 *    exact for it;
 *  - a (numerically) singular biased Hankel matrix: its last pivot d3 below
 *    a few float roundings of its terms (2^-22 b4') or below an eighth of
 *    the storage's noise (d3 is known only to about the moments' error).
 *    The bias cannot prevent it when the window's depths are 0 and 1 (where
 *    the bias distribution lives), and it leaves only bias-sized pivots at
 *    windows of two depths: the two-point distribution with the window's own
 *    moments (1, b1, b2, b3), support x1 <= x2 the roots of x^2 - s x + p,
 *    s = (b3 - b1 b2) / d2, p = (b1 b3 - b2^2) / d2, weight of x2
 *    (b1 - x1) / (x2 - x1); exact for a window of two depths. A fit that
 *    leaves [0, 1] falls back to Cantelli's bound.
 *  In both cases the bias distribution is added back exactly (alpha / 2 at
 *  depths 0 and 1), so that every path answers for the same biased window;
 *  for windows of one or two depths that answer is the truth, which the
 *  sharp bound of the biased moments only approaches (it can lie lighter,
 *  by up to 0.07 just behind the farther of two depths).
 * Safety net, everywhere: the intensity stays within Cantelli's two-sided
 * bounds from (b1', b2') (kernels/chebyshev.h's bound and its mirror): four
 * moments can only sharpen two, so this changes nothing in exact arithmetic
 * and keeps float rounding from lighting a covered window or darkening a
 * lit one; a non-finite intensity would be replaced by the lower bound.
 * Boundary: z_f <= 0 gives 1 (nothing lies in front of the near plane),
 * z_f > 1 gives 0 (everything lies in front), never NaN. Output in [0, 1].
 * Accuracy against the exact bound and the truth (tests/msm_test.cpp):
 * docs/moments.md.
 */
#ifndef PENUMBRA_MSM_H
#define PENUMBRA_MSM_H

#define PN_MSM_PIVOT_TOLERANCE 2.384185791015625e-07f /* 2^-22: a pivot below this share of its terms is zero */
#define PN_MSM_FIT_MARGIN 0.01f                        /* two-point fits: how far outside [0, 1] is rounding */
#define PN_MSM_DOMAIN_MARGIN 9.5367431640625e-07f   /* Hausdorff: z_f kept in [2^-20, 1 - 2^-20] */

PN_FN FourMoments msm_bias(FourMoments b, pn_float alpha)
{
    const pn_float keep = 1.0f - alpha;
    const pn_float shift = 0.5f * alpha;
    b.b1 = b.b1 * keep + shift;
    b.b2 = b.b2 * keep + shift;
    b.b3 = b.b3 * keep + shift;
    b.b4 = b.b4 * keep + shift;
    return b;
}

/* A divisor kept away from zero with its sign (a zero one becomes +tiny). */
PN_FN pn_float msm_safe(pn_float d)
{
    return pn_select(d < 0.0f, pn_min(d, -1e-30f), pn_max(d, 1e-30f));
}

/* L D L^T of B: D = diag(1, d2, d3), L32 = e / d2; kept undivided. */
typedef struct {
    pn_float d2;   /* b2 - b1^2, the variance */
    pn_float e;    /* L32 d2 = b3 - b1 b2 */
    pn_float d3d2; /* d3 d2 = (b4 - b2^2) d2 - e^2 */
} HankelFactors;

PN_FN HankelFactors msm_factor(FourMoments b)
{
    HankelFactors h;
    h.d2 = b.b2 - b.b1 * b.b1;
    h.e = b.b3 - b.b1 * b.b2;
    h.d3d2 = (b.b4 - b.b2 * b.b2) * h.d2 - h.e * h.e;
    return h;
}

PN_FN pn_mask msm_variance_positive(FourMoments b, HankelFactors h)
{
    return h.d2 > PN_MSM_PIVOT_TOLERANCE * b.b2;
}

/* The last pivot d3 must exceed both the float rounding of its terms and
 * the storage's noise: d3 is the variance of z^2 that (1, z) do not explain,
 * known to about the moments' own error, an eighth of the variance noise
 * (measured on one-depth 16-bit windows: 7e-7 against 1.02e-5). */
PN_FN pn_mask msm_positive_definite(FourMoments b, HankelFactors h, pn_float noise)
{
    const pn_float floor = pn_max(PN_MSM_PIVOT_TOLERANCE * b.b4, 0.125f * noise);
    return pn_and(msm_variance_positive(b, h), h.d3d2 > floor * h.d2);
}

/* The kernel polynomial c1 + c2 x + c3 x^2, c = B^-1 (1, z, z^2). Lanes where
 * B is not positive definite get finite values of no meaning. */
typedef struct {
    pn_float c1, c2, c3;
} KernelPolynomial;

PN_FN KernelPolynomial msm_solve(FourMoments b, HankelFactors h, pn_mask definite, pn_float z)
{
    const pn_float d2 = pn_select(definite, h.d2, 1.0f);
    const pn_float d3d2 = pn_select(definite, h.d3d2, 1.0f);
    const pn_float y2 = z - b.b1;                          /* L y = (1, z, z^2) */
    const pn_float y3d2 = (z * z - b.b2) * d2 - h.e * y2;  /* y3 d2 */
    KernelPolynomial c;
    c.c3 = y3d2 / d3d2;                                    /* y3 / d3 */
    c.c2 = (y2 - h.e * c.c3) / d2;                         /* y2 / d2 - L32 c3 */
    c.c1 = 1.0f - b.b1 * c.c2 - b.b2 * c.c3;
    return c;
}

PN_FN pn_float msm_polynomial_at(KernelPolynomial c, pn_float x)
{
    return c.c1 + (c.c2 + c.c3 * x) * x;
}

/* The roots z2 <= z3, by the cancellation-free pair q / c3 and c1 / q. A
 * root at infinity (c3 or q zero) comes out infinite or NaN; callers test
 * pn_finite. */
typedef struct {
    pn_float lo, hi;
} Roots;

PN_FN Roots msm_roots(KernelPolynomial c)
{
    const pn_float root = pn_sqrt(pn_max(c.c2 * c.c2 - 4.0f * c.c1 * c.c3, 0.0f));
    const pn_float q = pn_select(c.c2 < 0.0f, 0.5f * (root - c.c2), -0.5f * (c.c2 + root));
    const pn_float ra = q / c.c3;
    const pn_float rb = c.c1 / q;
    Roots r;
    r.lo = pn_min(ra, rb);
    r.hi = pn_max(ra, rb);
    return r;
}

PN_FN pn_mask msm_roots_in_domain(Roots r)
{
    const pn_mask finite = pn_and(pn_finite(r.lo), pn_finite(r.hi));
    return pn_and(finite, pn_and(r.lo >= 0.0f, r.hi <= 1.0f));
}

/* Step 2's three cases, for roots in [0, 1]. */
PN_FN pn_float msm_hamburger(FourMoments b, KernelPolynomial c, Roots r, pn_float z)
{
    const pn_float weight_z = 1.0f / msm_safe(msm_polynomial_at(c, z));
    const pn_float lower = (z * r.hi - b.b1 * (z + r.hi) + b.b2) / msm_safe((r.hi - r.lo) * (z - r.lo));
    return pn_select(z <= r.lo, 0.0f, pn_select(z <= r.hi, lower, 1.0f - weight_z));
}

/* Step 3: support {0, z, r, 1}, 0 < z < 1. */
PN_FN pn_float msm_hausdorff(FourMoments b, pn_float z_receiver)
{
    const pn_float z = pn_clamp(z_receiver, PN_MSM_DOMAIN_MARGIN, 1.0f - PN_MSM_DOMAIN_MARGIN);
    const pn_float a = b.b3 - (1.0f + z) * b.b2 + z * b.b1;   /* E[Z (Z - 1)(Z - z)] */
    const pn_float n = b.b4 - (1.0f + z) * b.b3 + z * b.b2;   /* E[Z^2 (Z - 1)(Z - z)] */
    const pn_float r = pn_clamp(n / msm_safe(a), 0.0f, 1.0f);
    /* r >= z: only 0 is in front; its weight E[(Z - z)(Z - r)(Z - 1)] / (-z r). */
    const pn_float at_zero = (b.b3 - (z + r + 1.0f) * b.b2 + (z * r + z + r) * b.b1 - z * r) / msm_safe(-z * r);
    /* r < z: 0 and r are in front: 1 - (weights of z and 1). */
    const pn_float at_z = (b.b3 - (1.0f + r) * b.b2 + r * b.b1) / msm_safe(z * pn_max(z - r, 1e-30f) * (z - 1.0f));
    const pn_float at_one = (b.b3 - (z + r) * b.b2 + z * r * b.b1) / ((1.0f - z) * (1.0f - r) + 1e-30f);
    return pn_select(r < z, 1.0f - at_z - at_one, at_zero);
}

/* The two-point distribution with moments (1, b1, b2, b3): x1 <= x2, the
 * weight of x2. Meaningful where b2 - b1^2 > 0. */
typedef struct {
    pn_float x1, x2, upper_weight;
} TwoPoints;

PN_FN TwoPoints msm_two_points(FourMoments b, HankelFactors h)
{
    const pn_float d2 = msm_safe(h.d2);
    const pn_float half_sum = 0.5f * h.e / d2;
    const pn_float product = (b.b1 * b.b3 - b.b2 * b.b2) / d2;
    const pn_float spread = pn_sqrt(pn_max(half_sum * half_sum - product, 0.0f));
    TwoPoints t;
    t.x1 = half_sum - spread;
    t.x2 = half_sum + spread;
    t.upper_weight = pn_clamp((b.b1 - t.x1) / pn_max(t.x2 - t.x1, 1e-30f), 0.0f, 1.0f);
    return t;
}

/* A fit that leaves [0, 1] by more than rounding is not a distribution of depths. */
PN_FN pn_mask msm_two_points_valid(TwoPoints t)
{
    return pn_and(t.x1 >= -PN_MSM_FIT_MARGIN, t.x2 <= 1.0f + PN_MSM_FIT_MARGIN);
}

PN_FN pn_float msm_two_point_intensity(TwoPoints t, pn_float z)
{
    return pn_select(z <= t.x1, 0.0f, pn_select(z <= t.x2, 1.0f - t.upper_weight, 1.0f));
}

/* Cantelli's two-moment bounds on P(Z < z) (kernels/chebyshev.h's bound, and
 * the same bound on the lower tail, P(Z <= z), through Z -> -Z): the
 * interval every distribution with mean b1 and second moment b2 keeps to. */
PN_FN pn_float msm_cantelli_lower(FourMoments b, pn_float z)
{
    DepthMoments m;
    m.mean = b.b1;
    m.mean_sq = b.b2;
    return 1.0f - chebyshev_upper_bound(m, z, 0.0f);
}

PN_FN pn_float msm_cantelli_upper(FourMoments b, pn_float z)
{
    DepthMoments reflected;
    reflected.mean = -b.b1;
    reflected.mean_sq = b.b2;
    return chebyshev_upper_bound(reflected, -z, 0.0f);
}

/* The window's own distribution where the moments determine it: one depth
 * (variance within the storage's noise), or two. The bias distribution is
 * then added back exactly: alpha / 2 at depth 0, alpha / 2 at depth 1. */
PN_FN pn_float msm_with_bias_atoms(pn_float window, pn_float z, pn_float alpha)
{
    const pn_float atoms = pn_select(z > 0.0f, 0.5f * alpha, 0.0f) + pn_select(z > 1.0f, 0.5f * alpha, 0.0f);
    return (1.0f - alpha) * window + atoms;
}

/* What a window's moments can be trusted to: the moment bias and the
 * variance its storage cannot resolve (see the header comment). */
typedef struct {
    pn_float alpha;
    pn_float noise;
} MsmPrecision;

PN_FN MsmPrecision msm_exact_precision(const MomentParams p)
{
    MsmPrecision s;
    s.alpha = p.moment_bias;
    s.noise = p.noise_variance;
    return s;
}

/* A float table's window means carry the rounding of its entries, which
 * grow with the distance from the origin: an entry S(x, y) sums up to x y
 * values of at most 1 and is rounded to 2^-24 of itself, a few times over
 * along the scan. The variance of a window of area A whose far corner is
 * (x1, y1) is then known to about 8 2^-24 x1 y1 / A; where that exceeds the
 * storage's noise it is the noise (docs/moment_table.md measures the float
 * table's error). The bias stays the caller's: raising it to cover a large
 * map's rounding would lift every shadow by alpha / 2. */
PN_FN MsmPrecision msm_float_precision(pn_float x1, pn_float y1, pn_float area, const MomentParams p)
{
    MsmPrecision s;
    s.noise = pn_max(p.noise_variance, (8.0f * 5.9604644775390625e-08f) * x1 * y1 / area);
    s.alpha = p.moment_bias;
    return s;
}

/* The intensity at z = z_f of a window's moments `raw` (steps 1-3 and the
 * fallbacks; see the header comment). */
PN_FN pn_float msm_intensity(FourMoments raw, pn_float z, MsmPrecision precision)
{
    const pn_float alpha = precision.alpha;
    const pn_mask one_point = raw.b2 - raw.b1 * raw.b1 <= precision.noise;
    const FourMoments b = msm_bias(raw, alpha);
    const HankelFactors h = msm_factor(b);
    const pn_mask definite = pn_and(msm_positive_definite(b, h, precision.noise), pn_not(one_point));
    const KernelPolynomial c = msm_solve(b, h, definite, z);
    const Roots r = msm_roots(c);
    const pn_mask hamburger = msm_roots_in_domain(r);
    pn_float g = msm_hamburger(b, c, r, z);
    if (pn_any(pn_and(definite, pn_not(hamburger)))) g = pn_select(hamburger, g, msm_hausdorff(b, z));
    const pn_float lower = msm_cantelli_lower(b, z);
    if (pn_any(pn_not(definite))) {
        const TwoPoints t = msm_two_points(raw, msm_factor(raw));
        const pn_float two = pn_select(msm_two_points_valid(t), msm_two_point_intensity(t, z), lower);
        const pn_float one = pn_select(raw.b1 < z, 1.0f, 0.0f);
        g = pn_select(definite, g, msm_with_bias_atoms(pn_select(one_point, one, two), z, alpha));
    }
    g = pn_select(pn_finite(g), g, lower);
    g = pn_clamp(g, lower, msm_cantelli_upper(b, z));
    return pn_select(z <= 0.0f, 0.0f, pn_select(z > 1.0f, 1.0f, g));
}

PN_FN pn_float msm_visibility(FourMoments raw, pn_float receiver_z, MsmPrecision precision, const MomentParams p)
{
    return 1.0f - msm_intensity(raw, receiver_z - p.depth_bias, precision);
}

/* The window's moments: power sums are the moments; optimized sums decode. */
PN_FN FourMoments msm_moments_from_means(const pn_float* mean, int storage)
{
    if (storage == PN_MOMENTS_OPTIMIZED16) return msm_decode_optimized(mean[0], mean[1], mean[2], mean[3]);
    FourMoments m;
    m.b1 = mean[0];
    m.b2 = mean[1];
    m.b3 = mean[2];
    m.b4 = mean[3];
    return m;
}

PN_KERNEL void msm_float(PN_GLOBAL const float* table, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                         PN_GLOBAL int* bad_rows, const MomentParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const Receiver r = load_checked_receiver(receivers, p.receivers, pn_x, pn_y, bad_rows);
    const TexelWindow w = texel_window(p.table, r.u, r.v, p.radius);
    const pn_float area = texel_window_area(w);
    pn_float mean[4];
    for (int k = 0; k < 4; ++k) mean[k] = encoded_box_mean_float(table, p.table, k, w, area);
    const MsmPrecision precision = msm_float_precision(pn_int_to_float(w.x1), pn_int_to_float(w.y1), area, p);
    pn_store(out, p.out, pn_x, pn_y, msm_visibility(msm_moments_from_means(mean, p.storage), r.z, precision, p));
}

PN_KERNEL void msm_exact(PN_GLOBAL const uint* table, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                         PN_GLOBAL int* bad_rows, const MomentParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const Receiver r = load_checked_receiver(receivers, p.receivers, pn_x, pn_y, bad_rows);
    const TexelWindow w = texel_window(p.table, r.u, r.v, p.radius);
    const pn_float area = texel_window_area(w);
    pn_float mean[4];
    for (int k = 0; k < 4; ++k) mean[k] = encoded_box_mean_exact(table, p.table, k, w, area);
    const FourMoments m = msm_moments_from_means(mean, PN_MOMENTS_OPTIMIZED16);
    pn_store(out, p.out, pn_x, pn_y, msm_visibility(m, r.z, msm_exact_precision(p), p));
}

#endif
