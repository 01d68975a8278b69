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
 * Arithmetic: everything from the window's means on is double (the dialect's
 * pn_double): the means come exact to the storage's step from a limb table
 * (kernels/moment_table.h: 3 limbs, 2^-49) or, with the opt-in 16-bit
 * optimized quantization, as exact means of the 16-bit steps, dequantized
 * in double. The Hankel pivots of raw moments cancel by about 3500 on
 * ordinary windows (the reason a float32 LDL^T failed), up to 1e8 at one
 * depth near 0; in double that costs at most 1e8 x 2^-53 = 1e-8 relative,
 * below the storage's own step, so the moments are not centred first.
 *
 * Where the moments cannot carry a four-moment answer (the shortcuts), only
 * where the Hankel matrix is singular to the arithmetic and storage:
 *  - one depth: the window's own variance b2 - b1^2 is at most `floor`
 *    (`pivot_floor`, set by the host: 2^-45, sixteen steps of a 3-limb
 *    table, or 0 for dequantized 16-bit moments; float tables raise it,
 *    msm_float_precision): the window is that depth, b1, and the answer is
 *    exact for it;
 *  - a singular biased Hankel matrix: its last pivot d3 at most 2^-44 of
 *    b4' (double rounding, with margin) or `floor`. With alpha > 0 that
 *    happens only when the window's depths are (nearly) all 0 and 1, where
 *    the bias distribution lives, or at one depth z very near 0 or 1
 *    (det B' = (alpha / 2)^2 (1 - alpha) z^2 (1 - z)^2 falls towards the
 *    floor), where the float64 answer itself is ill-conditioned; with
 *    alpha = 0 at windows of one or two depths. There: the two-point distribution with the window's own
 *    moments (1, b1, b2, b3), support x1 <= x2 the roots of x^2 - s x + p,
 *    s = (b3 - b1 b2) / d2, p = (b1 b3 - b2^2) / d2, weight of x2
 *    (b1 - x1) / (x2 - x1); exact for a window of two depths. A fit that
 *    leaves [0, 1] (by more than 0.01) falls back to Cantelli's bound.
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
 * Accuracy against the exact bound and the truth (tests/kernels/msm_test.cpp):
 * docs/moments.md.
 */
#ifndef PENUMBRA_MSM_H
#define PENUMBRA_MSM_H

#define PN_MSM_PIVOT_TOLERANCE 5.684341886080802e-14 /* 2^-44: a pivot below this share of its terms is zero in double */
#define PN_MSM_FIT_MARGIN 0.01                        /* two-point fits: how far outside [0, 1] is rounding */
#define PN_MSM_DOMAIN_MARGIN 9.5367431640625e-07   /* Hausdorff: z_f kept in [2^-20, 1 - 2^-20] */

PN_FN FourMoments msm_bias(FourMoments b, pn_double alpha)
{
    const pn_double keep = 1.0 - alpha;
    const pn_double shift = 0.5 * alpha;
    b.b1 = b.b1 * keep + shift;
    b.b2 = b.b2 * keep + shift;
    b.b3 = b.b3 * keep + shift;
    b.b4 = b.b4 * keep + shift;
    return b;
}

/* A divisor kept away from zero with its sign (a zero one becomes +tiny). */
PN_FN pn_double msm_safe(pn_double d)
{
    return pn_dselect(d < 0.0, pn_dmin(d, -1e-300), pn_dmax(d, 1e-300));
}

/* L D L^T of B: D = diag(1, d2, d3), L32 = e / d2; kept undivided. */
typedef struct {
    pn_double d2;   /* b2 - b1^2, the variance */
    pn_double e;    /* L32 d2 = b3 - b1 b2 */
    pn_double d3d2; /* d3 d2 = (b4 - b2^2) d2 - e^2 */
} HankelFactors;

PN_FN HankelFactors msm_factor(FourMoments b)
{
    HankelFactors h;
    h.d2 = b.b2 - b.b1 * b.b1;
    h.e = b.b3 - b.b1 * b.b2;
    h.d3d2 = (b.b4 - b.b2 * b.b2) * h.d2 - h.e * h.e;
    return h;
}

PN_FN pn_dmask msm_variance_positive(FourMoments b, HankelFactors h)
{
    return h.d2 > PN_MSM_PIVOT_TOLERANCE * b.b2;
}

/* The last pivot d3 must exceed both the double rounding of its terms
 * (2^-44 of b4, 256 roundings) and the floor the storage sets (`floor`:
 * a few steps of a limb table's rounding, 0 for dequantized 16-bit moments,
 * which are exact): below that the matrix is singular to the arithmetic. */
PN_FN pn_dmask msm_positive_definite(FourMoments b, HankelFactors h, pn_double floor)
{
    const pn_double tolerance = pn_dmax(PN_MSM_PIVOT_TOLERANCE * b.b4, floor);
    return pn_dand(pn_dand(msm_variance_positive(b, h), h.d2 > floor), h.d3d2 > tolerance * h.d2);
}

