/* Cross (joint) bilateral filter of a shadow or occlusion mask, guided by depth
 * and optionally normals.
 *
 * For a pixel p of depth z_p, every mask channel becomes
 *     out(p) = sum_q w(p, q) m(q) / sum_q w(p, q),   w(p, q) = s(q - p) r(p, q),
 * over the window's taps q = p + (dx, dy) (Tomasi & Manduchi, ICCV 1998; with
 * a separate guide image, the joint form of Petschnigg et al. and Eisemann &
 * Durand, SIGGRAPH 2004).
 *  - The window is a list the host computes once per call: `taps` holds the
 *    offsets (dx, dy) as int pairs, `weights` pairs of the spatial weight
 *    s = exp(-(dx^2 + dy^2) / (2 sigma_s^2)) and its base-2 exponent -log2 s;
 *    every offset lies within [-radius, radius]. The host lists a square or
 *    OpenCV's disk (dx^2 + dy^2 <= radius^2), centre tap included.
 *  - r weighs the depth difference d = z_q - z_p, or, with `relative`,
 *    d = (z_q - z_p) / |z_p| (perspective depth, where a step of one unit
 *    means more near the eye than far away):
 *      Gaussian:  r = exp(-d^2 / (2 sigma_d^2)), OpenCV's
 *                 cv::ximgproc::jointBilateralFilter for an absolute d;
 *      threshold: r = 1 if |d| <= t, else 0: the Toy Story 3 blur of shadow
 *                 and SSAO masks, which drops samples across depth edges;
 *    times, with normals, exp(-|n_q - n_p|^2 / (2 sigma_n^2)) (Dammertz et
 *    al., edge-avoiding A-Trous, HPG 2010), in the same exponential.
 *    Exponentials are base 2 (the host folds log2(e) into the scales) and
 *    polynomial (bilateral_exp2_neg: 3e-6 relative), one per tap for s r
 *    together, floored at 2^-60.
 * All channels share the weights. The centre tap weighs s(0, 0) r = 1, so the
 * sum of weights is at least 1: a pixel whose neighbours are all rejected
 * keeps its own value, with no division by zero and no NaN.
 *
 * Inputs: mask, 1 to 4 planes of finite values (shadow or occlusion in [0, 1]
 * in practice); guide, one plane of finite depths in any unit (absolute:
 * sigma_d and t in that unit; relative: fractions of the centre depth, and a
 * centre depth of 0 rejects every other depth); normals, 3 planes of unit
 * vectors. Mask, guide, normals and output have the same width and height.
 * Output: planes as the mask, each value within the range of its window's.
 * Boundary: clamp-to-edge, as OpenCV's BORDER_REPLICATE: a tap outside the
 * image reads the nearest border pixel. Strips whose window lies inside the
 * image take unchecked loads; the others clamp every tap.
 *
 * Two schedules of the one filter (the host chooses), each an entry of the kernel table
 * for one strip and a span of strips and rows for the SIMD schedule:
 *  - full: every tap of the 2D window (bilateral_full);
 *  - separable: the horizontal pass (bilateral_horizontal: the taps' dx,
 *    range weights against the row's centre) writes `pass`, whose row 0 holds
 *    image row pass_first_row; the vertical pass (bilateral_vertical: the
 *    taps' dy) filters `pass` into the output. The host lists the 1D taps as
 *    pairs (d, d). Exact for a flat guide (the spatial Gaussian is
 *    separable); across depth edges an approximation (Pham & van Vliet, ICME
 *    2005) whose measured distance from the full filter docs/bilateral.md
 *    gives.
 * The full and horizontal kernels flag, in bad_rows, each row whose guide,
 * normals or mask hold a NaN or infinity at a pixel they centre on; every
 * pixel is a centre once, so a clean run has checked all of them.
 */
#ifndef PENUMBRA_BILATERAL_H
#define PENUMBRA_BILATERAL_H

/* The largest factor a depth difference is scaled by: with it, 0 times the
 * factor stays 0 (a relative difference at a centre depth of 0). */
#define PN_BILATERAL_MAX_SCALE 1e30f

