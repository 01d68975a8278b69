/* Variance shadow maps with a fixed box window (Donnelly & Lauritzen 2006).
 *
 * Per receiver (u, v, z): the window is the (2r+1) x (2r+1) block of texels
 * centred on the texel containing (u, v) (u, v clamped into the map), clipped
 * to the map (kernels/box_window.h); its mean and variance come from the
 * moment table in O(1) (vsm_float, vsm_exact) or from direct sums of the
 * map's depths (vsm_direct, small radii); the visibility is the Chebyshev
 * bound of kernels/chebyshev.h, in [0, 1].
 * Inputs: receivers planes u, v in [0, 1] (texture coordinates), z (light
 * depth, same units as the map). Output: one plane of visibility.
 */
#ifndef PENUMBRA_VSM_H
#define PENUMBRA_VSM_H

#define PN_VSM_KERNEL(variant, T)                                                                  \
PN_KERNEL void vsm_##variant(PN_LOOKUP_ARGS(T, ChebyshevParams))                                   \
{                                                                                                  \
    PN_BOX_LOOKUP_BEGIN(r, w);                                                                     \
    const DepthMoments m = box_moments_##variant(table, p.table, p.limbs, w.x0, w.x1, w.y0, w.y1); \
    PN_LOOKUP_STORE(chebyshev_visibility(m, r.z, p.min_variance, p.bleed));                        \
}
PN_TABLE_VARIANTS(PN_VSM_KERNEL)

/* The same window summed directly from the depth map (kernels/box_window.h):
 * for small radii, where it is faster than the table and needs none. */
PN_KERNEL void vsm_direct(PN_LOOKUP_ARGS_OF(float, depth, ChebyshevParams))
{
    PN_BOX_LOOKUP_BEGIN(r, w);
    pn_double mean[2];
    const DirectMap map = direct_map(p.direct, p.table, p.convention);
    direct_box_means(depth, map, w, p.radius, PN_TABLE_POWERS, 0.0f, 0.0f, 2, mean);
    DepthMoments m;
    m.mean = mean[0];
    m.mean_sq = mean[1];
    PN_LOOKUP_STORE(chebyshev_visibility(m, r.z, p.min_variance, p.bleed));
}

#endif
