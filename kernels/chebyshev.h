/* The one-tailed Chebyshev bound on a window's depth distribution, and the
 * window statistics it needs, read from a moment table.
 *
 * Variance shadow maps (Donnelly & Lauritzen, I3D 2006): for a receiver at
 * depth z and a window whose depths have mean mu and variance s^2,
 *     P(depth >= z) <= p_max = s^2 / (s^2 + (z - mu)^2)   for z > mu,  else 1,
 * which is the visibility estimate. s^2 is floored at `min_variance` (depth^2
 * units) against acne and precision loss, and light bleeding is reduced by
 * remapping p_max with linstep(bleed, 1, p) (Lauritzen, GPU Gems 3 ch. 8).
 * Output in [0, 1]; a window of one depth (zero variance) gives 1 in front of
 * it and ~0 behind it, never NaN (the denominator is >= min_variance > 0).
 * Arithmetic: the window's moments arrive in double (from an exact limb
 * table, kernels/moment_table.h) and the bound is evaluated in double; only
 * the visibility is rounded to float. The variance E[z^2] - E[z]^2 cancels by
 * up to 1 / min_variance (5e4 at the default), which double absorbs (error
 * about 1e-16 / 2e-5 relative) and float could not (6e-8 x 5e4).
 */
#ifndef PENUMBRA_CHEBYSHEV_H
#define PENUMBRA_CHEBYSHEV_H

typedef struct {
    pn_double mean;     /* E[z]   */
    pn_double mean_sq;  /* E[z^2] */
} DepthMoments;

typedef struct {
    pn_float u, v, z;
} Receiver;

PN_FN Receiver load_receiver(PN_GLOBAL const float* receivers, pn_dims d, int x, int y)
{
    Receiver r;
    r.u = pn_clamp(pn_load(PN_PLANE(receivers, d, 0), d, x, y), 0.0f, 1.0f);
    r.v = pn_clamp(pn_load(PN_PLANE(receivers, d, 1), d, x, y), 0.0f, 1.0f);
    r.z = pn_load(PN_PLANE(receivers, d, 2), d, x, y);
    return r;
}

/* load_receiver that also flags the row when u, v or z is NaN or infinite
 * (before clamping, which would hide a NaN differently on each backend), and
 * converts z from its convention `c` (kernels/depth_convention.h). */
PN_FN Receiver load_checked_receiver(PN_GLOBAL const float* receivers, pn_dims d, DepthConversion c, int x, int y,
                                     PN_GLOBAL int* bad_rows)
{
    const pn_float u = pn_load(PN_PLANE(receivers, d, 0), d, x, y);
    const pn_float v = pn_load(PN_PLANE(receivers, d, 1), d, x, y);
    const pn_float z = pn_load(PN_PLANE(receivers, d, 2), d, x, y);
    pn_flag_any(bad_rows, y, pn_not(pn_and(pn_and(pn_finite(u), pn_finite(v)), pn_finite(z))));
    Receiver r;
    r.u = pn_clamp(u, 0.0f, 1.0f);
    r.v = pn_clamp(v, 0.0f, 1.0f);
    r.z = depth_to_normalized(z, c);
    return r;
}

/* The opening every moment-table lookup entry shares (vsm, vssm, msm,
 * msm_soft, evsm; each in both PN_TABLE_VARIANTS): the arguments -- the table
 * of element type T, the receivers' planes u, v, z, the visibility plane, the
 * bad-row flags, then the method's parameters `p` -- and the first statement,
 * which reads and checks the strip's receivers into `r`; PN_LOOKUP_STORE
 * writes the strip's visibility. Macros, because an argument list cannot be a
 * function; each entry keeps its own `PN_KERNEL void NAME_##variant(` line,
 * which the OpenCL embed step reads (cmake/embed_kernels.cmake). */
#define PN_LOOKUP_ARGS(T, Params) PN_LOOKUP_ARGS_OF(T, table, Params)
/* The same with the source named: `depth` for the entries that read the
 * shadow map itself (the direct window sums, kernels/box_window.h). */
#define PN_LOOKUP_ARGS_OF(T, source, Params)                                                              \
    PN_GLOBAL const T* source, PN_GLOBAL const float* receivers, PN_GLOBAL float* out, PN_GLOBAL int* bad_rows, \
        const Params p, PN_PIXEL_ARGS
#define PN_LOOKUP_BEGIN(r)                    \
    PN_PIXEL_BEGIN(p.out.width, p.out.height); \
    const Receiver r = load_checked_receiver(receivers, p.receivers, p.convention, pn_x, pn_y, bad_rows)
#define PN_LOOKUP_STORE(visibility) pn_store(out, p.out, pn_x, pn_y, visibility)

PN_FN pn_double chebyshev_upper_bound(DepthMoments m, pn_double z, double min_variance)
{
    const pn_double variance = pn_dmax(m.mean_sq - m.mean * m.mean, min_variance);
    const pn_double d = z - m.mean;
    /* With min_variance = 0 both terms can vanish (d * d underflows): the
     * floor keeps 0 / 0 out, giving 0, the right answer behind the window. */
    const pn_double p_max = variance / pn_dmax(variance + d * d, 1e-300);
    return pn_dselect(z <= m.mean, 1.0, p_max);
}

