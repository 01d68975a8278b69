/* Moment soft shadows (Peters, Münstermann, Wetzstein & Klein, "Beyond hard
 * shadows: moment shadow maps for single scattering, soft shadows and
 * translucent occluders", I3D 2016; "Improved moment shadow maps for
 * translucent occluders, soft shadows and single scattering", JCGT 2017):
 * PCSS's three steps with moments in place of samples.
 *
 * Per receiver (u, v, z), z_f = z - depth_bias, light_size L as VSSM's:
 *  1. Blocker search over VSSM's search window (kernels/vssm.h: width L,
 *     centred at (u W, v H), fractional, clipped): its four moments, biased
 *     as in kernels/msm.h, reconstructed by the Hamburger canonical
 *     representation through z_f (support z2, z_f, z3, weights from
 *     kernels/msm.h). The blockers are the support points in front of z_f:
 *     none (z_f <= z2), z2 alone (weight as in msm.h), or z2 and z3 (weight
 *     1 - w(z_f), and their mean depth (b1 - w(z_f) z_f) / (1 - w(z_f)) by
 *     the balance of mass and first moment). Their weighted average depth is
 *     the blocker depth z_occ. A singular Hankel matrix uses msm.h's
 *     two-point (or one-point) distribution the same way.
 *     Blocker weight below moment_bias + 1e-4: no blocker (the bias itself
 *     puts alpha / 2 at depth 0), fully lit.
 *  2. Penumbra estimate w = L (z_f - z_occ) / z_occ (PCSS) and its filter
 *     half-width, both exactly as VSSM's (vssm_filter_window), clamped to the
 *     table's largest window.
 *  1b. Steps 1-2 again with the filter window found as the search window,
 *     PN_MSM_SOFT_SEARCHES windows in all (issue 13): the first search, L
 *     wide, averages blockers that each leave the receiver lit (a blocker at
 *     z_b reaches only L (z - z_b) / (2 z_b) from it) into a depth nearer the
 *     light than the nearer one's, whose wider window then holds it: a halo
 *     of lit receivers darkened (12% of contact's, down to 0.90). Each
 *     search over the window found keeps only the blockers that window
 *     holds, so it narrows to the depth that matters or finds none (lit).
 *  3. The MSM reconstruction of kernels/msm.h over that fractional window.
 * The receiver's own plane (p.plane_bias > 0; issue 13's halo, its second
 * cause): on a surface tilted away from the light, a filter window h texels
 * wide holds the receiver's own surface up to |dz/du| h / W + |dz/dv| h / H
 * nearer the light, which darkens lit receivers beside a shadow. The
 * reconstruction of step 3 then takes z_f minus plane_bias times the
 * plane's largest drop inside the filter window (a plane's lowest point over
 * a box is at a corner: Isidoro's receiver-plane bias, GDC 2006, taken over
 * the whole box), at most plane_bias_max. The searches keep z_f: there the
 * receiver's own texels only pull the blocker depth towards z and narrow
 * the window, and removing them measured worse (contact: 95.4% of lit
 * receivers above 0.98 against 99.8% with the filter step's bias alone,
 * docs/moments.md). Receivers planes PN_PCF_PLANE_DZDU/_DZDV/_OK hold the
 * plane (kernels/receiver_slope.h; host: pcf_receivers); where the flag is 0
 * the window keeps z_f.
 * Output: one plane of visibility in [0, 1]; never NaN.
 */
#ifndef PENUMBRA_MSM_SOFT_H
#define PENUMBRA_MSM_SOFT_H

#define PN_MSM_NO_BLOCKER 1e-4f /* blocker weight (beyond the bias's) below this: lit */
#define PN_MSM_SOFT_SEARCHES 3  /* blocker searches: the light's window, then each penumbra window found */

typedef struct {
    pn_double weight; /* the blockers' share of the window */
    pn_double depth;  /* their weighted average depth */
} Blockers;

PN_FN Blockers msm_blockers_definite(FourMoments b, HankelFactors h, pn_dmask definite, pn_double z)
{
    const KernelPolynomial c = msm_solve(b, h, definite, z);
    const Roots r = msm_roots(c);
    const pn_double weight_z = pn_dclamp(1.0 / msm_safe(msm_polynomial_at(c, z)), 0.0, 1.0);
    const pn_double rest = 1.0 - weight_z;
    const pn_double rest_depth = (b.b1 - weight_z * z) / pn_dmax(rest, 1e-300);
    const pn_double lower = (z * r.hi - b.b1 * (z + r.hi) + b.b2) / msm_safe((r.hi - r.lo) * (z - r.lo));
    /* A root at infinity carries no weight: the other root holds all but w(z). */
    const pn_dmask one_root = pn_dand(pn_dfinite(r.lo), pn_dnot(pn_dfinite(r.hi)));
    Blockers k;
    k.weight = pn_dselect(z <= r.lo, 0.0, pn_dselect(pn_dor(z > r.hi, one_root), rest, lower));
    k.depth = pn_dselect(pn_dor(z > r.hi, one_root), rest_depth, r.lo);
    k.weight = pn_dselect(pn_dand(pn_dfinite(k.weight), pn_dfinite(k.depth)), k.weight, 0.0);
    return k;
}