/* Gaussian weights are floored at 2^-PN_BILATERAL_CUT: 8.7e-19 next to the
 * centre tap's 1 changes no float result, and the floor keeps weights, and
 * their products with mask values, far from subnormal floats, which cost a
 * hundred times a normal operation on x86. */
#define PN_BILATERAL_CUT 60.0f

/* The centre pixel of a strip: its depth, the factor that turns a depth
 * difference into d (Gaussian: into d sqrt(log2(e) / 2) / sigma_d), its normal. */
typedef struct {
    pn_float depth;
    pn_float diff_scale;
    pn_float nx, ny, nz;
} BilateralCentre;

/* Running weighted sums of up to four channels, and of the weights. */
typedef struct {
    pn_float m0, m1, m2, m3;
    pn_float weight;
} BilateralSum;

PN_FN BilateralCentre bilateral_centre(const BilateralParams p, PN_GLOBAL const float* guide,
                                       PN_GLOBAL const float* normals, int x, int y)
{
    BilateralCentre c;
    c.depth = pn_load(guide, p.guide, x, y);
    const float scale = p.threshold ? 1.0f : p.depth_scale;
    c.diff_scale = scale;
    if (p.relative) c.diff_scale = pn_min(scale / pn_max(pn_abs(c.depth), 1e-30f), PN_BILATERAL_MAX_SCALE);
    c.nx = 0.0f;
    c.ny = 0.0f;
    c.nz = 0.0f;
    if (p.use_normals) {
        c.nx = pn_load(PN_PLANE(normals, p.normals, 0), p.normals, x, y);
        c.ny = pn_load(PN_PLANE(normals, p.normals, 1), p.normals, x, y);
        c.nz = pn_load(PN_PLANE(normals, p.normals, 2), p.normals, x, y);
    }
    return c;
}

/* Flags row y if the strip's own guide, normals or mask values are not finite. */
PN_FN void bilateral_check(const BilateralParams p, BilateralCentre c, PN_GLOBAL const float* mask, int x, int y,
                           PN_GLOBAL int* bad_rows)
{
    pn_mask finite = pn_finite(c.depth);
    if (p.use_normals) finite = pn_and(finite, pn_and(pn_finite(c.nx), pn_and(pn_finite(c.ny), pn_finite(c.nz))));
    for (int k = 0; k < p.channels; ++k)
        finite = pn_and(finite, pn_finite(pn_load(PN_PLANE(mask, p.mask, k), p.mask, x, y)));
    pn_flag_any(bad_rows, y, pn_not(finite));
}

/* 1.5 2^23: adding it to a float in [0, 2^22) rounds the float to an integer
 * n, held in the sum's low mantissa bits: bits(sum) = bits(1.5 2^23) + n. */
#define PN_BILATERAL_ROUNDER 12582912.0f

/* 2^-min(s, PN_BILATERAL_CUT) for s >= 0, within 3e-6 relative, in a third
 * of the operations of a full-precision exp (which would dominate the
 * filter's cost). With n = round(s) and f = n - s in [-0.5, 0.5],
 * 2^-s = 2^f 2^-n. 2^f is a degree-4 polynomial fitted for the least maximum
 * relative error (2.9e-6) with p(0) = 1 exactly, so that 2^-0 = 1: the centre
 * tap weighs exactly 1. Horner by pn_fma. 2^-n: n subtracted from the
 * exponent field of p (in [0.7, 1.42], so the result stays a normal float);
 * bits(sum) << 23 is n << 23, as bits(1.5 2^23) << 23 wraps to 0. */
PN_FN pn_float bilateral_exp2_neg(pn_float s)
{
    const pn_float clamped = pn_min(s, PN_BILATERAL_CUT);
    const pn_float rounded = clamped + PN_BILATERAL_ROUNDER;
    const pn_float f = (rounded - PN_BILATERAL_ROUNDER) - clamped;
    pn_float poly = pn_fma(f, 0.009582854807f, 0.05590642989f);
    poly = pn_fma(poly, f, 0.2402409911f);
    poly = pn_fma(poly, f, 0.6931241751f);
    poly = pn_fma(poly, f, 1.0f);
    return pn_as_float(pn_as_uint(poly) - pn_ushl(pn_as_uint(rounded), 23));
}

