/* Exponential variance shadow maps with a fixed box window (Lauritzen &
 * McCool, GI 2008; the warps and their storage limits are in
 * kernels/exponential_warp.h).
 *
 * Per receiver (u, v, z): the window is the (2r+1) x (2r+1) block of texels
 * around the texel of (u, v), clipped to the map, as VSM's (kernels/vsm.h).
 * The table (kernels/encoded_table.h) gives the window means of w+ and w+^2,
 * and with 4 channels of |w-| and w-^2. The receiver's depth, minus
 * depth_bias and clamped into [0, 1] (so that its warp stays finite), is
 * warped the same way; for each warp the variance is floored at
 * min_variance (depth^2) times the warp's squared slope at the receiver, and
 * the visibility is the Chebyshev bound of kernels/chebyshev.h, reused as it
 * is (see evsm_warp_visibility), with its light-bleeding reduction. With 4 channels the smaller of the two bounds is
 * taken (both are upper bounds of the same lit fraction).
 * Output: one plane of visibility in [0, 1].
 */
#ifndef PENUMBRA_EVSM_H
#define PENUMBRA_EVSM_H

/* One warp: the window's (E[w], E[w^2]) against the receiver's warped depth
 * w_r, with the variance floor min_variance times the warp's squared slope
 * at the receiver, all in double. The bound is invariant under scaling the
 * variable, so dividing w by the slope s = |dw/dz| at the receiver turns it
 * into depth units there, where the floor is min_variance itself: the kernel
 * reuses chebyshev_visibility (kernels/chebyshev.h) as it is. */
PN_FN pn_float evsm_warp_visibility(pn_double mean, pn_double mean_sq, pn_double warped_receiver, pn_double slope,
                                    const MomentParams p)
{
    const pn_double inverse = 1.0 / slope;
    DepthMoments m;
    m.mean = mean * inverse;
    m.mean_sq = mean_sq * (inverse * inverse);
    return pn_double_to_float(chebyshev_bleed(chebyshev_upper_bound(m, warped_receiver * inverse, p.min_variance),
                                              p.bleed));
}

/* `mean` holds the window means of the table's channels. */
PN_FN pn_float evsm_visibility(const pn_double* mean, pn_float receiver_z, const MomentParams p)
{
    const pn_double z = pn_dclamp(pn_to_double(receiver_z) - (double)p.depth_bias, 0.0, 1.0);
    const double c_positive = p.exponent_positive, c_negative = p.exponent_negative;
    const pn_double wp = pn_dexp(c_positive * (z - 1.0));
    pn_float visibility = evsm_warp_visibility(mean[0], mean[1], wp, c_positive * wp, p);
    if (p.channels == 4) {
        const pn_double wn = pn_dexp(-c_negative * z);
        const pn_float negative = evsm_warp_visibility(-mean[2], mean[3], -wn, c_negative * wn, p);
        visibility = pn_min(visibility, negative);
    }
    return visibility;
}

/* The window means of the table's channels: a float table, or (exact) a
 * limb table of the warps (kernels/moment_table.h, PN_TABLE_EVSM) or the
 * 16-bit steps of an encoded table (one limb). */
PN_FN void evsm_box_means_float(PN_GLOBAL const float* table, const MomentParams p, TexelWindow w, pn_double* mean)
{
    const pn_float area = texel_window_area(w);
    for (int k = 0; k < p.channels; ++k) mean[k] = encoded_box_mean_float(table, p.table, k, w, area);
}

PN_FN void evsm_box_means_exact(PN_GLOBAL const uint* table, const MomentParams p, TexelWindow w, pn_double* mean)
{
    const pn_double inverse_area = 1.0 / pn_int_to_double((w.x1 - w.x0) * (w.y1 - w.y0));  /* as direct_box_means */
    for (int k = 0; k < p.channels; ++k)
        mean[k] = sat_limb_box_sum(table, p.table, p.limbs, k, sat_limb_unit(p.limbs), w.x0, w.x1, w.y0, w.y1) *
                  inverse_area;
}

#define PN_EVSM_KERNEL(variant, T)                                    \
PN_KERNEL void evsm_##variant(PN_LOOKUP_ARGS(T, MomentParams))        \
{                                                                     \
    PN_BOX_LOOKUP_BEGIN(r, w);                                        \
    pn_double mean[4];                                                \
    evsm_box_means_##variant(table, p, w, mean);                      \
    PN_LOOKUP_STORE(evsm_visibility(mean, r.z, p));                   \
}
PN_TABLE_VARIANTS(PN_EVSM_KERNEL)

/* The same window's means of the warps summed directly from the depth map
 * (kernels/box_window.h); the channel count as a literal, as the table
 * build's. */
PN_KERNEL void evsm_direct(PN_LOOKUP_ARGS_OF(float, depth, MomentParams))
{
    PN_BOX_LOOKUP_BEGIN(r, w);
    const DirectMap map = direct_map(p.direct, p.table, p.convention);
    pn_double mean[4];
    if (p.channels == 4)
        direct_box_means(depth, map, w, p.radius, PN_TABLE_EVSM, p.exponent_positive, p.exponent_negative, 4, mean);
    else
        direct_box_means(depth, map, w, p.radius, PN_TABLE_EVSM, p.exponent_positive, p.exponent_negative, 2, mean);
    PN_LOOKUP_STORE(evsm_visibility(mean, r.z, p));
}

#endif