/* The kernel polynomial c1 + c2 x + c3 x^2, c = B^-1 (1, z, z^2). Lanes where
 * B is not positive definite get finite values of no meaning. */
typedef struct {
    pn_double c1, c2, c3;
} KernelPolynomial;

PN_FN KernelPolynomial msm_solve(FourMoments b, HankelFactors h, pn_dmask definite, pn_double z)
{
    const pn_double d2 = pn_dselect(definite, h.d2, 1.0);
    const pn_double d3d2 = pn_dselect(definite, h.d3d2, 1.0);
    const pn_double y2 = z - b.b1;                          /* L y = (1, z, z^2) */
    const pn_double y3d2 = (z * z - b.b2) * d2 - h.e * y2;  /* y3 d2 */
    KernelPolynomial c;
    c.c3 = y3d2 / d3d2;                                    /* y3 / d3 */
    c.c2 = (y2 - h.e * c.c3) / d2;                         /* y2 / d2 - L32 c3 */
    c.c1 = 1.0 - b.b1 * c.c2 - b.b2 * c.c3;
    return c;
}

PN_FN pn_double msm_polynomial_at(KernelPolynomial c, pn_double x)
{
    return c.c1 + (c.c2 + c.c3 * x) * x;
}

/* The roots z2 <= z3, by the cancellation-free pair q / c3 and c1 / q. A
 * root at infinity (c3 or q zero) comes out infinite or NaN; callers test
 * pn_finite. */
typedef struct {
    pn_double lo, hi;
} Roots;

PN_FN Roots msm_roots(KernelPolynomial c)
{
    const pn_double root = pn_dsqrt(pn_dmax(c.c2 * c.c2 - 4.0 * c.c1 * c.c3, 0.0));
    const pn_double q = pn_dselect(c.c2 < 0.0, 0.5 * (root - c.c2), -0.5 * (c.c2 + root));
    const pn_double ra = q / c.c3;
    const pn_double rb = c.c1 / q;
    Roots r;
    r.lo = pn_dmin(ra, rb);
    r.hi = pn_dmax(ra, rb);
    return r;
}

PN_FN pn_dmask msm_roots_in_domain(Roots r)
{
    const pn_dmask finite = pn_dand(pn_dfinite(r.lo), pn_dfinite(r.hi));
    return pn_dand(finite, pn_dand(r.lo >= 0.0, r.hi <= 1.0));
}

/* Step 2's three cases, for roots in [0, 1]. */
PN_FN pn_double msm_hamburger(FourMoments b, KernelPolynomial c, Roots r, pn_double z)
{
    const pn_double weight_z = 1.0 / msm_safe(msm_polynomial_at(c, z));
    const pn_double lower = (z * r.hi - b.b1 * (z + r.hi) + b.b2) / msm_safe((r.hi - r.lo) * (z - r.lo));
    return pn_dselect(z <= r.lo, 0.0, pn_dselect(z <= r.hi, lower, 1.0 - weight_z));
}

/* Step 3: support {0, z, r, 1}, 0 < z < 1. */
PN_FN pn_double msm_hausdorff(FourMoments b, pn_double z_receiver)
{
    const pn_double z = pn_dclamp(z_receiver, PN_MSM_DOMAIN_MARGIN, 1.0 - PN_MSM_DOMAIN_MARGIN);
    const pn_double a = b.b3 - (1.0 + z) * b.b2 + z * b.b1;   /* E[Z (Z - 1)(Z - z)] */
    const pn_double n = b.b4 - (1.0 + z) * b.b3 + z * b.b2;   /* E[Z^2 (Z - 1)(Z - z)] */
    const pn_double r = pn_dclamp(n / msm_safe(a), 0.0, 1.0);
    /* r >= z: only 0 is in front; its weight E[(Z - z)(Z - r)(Z - 1)] / (-z r). */
    const pn_double at_zero = (b.b3 - (z + r + 1.0) * b.b2 + (z * r + z + r) * b.b1 - z * r) / msm_safe(-z * r);
    /* r < z: 0 and r are in front: 1 - (weights of z and 1). */
    const pn_double at_z = (b.b3 - (1.0 + r) * b.b2 + r * b.b1) / msm_safe(z * pn_dmax(z - r, 1e-300) * (z - 1.0));
    const pn_double at_one = (b.b3 - (z + r) * b.b2 + z * r * b.b1) / ((1.0 - z) * (1.0 - r) + 1e-300);
    return pn_dselect(r < z, 1.0 - at_z - at_one, at_zero);
}

/* The two-point distribution with moments (1, b1, b2, b3): x1 <= x2, the
 * weight of x2. Meaningful where b2 - b1^2 > 0. */