/* Where the window is one depth or two (kernels/msm.h's rule), the blockers
 * are those depths in front of z; the bias atoms are not blockers. */
PN_FN Blockers msm_blockers(FourMoments raw, pn_double z, MsmPrecision precision)
{
    const pn_dmask one_point = raw.b2 - raw.b1 * raw.b1 <= precision.floor;
    const FourMoments b = msm_bias(raw, precision.alpha);
    const HankelFactors h = msm_factor(b);
    const pn_dmask definite = msm_positive_definite(b, h, precision.floor);
    Blockers k = msm_blockers_definite(b, h, definite, z);
    const TwoPoints t = msm_two_points(raw, msm_factor(raw));
    const pn_dmask two_point = pn_dand(pn_dnot(pn_dor(definite, one_point)), msm_two_points_valid(t));
    const pn_double two_weight = pn_dselect(z <= t.x1, 0.0, pn_dselect(z <= t.x2, 1.0 - t.upper_weight, 1.0));
    const pn_double two_depth = pn_dselect(z <= t.x2, t.x1, raw.b1);
    const pn_dmask point = pn_dnot(pn_dor(definite, two_point));
    k.weight = pn_dselect(two_point, two_weight, pn_dselect(point, pn_dselect(raw.b1 < z, 1.0, 0.0), k.weight));
    k.depth = pn_dselect(two_point, two_depth, pn_dselect(point, raw.b1, k.depth));
    k.weight = pn_dclamp(k.weight, 0.0, 1.0);
    k.depth = pn_dclamp(k.depth, 0.0, pn_dmax(z, 0.0));
    return k;
}

/* VSSM's window geometry (kernels/vssm.h) from these parameters. */
PN_FN ChebyshevParams msm_soft_geometry(const MomentParams p)
{
    ChebyshevParams c;
    c.table = p.table;
    c.receivers = p.receivers;
    c.out = p.out;
    c.radius = 0;
    c.max_radius = p.max_radius;
    c.min_variance = 0.0f;
    c.bleed = 0.0f;
    c.light_size = p.light_size;
    c.limbs = p.limbs;
    return c;
}

/* A window's moments and what they can be trusted to. */
typedef struct {
    FourMoments m;
    MsmPrecision precision;
} WindowMoments;

PN_FN WindowMoments msm_soft_moments_float(PN_GLOBAL const float* table, FractionalWindow f, const MomentParams p)
{
    const SatFractionalWindow w = sat_fractional_window(p.table, f.x0, f.x1, f.y0, f.y1);
    const pn_float area = (f.x1 - f.x0) * (f.y1 - f.y0);
    pn_double mean[4];
    for (int k = 0; k < 4; ++k) mean[k] = encoded_fractional_mean_float(table, p.table, k, w, area);
    WindowMoments r;
    r.m = msm_moments_from_means(mean, p.storage);
    r.precision = msm_float_precision(pn_to_double(f.x1 + 1.0f), pn_to_double(f.y1 + 1.0f), pn_to_double(area), p);
    return r;
}

/* An exact table's moments over a fractional window (units as msm_box_means_exact). */
PN_FN WindowMoments msm_soft_moments_exact(PN_GLOBAL const uint* table, FractionalWindow f, const MomentParams p)
{
    const SatFractionalWindow w = sat_fractional_window(p.table, f.x0, f.x1, f.y0, f.y1);
    const pn_double area = fractional_area(f);
    const double unit = sat_limb_unit(p.limbs);
    pn_double mean[4];
    for (int k = 0; k < 4; ++k) mean[k] = sat_limb_fractional_sum(table, p.table, p.limbs, k, unit, w) / area;
    WindowMoments r;
    r.m = msm_moments_from_means(mean, p.storage);
    r.precision = msm_exact_precision(p);
    return r;
}

/* Steps 1-2 from the search window's moments: the filter window, and `lit`
 * for receivers with no blocker. The blocker depth is rounded to float for
 * the window geometry (as VSSM's). */