/* The light-bleeding reduction pn_linstep(bleed, 1, p), in double: times
 * the uniform 1 / (1 - bleed), so that no lane divides (exact for the
 * default bleed 0). */
PN_FN pn_double chebyshev_bleed(pn_double p, float bleed)
{
    const double lo = bleed;
    return pn_dclamp((p - lo) * (1.0 / (1.0 - lo)), 0.0, 1.0);
}

PN_FN pn_float chebyshev_visibility(DepthMoments m, pn_float z, float min_variance, float bleed)
{
    return pn_double_to_float(chebyshev_bleed(chebyshev_upper_bound(m, pn_to_double(z), min_variance), bleed));
}

/* Mean and mean square over the texels [x0, x1) x [y0, y1). `limbs` is the
 * exact variant's (one argument list for both, PN_TABLE_VARIANTS); unused. */
PN_FN DepthMoments box_moments_float(PN_GLOBAL const float* table, pn_dims t, int limbs, pn_int x0, pn_int x1,
                                     pn_int y0, pn_int y1)
{
    const pn_float area = pn_int_to_float((x1 - x0) * (y1 - y0));
    DepthMoments m;
    m.mean = pn_to_double(sat_box_sum_float(PN_PLANE(table, t, 0), t, x0, x1, y0, y1) / area);
    m.mean_sq = pn_to_double(sat_box_sum_float(PN_PLANE(table, t, 1), t, x0, x1, y0, y1) / area);
    return m;
}

/* The same from a limb table of z, z^2 (`limbs` limbs per value). */
PN_FN DepthMoments box_moments_exact(PN_GLOBAL const uint* table, pn_dims t, int limbs, pn_int x0, pn_int x1,
                                     pn_int y0, pn_int y1)
{
    const pn_double inverse_area = 1.0 / pn_int_to_double((x1 - x0) * (y1 - y0));  /* as direct_box_means */
    DepthMoments m;
    pn_double sums[2];
    sat_limb_box_sums01(table, t, limbs, 1.0 / 65536.0, x0, x1, y0, y1, sums);
    m.mean = sums[0] * inverse_area;
    m.mean_sq = sums[1] * inverse_area;
    return m;
}

/* A window of half-width `half` texels (fractional) centred at texel-space
 * (cx, cy), clipped to the map: exclusive corners in [0, width] x [0, height]. */
typedef struct {
    pn_float x0, x1, y0, y1;
} FractionalWindow;

PN_FN FractionalWindow clip_window(pn_dims t, pn_float cx, pn_float cy, pn_float half_x, pn_float half_y)
{
    FractionalWindow w;
    w.x0 = pn_clamp(cx - half_x, 0.0f, (float)t.width);
    w.x1 = pn_clamp(cx + half_x, 0.0f, (float)t.width);
    w.y0 = pn_clamp(cy - half_y, 0.0f, (float)t.height);
    w.y1 = pn_clamp(cy + half_y, 0.0f, (float)t.height);
    return w;
}

/* A fractional window's area, in double (exact: differences of float32 corners). */
PN_FN pn_double fractional_area(FractionalWindow f)
{
    return (pn_to_double(f.x1) - pn_to_double(f.x0)) * (pn_to_double(f.y1) - pn_to_double(f.y0));
}

/* `limbs`: as box_moments_float's, unused. */
PN_FN DepthMoments fractional_moments_float(PN_GLOBAL const float* table, pn_dims t, int limbs, FractionalWindow f)
{
    const SatFractionalWindow w = sat_fractional_window(t, f.x0, f.x1, f.y0, f.y1);
    const pn_float area = (f.x1 - f.x0) * (f.y1 - f.y0);
    DepthMoments m;
    m.mean = pn_to_double(sat_fractional_sum_float(PN_PLANE(table, t, 0), t, w) / area);
    m.mean_sq = pn_to_double(sat_fractional_sum_float(PN_PLANE(table, t, 1), t, w) / area);
    return m;
}

PN_FN DepthMoments fractional_moments_exact(PN_GLOBAL const uint* table, pn_dims t, int limbs, FractionalWindow f)
{
    const SatFractionalWindow w = sat_fractional_window(t, f.x0, f.x1, f.y0, f.y1);
    const pn_double area = fractional_area(f);
    DepthMoments m;
    pn_double sums[2];  /* the same doubles on either path (the binding's schedule choice) */
    if (PN_FRACTIONAL_ROWS_IN_ORDER && limbs == 2) {
        sat_limb_fractional_sums01(table, t, 1.0 / 65536.0, w, sums);
    } else {
        sums[0] = sat_limb_fractional_sum(table, t, limbs, 0, 1.0 / 65536.0, w);
        sums[1] = sat_limb_fractional_sum(table, t, limbs, 1, 1.0 / 65536.0, w);
    }
    m.mean = sums[0] / area;
    m.mean_sq = sums[1] / area;
    return m;
}

#endif