/* A strip at (x, y): unchecked inside the image, else clamped to it. */
PN_FN pn_float bilateral_load(PN_GLOBAL const float* plane, pn_dims d, int x, int y, int inside)
{
    return inside ? pn_load_inside(plane, d, x, y) : pn_load_clamped(plane, d, x, y);
}

/* The normals' share of the exponent (base 2): |n_q - n_p|^2 normal_scale. */
PN_FN pn_float bilateral_normal_term(const BilateralParams p, BilateralCentre c, PN_GLOBAL const float* normals,
                                     int x, int y, int inside)
{
    const pn_float ex = bilateral_load(PN_PLANE(normals, p.normals, 0), p.normals, x, y, inside) - c.nx;
    const pn_float ey = bilateral_load(PN_PLANE(normals, p.normals, 1), p.normals, x, y, inside) - c.ny;
    const pn_float ez = bilateral_load(PN_PLANE(normals, p.normals, 2), p.normals, x, y, inside) - c.nz;
    return (ex * ex + ey * ey + ez * ez) * p.normal_scale;
}

/* w = s r for the tap strip at (x, y), given the tap's spatial weight s and
 * its base-2 exponent e = -log2 s. Gaussian: w = 2^-(e + d'^2), one
 * exponential for both factors, with d' the difference times the centre's
 * diff_scale. `plain`: the caller knows the range is Gaussian and there are
 * no normals (a constant, so that the tests fold away). */
PN_FN pn_float bilateral_weight(const BilateralParams p, BilateralCentre c, float spatial, float spatial_exponent,
                                PN_GLOBAL const float* guide, PN_GLOBAL const float* normals, int x, int y,
                                int inside, int plain)
{
    const pn_float d = (bilateral_load(guide, p.guide, x, y, inside) - c.depth) * c.diff_scale;
    if (plain) return bilateral_exp2_neg(pn_fma(d, d, spatial_exponent));
    if (p.threshold) {
        const pn_float kept = pn_select(pn_abs(d) <= p.depth_threshold, spatial, 0.0f);
        if (!p.use_normals) return kept;
        return kept * bilateral_exp2_neg(bilateral_normal_term(p, c, normals, x, y, inside));
    }
    pn_float exponent = pn_fma(d, d, spatial_exponent);
    if (p.use_normals) exponent = exponent + bilateral_normal_term(p, c, normals, x, y, inside);
    return bilateral_exp2_neg(exponent);
}

PN_FN BilateralSum bilateral_sum_zero(void)
{
    BilateralSum s;
    s.m0 = 0.0f;
    s.m1 = 0.0f;
    s.m2 = 0.0f;
    s.m3 = 0.0f;
    s.weight = 0.0f;
    return s;
}

/* Adds w times the strip at (x, y) of each plane of `planes` (geometry d). */
PN_FN void bilateral_add(BilateralSum* s, const BilateralParams p, PN_GLOBAL const float* planes, pn_dims d,
                         pn_float w, int x, int y, int inside)
{
    s->weight = s->weight + w;
    s->m0 = pn_fma(w, bilateral_load(planes, d, x, y, inside), s->m0);
    if (p.channels > 1) s->m1 = pn_fma(w, bilateral_load(PN_PLANE(planes, d, 1), d, x, y, inside), s->m1);
    if (p.channels > 2) s->m2 = pn_fma(w, bilateral_load(PN_PLANE(planes, d, 2), d, x, y, inside), s->m2);
    if (p.channels > 3) s->m3 = pn_fma(w, bilateral_load(PN_PLANE(planes, d, 3), d, x, y, inside), s->m3);
}

PN_FN int bilateral_clamp_row(int y, int height)
{
    return y < 0 ? 0 : (y >= height ? height - 1 : y);
}

/* Every tap of the list, centred on the strip at (x, y): offsets (dx, dy),
 * either zeroed by use_dx / use_dy (the separable passes). The mask planes
 * hold image row y in their row y - planes_first_row. `inside`: every tap lies
 * in the image; `plain`: see bilateral_weight. The kernels pass constants for
 * the interior of a plain Gaussian filter, the common case, so that its copy
 * of this loop has every uniform test folded away. */