PN_FN FractionalWindow msm_soft_filter_window(WindowMoments search, Receiver r, pn_double z_f, const MomentParams p,
                                              pn_mask* lit)
{
    const Blockers k = msm_blockers(search.m, z_f, search.precision);
    *lit = pn_or(pn_dmask_to_mask(k.weight < search.precision.alpha + PN_MSM_NO_BLOCKER), r.z <= 0.0f);
    return vssm_filter_window(msm_soft_geometry(p), r, pn_double_to_float(k.depth));
}

/* The receiver with its depth biased (float, for the window geometry); the
 * reconstruction takes z_f = z - depth_bias in double. */
PN_FN Receiver msm_soft_receiver(Receiver r, const MomentParams p)
{
    r.z = r.z - p.depth_bias;
    return r;
}

PN_FN pn_float msm_soft_visibility(WindowMoments filter_moments, pn_double z_f, pn_mask lit)
{
    const pn_float visibility = pn_double_to_float(1.0 - msm_intensity(filter_moments.m, z_f, filter_moments.precision));
    return pn_select(lit, 1.0f, visibility);
}

/* The receiver's plane (kernels/receiver_slope.h), or none when the plane
 * bias is off (the receivers then hold u, v, z only). */
PN_FN ReceiverSlope msm_soft_load_slope(PN_GLOBAL const float* receivers, const MomentParams p, Receiver raw, int x,
                                        int y, PN_GLOBAL int* bad_rows)
{
    if (p.plane_bias <= 0.0f) return no_receiver_slope();
    ReceiverSlope s = load_receiver_slope(receivers, p.receivers, x, y, bad_rows);
    /* The slopes are the stored convention's; the bias is in normalised depth. */
    const pn_float factor = depth_slope_factor(raw.z, p.convention);
    s.dzdu = s.dzdu * factor;
    s.dzdv = s.dzdv * factor;
    return s;
}

/* z_f lowered by the receiver plane's largest drop inside window f, capped. */
PN_FN pn_double msm_soft_window_depth(pn_double z_f, ReceiverSlope s, Receiver r, FractionalWindow f,
                                      const MomentParams p)
{
    const pn_float w = (float)p.table.width, h = (float)p.table.height;
    const pn_float drop_u = pn_max(s.dzdu * (r.u - f.x0 / w), s.dzdu * (r.u - f.x1 / w));
    const pn_float drop_v = pn_max(s.dzdv * (r.v - f.y0 / h), s.dzdv * (r.v - f.y1 / h));
    const pn_float beta = pn_min(p.plane_bias * pn_max(drop_u + drop_v, 0.0f), p.plane_bias_max);
    return z_f - pn_to_double(pn_select(s.holds, beta, 0.0f));
}

#define PN_MSM_SOFT_KERNEL(variant, T)                                                                              \
PN_KERNEL void msm_soft_##variant(PN_LOOKUP_ARGS(T, MomentParams))                                              \
{                                                                                                                   \
    PN_LOOKUP_BEGIN(raw);                                                                                           \
    const pn_double z_f = pn_to_double(raw.z) - (double)p.depth_bias;                                               \
    const ReceiverSlope slope = msm_soft_load_slope(receivers, p, raw, pn_x, pn_y, bad_rows);                      \
    const Receiver r = msm_soft_receiver(raw, p);                                                                   \
    pn_mask lit;                                                                                                    \
    FractionalWindow window = vssm_search_window(msm_soft_geometry(p), r);                                          \
    window = msm_soft_filter_window(msm_soft_moments_##variant(table, window, p), r, z_f, p, &lit);                 \
    for (int pass = 1; pass < PN_MSM_SOFT_SEARCHES && !pn_all(lit); ++pass) {                                       \
        pn_mask lit_here;                                                                                           \
        window = msm_soft_filter_window(msm_soft_moments_##variant(table, window, p), r, z_f, p, &lit_here);         \
        lit = pn_or(lit, lit_here);                                                                                 \
    }                                                                                                               \
    if (pn_all(lit)) { /* a receiver once lit stays lit: the rest is unused */                                      \
        PN_LOOKUP_STORE(1.0f);                                                                                      \
        return;                                                                                                     \
    }                                                                                                               \
    PN_LOOKUP_STORE(msm_soft_visibility(msm_soft_moments_##variant(table, window, p),                               \
                                        msm_soft_window_depth(z_f, slope, r, window, p), lit));                     \
}
PN_TABLE_VARIANTS(PN_MSM_SOFT_KERNEL)

#endif
