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
 */
#ifndef PENUMBRA_CHEBYSHEV_H
#define PENUMBRA_CHEBYSHEV_H

typedef struct {
    pn_float mean;     /* E[z]   */
    pn_float mean_sq;  /* E[z^2] */
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
 * (before clamping, which would hide a NaN differently on each backend). */
PN_FN Receiver load_checked_receiver(PN_GLOBAL const float* receivers, pn_dims d, int x, int y,
                                     PN_GLOBAL int* bad_rows)
{
    const pn_float u = pn_load(PN_PLANE(receivers, d, 0), d, x, y);
    const pn_float v = pn_load(PN_PLANE(receivers, d, 1), d, x, y);
    const pn_float z = pn_load(PN_PLANE(receivers, d, 2), d, x, y);
    pn_flag_any(bad_rows, y, pn_not(pn_and(pn_and(pn_finite(u), pn_finite(v)), pn_finite(z))));
    Receiver r;
    r.u = pn_clamp(u, 0.0f, 1.0f);
    r.v = pn_clamp(v, 0.0f, 1.0f);
    r.z = z;
    return r;
}

PN_FN pn_float chebyshev_upper_bound(DepthMoments m, pn_float z, float min_variance)
{
    const pn_float variance = pn_max(m.mean_sq - m.mean * m.mean, min_variance);
    const pn_float d = z - m.mean;
    /* With min_variance = 0 both terms can vanish (d * d underflows): the
     * floor keeps 0 / 0 out, giving 0, the right answer behind the window. */
    const pn_float p_max = variance / pn_max(variance + d * d, 1e-30f);
    return pn_select(z <= m.mean, 1.0f, p_max);
}

PN_FN pn_float chebyshev_visibility(DepthMoments m, pn_float z, float min_variance, float bleed)
{
    return pn_linstep(bleed, 1.0f, chebyshev_upper_bound(m, z, min_variance));
}

/* Mean and mean square over the texels [x0, x1) x [y0, y1). */
PN_FN DepthMoments box_moments_float(PN_GLOBAL const float* table, pn_dims t, pn_int x0, pn_int x1, pn_int y0,
                                     pn_int y1)
{
    const pn_float area = pn_int_to_float((x1 - x0) * (y1 - y0));
    DepthMoments m;
    m.mean = sat_box_sum_float(PN_PLANE(table, t, 0), t, x0, x1, y0, y1) / area;
    m.mean_sq = sat_box_sum_float(PN_PLANE(table, t, 1), t, x0, x1, y0, y1) / area;
    return m;
}

PN_FN DepthMoments box_moments_exact(PN_GLOBAL const uint* table, pn_dims t, pn_int x0, pn_int x1, pn_int y0,
                                     pn_int y1)
{
    const pn_float area = pn_int_to_float((x1 - x0) * (y1 - y0));
    DepthMoments m;
    m.mean = sat_box_sum_exact(PN_PLANE(table, t, 0), t, x0, x1, y0, y1) / area * sat_exact_moment_scale(1);
    m.mean_sq = sat_box_sum_exact(PN_PLANE(table, t, 1), t, x0, x1, y0, y1) / area * sat_exact_moment_scale(2);
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

PN_FN DepthMoments fractional_moments_float(PN_GLOBAL const float* table, pn_dims t, FractionalWindow f)
{
    const SatFractionalWindow w = sat_fractional_window(t, f.x0, f.x1, f.y0, f.y1);
    const pn_float area = (f.x1 - f.x0) * (f.y1 - f.y0);
    DepthMoments m;
    m.mean = sat_fractional_sum_float(PN_PLANE(table, t, 0), t, w) / area;
    m.mean_sq = sat_fractional_sum_float(PN_PLANE(table, t, 1), t, w) / area;
    return m;
}

PN_FN DepthMoments fractional_moments_exact(PN_GLOBAL const uint* table, pn_dims t, FractionalWindow f)
{
    const SatFractionalWindow w = sat_fractional_window(t, f.x0, f.x1, f.y0, f.y1);
    const pn_float area = (f.x1 - f.x0) * (f.y1 - f.y0);
    DepthMoments m;
    m.mean = sat_fractional_sum_exact(PN_PLANE(table, t, 0), t, w) / area * sat_exact_moment_scale(1);
    m.mean_sq = sat_fractional_sum_exact(PN_PLANE(table, t, 1), t, w) / area * sat_exact_moment_scale(2);
    return m;
}

#endif