PN_FN void bilateral_taps(BilateralSum* s, const BilateralParams p, BilateralCentre c,
                          PN_GLOBAL const float* planes, pn_dims planes_dims, int planes_first_row,
                          PN_GLOBAL const float* guide, PN_GLOBAL const float* normals, PN_GLOBAL const int* taps,
                          PN_GLOBAL const float* weights, int x, int y, int use_dx, int use_dy, int inside,
                          int plain)
{
    for (int k = 0; k < p.taps; ++k) {
        const int tx = use_dx ? x + taps[2 * k] : x;
        int ty = y;
        if (use_dy) ty = inside ? y + taps[2 * k + 1] : bilateral_clamp_row(y + taps[2 * k + 1], p.guide.height);
        const pn_float w = bilateral_weight(p, c, weights[2 * k], weights[2 * k + 1], guide, normals, tx, ty, inside,
                                            plain);
        bilateral_add(s, p, planes, planes_dims, w, tx, ty - planes_first_row, inside);
    }
}

/* The range weight needs neither the threshold test nor normals. */
PN_FN int bilateral_plain(const BilateralParams p)
{
    return !p.threshold && !p.use_normals;
}

/* Stores the normalised sums into row `row` of `planes` (geometry d). One
 * division, then a multiply per channel: a division costs ten multiplies. */
PN_FN void bilateral_store(PN_GLOBAL float* planes, pn_dims d, const BilateralParams p, BilateralSum s, int x,
                           int row)
{
    const pn_float inverse = 1.0f / s.weight;
    pn_store(planes, d, x, row, s.m0 * inverse);
    if (p.channels > 1) pn_store(PN_PLANE(planes, d, 1), d, x, row, s.m1 * inverse);
    if (p.channels > 2) pn_store(PN_PLANE(planes, d, 2), d, x, row, s.m2 * inverse);
    if (p.channels > 3) pn_store(PN_PLANE(planes, d, 3), d, x, row, s.m3 * inverse);
}

/* Rows y - radius .. y + radius all lie in the image. */
PN_FN int bilateral_rows_inside(const BilateralParams p, int y)
{
    return y - p.radius >= 0 && y + p.radius < p.guide.height;
}

/* ---- entry points ---------------------------------------------------------
 * The table's kernels filter one strip; the spans filter the strips from
 * x0 to x1 of rows [y0, y1). The SIMD schedule calls the spans (not table
 * entries, as moment_table.h's blocks) with whole rows: a call, and the work
 * the compiler hoists out of the strip loop, once per band of rows instead of
 * once per strip. The kernels call them with their one strip. */

/* The full 2D filter: every tap of the window. */
PN_FN void bilateral_full_span(PN_GLOBAL const float* mask, PN_GLOBAL const float* guide,
                               PN_GLOBAL const float* normals, PN_GLOBAL const int* taps,
                               PN_GLOBAL const float* weights, PN_GLOBAL float* out, PN_GLOBAL int* bad_rows,
                               const BilateralParams p, int x0, int x1, int y0, int y1)
{
    const int plain = bilateral_plain(p);
    for (int y = y0; y < y1; ++y) {
        const int rows_inside = bilateral_rows_inside(p, y);
        PN_FOR_STRIPS(x, x0, x1)
        {
            const BilateralCentre c = bilateral_centre(p, guide, normals, x, y);
            bilateral_check(p, c, mask, x, y, bad_rows);
            BilateralSum s = bilateral_sum_zero();
            const int inside = rows_inside && pn_strips_inside(p.guide, x - p.radius, x + p.radius);
            if (inside && plain)
                bilateral_taps(&s, p, c, mask, p.mask, 0, guide, normals, taps, weights, x, y, 1, 1, 1, 1);
            else
                bilateral_taps(&s, p, c, mask, p.mask, 0, guide, normals, taps, weights, x, y, 1, 1, inside, 0);
            bilateral_store(out, p.out, p, s, x, y);
        }
    }
}

