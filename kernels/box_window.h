/* The box window of the box methods (vsm, msm, evsm), and its sums taken
 * directly from the depth map.
 *
 * Window contract (`penumbra shade`'s; tests/support/fidelity_reference.cpp
 * states it the same way): the (2r+1) x (2r+1) block of texels centred on the
 * texel containing (u, v) (u, v clamped into [0, 1], the texel floor(u W) as
 * the float32 product, clamped into the map), clipped to the map.
 *
 * Two ways to a window's means of the per-texel values (texel_values,
 * kernels/moment_table.h: z .. z^4, or EVSM's warps, all double from the
 * float32 depth):
 *  - a moment table, four corners per value (kernels/moment_table.h): O(1)
 *    whatever the radius, but 2 or 3 limbs per corner and a table to build;
 *  - direct sums (direct_box_means): the (2r+1)^2 depths gathered from the
 *    map and their values summed in double, O(r^2) per receiver and no table
 *    (issue 9: small windows). Each value is the table's own double before
 *    its rounding to limbs; a sum of at most 25 of them rounds at most 25
 *    times at 2^-53 relative (z and z^2 of float32 depths are exact), below
 *    the 3-limb table's 2^-49 per value, so both ways compute the same method
 *    to the last few bits of double. The host picks one by radius
 *    (docs/moment_table.md, "Direct sums for small windows").
 */
#ifndef PENUMBRA_BOX_WINDOW_H
#define PENUMBRA_BOX_WINDOW_H

typedef struct {
    pn_int x0, x1, y0, y1;
} TexelWindow;

/* The texel containing (u, v), clamped to the map, grown by rx columns and
 * ry rows on each side and clipped. */
PN_FN TexelWindow texel_window_xy(pn_dims t, pn_float u, pn_float v, int rx, int ry)
{
    const float w = (float)t.width, h = (float)t.height;
    const pn_float tx = pn_clamp(pn_floor(u * w), 0.0f, w - 1.0f);
    const pn_float ty = pn_clamp(pn_floor(v * h), 0.0f, h - 1.0f);
    TexelWindow win;
    win.x0 = pn_to_int(pn_max(tx - (float)rx, 0.0f));
    win.x1 = pn_to_int(pn_min(tx + (float)(rx + 1), w));
    win.y0 = pn_to_int(pn_max(ty - (float)ry, 0.0f));
    win.y1 = pn_to_int(pn_min(ty + (float)(ry + 1), h));
    return win;
}

/* The texel containing (u, v), clamped to the map, grown by r and clipped. */
PN_FN TexelWindow texel_window(pn_dims t, pn_float u, pn_float v, int radius)
{
    return texel_window_xy(t, u, v, radius, radius);
}

/* The lowest and highest v of receiver rows [y0, y1), clamped into [0, 1]
 * as the lookups' receivers are (load_checked_receiver), lane by lane into
 * `low` and `high` at (0, 0) of dims `strip` (one strip: the caller takes
 * the lanes' extremes). The map rows a band of direct sums reads follow from
 * them (texel_window_xy's rows; simd/cpu_direct_sums.cpp). The row is read
 * clamped to its width, so that no lane past it reads as v = 0. */
PN_FN void receiver_v_bounds(PN_GLOBAL const float* receivers, pn_dims d, int y0, int y1, PN_GLOBAL float* low,
                             PN_GLOBAL float* high, pn_dims strip)
{
    pn_float lowest = 1.0f, highest = 0.0f;
    for (int y = y0; y < y1; ++y)
        PN_FOR_STRIPS(x, 0, d.width)
        {
            const pn_float v = pn_clamp(pn_load_clamped(PN_PLANE(receivers, d, 1), d, x, y), 0.0f, 1.0f);
            lowest = pn_min(lowest, v);
            highest = pn_max(highest, v);
        }
    pn_store(low, strip, 0, 0, lowest);
    pn_store(high, strip, 0, 0, highest);
}

