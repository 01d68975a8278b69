/* Variance soft shadow maps (Yang, Dong, Chen, Feng, Bao, Peng, EGSR 2010).
 *
 * Per receiver (u, v, z), with light_size L the light's width in texture
 * units at the near plane:
 *  1. Blocker search: over the box of (2 R + 1)^2 texels centred on the
 *     receiver's texel, R = floor(max(L W / 2, 1/2)) per axis (the odd width
 *     nearest L W), clipped to the map (the box methods' texel window,
 *     kernels/box_window.h), the Chebyshev bound p = P(depth >= z) is the lit
 *     fraction; assuming the non-blockers lie at z, mean = p z + (1 - p) z_occ,
 *     so the average blocker depth is z_occ = (mean - p z) / (1 - p).
 *     p -> 1 (1 - p < 1e-4): no blocker, fully lit. z_occ <= 0 (blockers at
 *     or behind the light plane, an estimate the bound can produce): clamped to
 *     1e-4 z, the widest penumbra, itself clamped to the table's largest window.
 *  2. Penumbra width w = L (z - z_occ) / z_occ in texture units (PCSS,
 *     Fernando 2005), a filter of half-width max(0.5, w W / 2) texels,
 *     fractional, by interpolating the table (kernels/moment_table.h).
 *  3. The Chebyshev bound over that window, with the variance floor and the
 *     light-bleeding reduction. Output in [0, 1].
 * The filter window is centred at the continuous texel position (u W, v H),
 * so the estimate varies smoothly with (u, v) within a texel. The search is
 * an integer window (4 corners per value, not a fractional window's 16: 40
 * pair gathers per receiver instead of 64, docs/moment_table.md): the
 * blocker depth, and so the filter's width, is one value per texel and steps
 * at texel edges (docs/moments.md, "VSSM's search window").
 */
#ifndef PENUMBRA_VSSM_H
#define PENUMBRA_VSSM_H

#define PN_VSSM_NO_BLOCKER 1e-4    /* 1 - p below this: no blocker (double) */
#define PN_VSSM_MIN_OCCLUDER 1e-4f /* z_occ floor, as a fraction of z */

/* Filter half-width in texels for a receiver at z with blockers at z_occ. */
PN_FN pn_float vssm_filter_half_width(const ChebyshevParams p, pn_float z, pn_float z_occ, float texels)
{
    const pn_float occluder = pn_max(z_occ, z * PN_VSSM_MIN_OCCLUDER);
    const pn_float w = p.light_size * (z - occluder) / occluder;
    return pn_clamp(w * (0.5f * texels), 0.5f, (float)p.max_radius + 0.5f);
}

/* Step 1 from the search window's moments, in double: the lit fraction's
 * complement and the blocker depth; `lit` marks receivers with no blocker.
 * The blocker depth is rounded to float for the window geometry. */
PN_FN pn_float vssm_blocker_depth(DepthMoments search, pn_float z, float min_variance, pn_mask* lit)
{
    const pn_double zd = pn_to_double(z);
    const pn_double p = chebyshev_upper_bound(search, zd, min_variance);
    const pn_double blocked = 1.0 - p;
    *lit = pn_dmask_to_mask(blocked < PN_VSSM_NO_BLOCKER);
    const pn_double safe_blocked = pn_dmax(blocked, PN_VSSM_NO_BLOCKER);
    return pn_double_to_float((search.mean - p * zd) / safe_blocked);
}

/* The light's half-width in texels along an axis of `texels`, at least half
 * a texel: the fractional search window's (msm-soft's) half-width, and the
 * integer search box's radius is its floor. */
PN_FN float vssm_search_half(const ChebyshevParams p, float texels)
{
    const float width = p.light_size * 0.5f * texels;
    return width > 0.5f ? width : 0.5f;
}

/* MSM-soft's first search window (kernels/msm_soft.h): fractional, centred at (u W, v H). */
PN_FN FractionalWindow vssm_search_window(const ChebyshevParams p, Receiver r)
{
    const float w = (float)p.table.width, h = (float)p.table.height;
    return clip_window(p.table, r.u * w, r.v * h, vssm_search_half(p, w), vssm_search_half(p, h));
}

/* VSSM's search box: the receiver's texel grown by R_x, R_y and clipped
 * (the conversion truncates: the floor of a positive half-width). */
PN_FN TexelWindow vssm_search_box(const ChebyshevParams p, Receiver r)
{
    const int rx = (int)vssm_search_half(p, (float)p.table.width);
    const int ry = (int)vssm_search_half(p, (float)p.table.height);
    return texel_window_xy(p.table, r.u, r.v, rx, ry);
}

PN_FN FractionalWindow vssm_filter_window(const ChebyshevParams p, Receiver r, pn_float z_occ)
{
    const float w = (float)p.table.width, h = (float)p.table.height;
    return clip_window(p.table, r.u * w, r.v * h, vssm_filter_half_width(p, r.z, z_occ, w),
                       vssm_filter_half_width(p, r.z, z_occ, h));
}

#define PN_VSSM_KERNEL(variant, T)                                                                               \
PN_KERNEL void vssm_##variant(PN_LOOKUP_ARGS(T, ChebyshevParams))                                                \
{                                                                                                                \
    PN_LOOKUP_BEGIN(r);                                                                                          \
    pn_mask lit;                                                                                                 \
    const TexelWindow box = vssm_search_box(p, r);                                                               \
    const DepthMoments search = box_moments_##variant(table, p.table, p.limbs, box.x0, box.x1, box.y0, box.y1);  \
    const pn_float z_occ = vssm_blocker_depth(search, r.z, p.min_variance, &lit);                                \
    if (pn_all(lit)) { /* no blocker in any lane: lit, the filter's answer unused */                             \
        PN_LOOKUP_STORE(1.0f);                                                                                   \
        return;                                                                                                  \
    }                                                                                                            \
    const DepthMoments filter =                                                                                  \
        fractional_moments_##variant(table, p.table, p.limbs, vssm_filter_window(p, r, z_occ));                  \
    const pn_float visibility = chebyshev_visibility(filter, r.z, p.min_variance, p.bleed);                      \
    PN_LOOKUP_STORE(pn_select(lit, 1.0f, visibility));                                                           \
}
PN_TABLE_VARIANTS(PN_VSSM_KERNEL)

#endif
