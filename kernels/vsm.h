/* Variance shadow maps with a fixed box window (Donnelly & Lauritzen 2006).
 *
 * Per receiver (u, v, z): the window is the (2r+1) x (2r+1) block of texels
 * centred on the texel containing (u, v) (u, v clamped into the map), clipped
 * to the map; its mean and variance come from the moment table in O(1); the
 * visibility is the Chebyshev bound of kernels/chebyshev.h, in [0, 1].
 * Inputs: receivers planes u, v in [0, 1] (texture coordinates), z (light
 * depth, same units as the map). Output: one plane of visibility.
 */
#ifndef PENUMBRA_VSM_H
#define PENUMBRA_VSM_H

typedef struct {
    pn_int x0, x1, y0, y1;
} TexelWindow;

/* The texel containing (u, v), clamped to the map, grown by r and clipped. */
PN_FN TexelWindow texel_window(pn_dims t, pn_float u, pn_float v, int radius)
{
    const float w = (float)t.width, h = (float)t.height;
    const pn_float tx = pn_clamp(pn_floor(u * w), 0.0f, w - 1.0f);
    const pn_float ty = pn_clamp(pn_floor(v * h), 0.0f, h - 1.0f);
    TexelWindow win;
    win.x0 = pn_to_int(pn_max(tx - (float)radius, 0.0f));
    win.x1 = pn_to_int(pn_min(tx + (float)(radius + 1), w));
    win.y0 = pn_to_int(pn_max(ty - (float)radius, 0.0f));
    win.y1 = pn_to_int(pn_min(ty + (float)(radius + 1), h));
    return win;
}

/* The opening of the box-window lookups (vsm, msm, evsm): PN_LOOKUP_BEGIN
 * (kernels/chebyshev.h), then the receiver's window `w`. */
#define PN_BOX_LOOKUP_BEGIN(r, w) \
    PN_LOOKUP_BEGIN(r);           \
    const TexelWindow w = texel_window(p.table, r.u, r.v, p.radius)

#define PN_VSM_KERNEL(variant, T)                                                                  \
PN_KERNEL void vsm_##variant(PN_LOOKUP_ARGS(T, ChebyshevParams))                                   \
{                                                                                                  \
    PN_BOX_LOOKUP_BEGIN(r, w);                                                                     \
    const DepthMoments m = box_moments_##variant(table, p.table, p.limbs, w.x0, w.x1, w.y0, w.y1); \
    PN_LOOKUP_STORE(chebyshev_visibility(m, r.z, p.min_variance, p.bleed));                        \
}
PN_TABLE_VARIANTS(PN_VSM_KERNEL)

#endif