typedef struct {
    pn_double x1, x2, upper_weight;
} TwoPoints;

PN_FN TwoPoints msm_two_points(FourMoments b, HankelFactors h)
{
    const pn_double d2 = msm_safe(h.d2);
    const pn_double half_sum = 0.5 * h.e / d2;
    const pn_double product = (b.b1 * b.b3 - b.b2 * b.b2) / d2;
    const pn_double spread = pn_dsqrt(pn_dmax(half_sum * half_sum - product, 0.0));
    TwoPoints t;
    t.x1 = half_sum - spread;
    t.x2 = half_sum + spread;
    t.upper_weight = pn_dclamp((b.b1 - t.x1) / pn_dmax(t.x2 - t.x1, 1e-300), 0.0, 1.0);
    return t;
}

/* A fit that leaves [0, 1] by more than rounding is not a distribution of depths. */
PN_FN pn_dmask msm_two_points_valid(TwoPoints t)
{
    return pn_dand(t.x1 >= -PN_MSM_FIT_MARGIN, t.x2 <= 1.0 + PN_MSM_FIT_MARGIN);
}

PN_FN pn_double msm_two_point_intensity(TwoPoints t, pn_double z)
{
    return pn_dselect(z <= t.x1, 0.0, pn_dselect(z <= t.x2, 1.0 - t.upper_weight, 1.0));
}

/* Cantelli's two-moment bounds on P(Z < z) (kernels/chebyshev.h's bound
 * 1 - P(Z >= z), and the same bound on the lower tail, P(Z <= z), through
 * Z -> -Z): the interval every distribution with mean b1 and second moment
 * b2 keeps to. Both tails share the quotient p = s^2 / (s^2 + (z - b1)^2)
 * (the reflection keeps s^2 and (z - b1)^2 to the bit), so it is divided
 * once: double divisions are much of MSM's time (docs/moment_table.md). */
typedef struct {
    pn_double lower, upper;
} CantelliBounds;

PN_FN CantelliBounds msm_cantelli(FourMoments b, pn_double z)
{
    const pn_double variance = pn_dmax(b.b2 - b.b1 * b.b1, 0.0);
    const pn_double d = z - b.b1;
    /* As chebyshev_upper_bound: the floor keeps 0 / 0 out. */
    const pn_double p = variance / pn_dmax(variance + d * d, 1e-300);
    CantelliBounds c;
    c.lower = pn_dselect(z <= b.b1, 0.0, 1.0 - p);
    c.upper = pn_dselect(z >= b.b1, 1.0, p);
    return c;
}

/* The window's own distribution where the moments determine it: one depth
 * (variance within the storage's noise), or two. The bias distribution is
 * then added back exactly: alpha / 2 at depth 0, alpha / 2 at depth 1. */
PN_FN pn_double msm_with_bias_atoms(pn_double window, pn_double z, pn_double alpha)
{
    const pn_double atoms = pn_dselect(z > 0.0, 0.5 * alpha, 0.0) + pn_dselect(z > 1.0, 0.5 * alpha, 0.0);
    return (1.0 - alpha) * window + atoms;
}

/* What a window's moments can be trusted to: the moment bias and the pivot
 * floor of their storage (see the header comment). */
typedef struct {
    pn_double alpha;
    pn_double floor;
} MsmPrecision;

PN_FN MsmPrecision msm_exact_precision(const MomentParams p)
{
    MsmPrecision s;
    s.alpha = p.moment_bias;
    s.floor = p.pivot_floor;
    return s;
}

/* A float table's window means carry the rounding of its entries, which
 * grow with the distance from the origin: an entry S(x, y) sums up to x y
 * values of at most 1 and is rounded to 2^-24 of itself, a few times over
 * along the scan. The variance of a window of area A whose far corner is
 * (x1, y1) is then known to about 8 2^-24 x1 y1 / A (docs/moment_table.md
 * measures the float table's error). */
PN_FN MsmPrecision msm_float_precision(pn_double x1, pn_double y1, pn_double area, const MomentParams p)
{
    MsmPrecision s;
    s.floor = pn_dmax(p.pivot_floor, (8.0 * 5.9604644775390625e-08) * x1 * y1 / area);
    s.alpha = p.moment_bias;
    return s;
}

/* The intensity at z = z_f of a window's moments `raw` (steps 1-3 and the
 * fallbacks; see the header comment). */