PN_KERNEL void bilateral_full(PN_GLOBAL const float* mask, PN_GLOBAL const float* guide,
                              PN_GLOBAL const float* normals, PN_GLOBAL const int* taps,
                              PN_GLOBAL const float* weights, PN_GLOBAL float* out, PN_GLOBAL int* bad_rows,
                              const BilateralParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    bilateral_full_span(mask, guide, normals, taps, weights, out, bad_rows, p, pn_x, pn_x + 1, pn_y, pn_y + 1);
}

/* Separable, pass 1: image rows [y0, y1) filtered along x into rows
 * y - pass_first_row of `pass`. */
PN_FN void bilateral_horizontal_span(PN_GLOBAL const float* mask, PN_GLOBAL const float* guide,
                                     PN_GLOBAL const float* normals, PN_GLOBAL const int* taps,
                                     PN_GLOBAL const float* weights, PN_GLOBAL float* pass, PN_GLOBAL int* bad_rows,
                                     const BilateralParams p, int x0, int x1, int y0, int y1)
{
    const int plain = bilateral_plain(p);
    for (int y = y0; y < y1; ++y)
        PN_FOR_STRIPS(x, x0, x1)
        {
            const BilateralCentre c = bilateral_centre(p, guide, normals, x, y);
            bilateral_check(p, c, mask, x, y, bad_rows);
            BilateralSum s = bilateral_sum_zero();
            const int inside = pn_strips_inside(p.guide, x - p.radius, x + p.radius);
            if (inside && plain)
                bilateral_taps(&s, p, c, mask, p.mask, 0, guide, normals, taps, weights, x, y, 1, 0, 1, 1);
            else
                bilateral_taps(&s, p, c, mask, p.mask, 0, guide, normals, taps, weights, x, y, 1, 0, inside, 0);
            bilateral_store(pass, p.pass, p, s, x, y - p.pass_first_row);
        }
}

PN_KERNEL void bilateral_horizontal(PN_GLOBAL const float* mask, PN_GLOBAL const float* guide,
                                    PN_GLOBAL const float* normals, PN_GLOBAL const int* taps,
                                    PN_GLOBAL const float* weights, PN_GLOBAL float* pass, PN_GLOBAL int* bad_rows,
                                    const BilateralParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.mask.width, p.mask.height);
    bilateral_horizontal_span(mask, guide, normals, taps, weights, pass, bad_rows, p, pn_x, pn_x + 1, pn_y, pn_y + 1);
}

/* Separable, pass 2: `pass` filtered along y into rows [y0, y1) of the
 * output. Rows are clamped in image coordinates, then looked up in `pass`. */
PN_FN void bilateral_vertical_span(PN_GLOBAL const float* pass, PN_GLOBAL const float* guide,
                                   PN_GLOBAL const float* normals, PN_GLOBAL const int* taps,
                                   PN_GLOBAL const float* weights, PN_GLOBAL float* out, const BilateralParams p,
                                   int x0, int x1, int y0, int y1)
{
    const int plain = bilateral_plain(p);
    for (int y = y0; y < y1; ++y) {
        const int rows_inside = bilateral_rows_inside(p, y);
        PN_FOR_STRIPS(x, x0, x1)
        {
            const BilateralCentre c = bilateral_centre(p, guide, normals, x, y);
            BilateralSum s = bilateral_sum_zero();
            const int inside = rows_inside && pn_strips_inside(p.guide, x, x);
            if (inside && plain)
                bilateral_taps(&s, p, c, pass, p.pass, p.pass_first_row, guide, normals, taps, weights, x, y, 0, 1, 1,
                               1);
            else
                bilateral_taps(&s, p, c, pass, p.pass, p.pass_first_row, guide, normals, taps, weights, x, y, 0, 1,
                               inside, 0);
            bilateral_store(out, p.out, p, s, x, y);
        }
    }
}

PN_KERNEL void bilateral_vertical(PN_GLOBAL const float* pass, PN_GLOBAL const float* guide,
                                  PN_GLOBAL const float* normals, PN_GLOBAL const int* taps,
                                  PN_GLOBAL const float* weights, PN_GLOBAL float* out, const BilateralParams p,
                                  PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    bilateral_vertical_span(pass, guide, normals, taps, weights, out, p, pn_x, pn_x + 1, pn_y, pn_y + 1);
}

#endif