/* The opening of the box-window lookups (vsm, msm, evsm): PN_LOOKUP_BEGIN
 * (kernels/chebyshev.h), then the receiver's window `w`. */
#define PN_BOX_LOOKUP_BEGIN(r, w) \
    PN_LOOKUP_BEGIN(r);           \
    const TexelWindow w = texel_window(p.table, r.u, r.v, p.radius)

/* The sums of the `moments` values over the window's texels, read from
 * `map` (a DirectMap: the map's rows it holds, and their convention). A
 * strip whose windows all lie inside the map reads its taps at uniform
 * offsets from each lane's window origin; a strip touching an edge masks the
 * taps beyond the clipped window (as kernels/pcf.h's box). A window's rows
 * lie in `map` for every active lane (simd/cpu_direct_sums.cpp picks a band
 * that holds them); the origin's row is clamped into it so that an inactive
 * lane (the tail of a row, its window at u = v = 0) reads inside it too. */
PN_FN void direct_box_sums(PN_GLOBAL const float* depth, DirectMap map, TexelWindow w, int radius, int encoding,
                           float c_positive, float c_negative, int moments, pn_double* sum)
{
    for (int k = 0; k < moments; ++k) sum[k] = 0.0;
    const int side = 2 * radius + 1;
    const pn_int width = w.x1 - w.x0, height = w.y1 - w.y0;
    const pn_float full = pn_int_to_float(width * height);
    const pn_int row = w.y0 - map.first_row;
    pn_double v[4];
    if (pn_all(full == (float)(side * side))) {
        const pn_int origin = pn_iclamp(row, 0, map.rows.height - side) * map.rows.pitch + w.x0;
        for (int dy = 0; dy < side; ++dy)
            for (int dx = 0; dx < side; ++dx) {
                const pn_float stored = pn_gather(depth, origin + (dy * map.rows.pitch + dx));
                texel_values(depth_to_unclamped(stored, map.convention), encoding, c_positive, c_negative, moments,
                             v);
                for (int k = 0; k < moments; ++k) sum[k] = sum[k] + v[k];
            }
        return;
    }
    const pn_float columns = pn_int_to_float(width), rows = pn_int_to_float(height);
    for (int dy = 0; dy < side; ++dy)
        for (int dx = 0; dx < side; ++dx) {
            const pn_dmask inside = pn_mask_to_dmask(pn_and(columns > (float)dx, rows > (float)dy));
            const pn_float stored = pn_fetch(depth, map.rows, w.x0 + dx, row + dy);
            texel_values(depth_to_unclamped(stored, map.convention), encoding, c_positive, c_negative, moments, v);
            for (int k = 0; k < moments; ++k) sum[k] = sum[k] + pn_dselect(inside, v[k], 0.0);
        }
}

/* The window's means of the values: the direct counterpart of a table's
 * box query (`depth`: the map's rows `map` holds, stored in its convention,
 * converted per tap without clamps: the host checked the map's range up
 * front, and texel_values clamps l; kernels/depth_convention.h. The kind
 * is not made a literal: four copies of EVSM's window made its normalised
 * path slower, docs/integration.md, "Depth conventions").
 * One reciprocal of the area, not a division per value: double divisions are
 * much of MSM's and EVSM's time; it moves a mean by at most one rounding
 * (2^-53 relative). */
PN_FN void direct_box_means(PN_GLOBAL const float* depth, DirectMap map, TexelWindow w, int radius, int encoding,
                            float c_positive, float c_negative, int moments, pn_double* mean)
{
    pn_double sum[4];
    direct_box_sums(depth, map, w, radius, encoding, c_positive, c_negative, moments, sum);
    const pn_double inverse_area = 1.0 / pn_int_to_double((w.x1 - w.x0) * (w.y1 - w.y0));
    for (int k = 0; k < moments; ++k) mean[k] = sum[k] * inverse_area;
}

#endif