PN_FN pn_double msm_intensity(FourMoments raw, pn_double z, MsmPrecision precision)
{
    const pn_double alpha = precision.alpha;
    const pn_dmask one_point = raw.b2 - raw.b1 * raw.b1 <= precision.floor;
    const FourMoments b = msm_bias(raw, alpha);
    const HankelFactors h = msm_factor(b);
    const pn_dmask definite = msm_positive_definite(b, h, precision.floor);
    const KernelPolynomial c = msm_solve(b, h, definite, z);
    const Roots r = msm_roots(c);
    const pn_dmask hamburger = msm_roots_in_domain(r);
    pn_double g = msm_hamburger(b, c, r, z);
    if (pn_dany(pn_dand(definite, pn_dnot(hamburger)))) g = pn_dselect(hamburger, g, msm_hausdorff(b, z));
    const CantelliBounds cantelli = msm_cantelli(b, z);
    const pn_double lower = cantelli.lower;
    if (pn_dany(pn_dnot(definite))) {
        const TwoPoints t = msm_two_points(raw, msm_factor(raw));
        const pn_double two = pn_dselect(msm_two_points_valid(t), msm_two_point_intensity(t, z), lower);
        const pn_double one = pn_dselect(raw.b1 < z, 1.0, 0.0);
        g = pn_dselect(definite, g, msm_with_bias_atoms(pn_dselect(one_point, one, two), z, alpha));
    }
    g = pn_dselect(pn_dfinite(g), g, lower);
    g = pn_dclamp(g, lower, cantelli.upper);
    return pn_dselect(z <= 0.0, 0.0, pn_dselect(z > 1.0, 1.0, g));
}

/* z_f = z - depth_bias in double. */
PN_FN pn_float msm_visibility(FourMoments raw, pn_float receiver_z, MsmPrecision precision, const MomentParams p)
{
    const pn_double z_f = pn_to_double(receiver_z) - (double)p.depth_bias;
    return pn_double_to_float(1.0 - msm_intensity(raw, z_f, precision));
}

/* The window's moments: power sums are the moments; optimized sums decode. */
PN_FN FourMoments msm_moments_from_means(const pn_double* mean, int storage)
{
    if (storage == PN_MOMENTS_OPTIMIZED16) return msm_decode_optimized(mean[0], mean[1], mean[2], mean[3]);
    FourMoments m;
    m.b1 = mean[0];
    m.b2 = mean[1];
    m.b3 = mean[2];
    m.b4 = mean[3];
    return m;
}

/* The four window means of a float table, and the precision their rounding
 * allows. */
PN_FN MsmPrecision msm_box_means_float(PN_GLOBAL const float* table, const MomentParams p, TexelWindow w,
                                       pn_double* mean)
{
    const pn_float area = texel_window_area(w);
    for (int k = 0; k < 4; ++k) mean[k] = encoded_box_mean_float(table, p.table, k, w, area);
    return msm_float_precision(pn_int_to_double(w.x1), pn_int_to_double(w.y1), pn_to_double(area), p);
}

/* The four window means of an exact table: a limb table of z..z^4
 * (PN_MOMENTS_POWER) or sums of 16-bit steps of the optimized moments; one
 * reciprocal of the area, as direct_box_means (kernels/box_window.h). */
PN_FN MsmPrecision msm_box_means_exact(PN_GLOBAL const uint* table, const MomentParams p, TexelWindow w,
                                       pn_double* mean)
{
    const pn_double inverse_area = 1.0 / pn_int_to_double((w.x1 - w.x0) * (w.y1 - w.y0));
    const double unit = sat_limb_unit(p.limbs);
    for (int k = 0; k < 4; ++k)
        mean[k] = sat_limb_box_sum(table, p.table, p.limbs, k, unit, w.x0, w.x1, w.y0, w.y1) * inverse_area;
    return msm_exact_precision(p);
}

#define PN_MSM_KERNEL(variant, T)                                                                            \
PN_KERNEL void msm_##variant(PN_LOOKUP_ARGS(T, MomentParams))                                                \
{                                                                                                            \
    PN_BOX_LOOKUP_BEGIN(r, w);                                                                               \
    pn_double mean[4];                                                                                       \
    const MsmPrecision precision = msm_box_means_##variant(table, p, w, mean);                               \
    PN_LOOKUP_STORE(msm_visibility(msm_moments_from_means(mean, p.storage), r.z, precision, p));             \
}
PN_TABLE_VARIANTS(PN_MSM_KERNEL)

/* The same window's means of z .. z^4 summed directly from the depth map
 * (kernels/box_window.h), held to the exact table's precision (they are at
 * least as close to the float32 depths' own moments). */
PN_KERNEL void msm_direct(PN_LOOKUP_ARGS_OF(float, depth, MomentParams))
{
    PN_BOX_LOOKUP_BEGIN(r, w);
    pn_double mean[4];
    const DirectMap map = direct_map(p.direct, p.table, p.convention);
    direct_box_means(depth, map, w, p.radius, PN_TABLE_POWERS, 0.0f, 0.0f, 4, mean);
    PN_LOOKUP_STORE(msm_visibility(msm_moments_from_means(mean, PN_MOMENTS_POWER), r.z, msm_exact_precision(p), p));
}

#endif
