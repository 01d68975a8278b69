/* Summed-area tables of depth moments: build and box queries.
 *
 * Computes, for a depth map z(i, j) in [0, 1], the inclusive sums
 *     S_k(x, y) = sum_{i <= x, j <= y} m_k(i, j),  m_k = z^k, k = 1 .. moments
 * (Crow 1984; as used for variance shadow maps by Lauritzen, GPU Gems 3 ch. 8),
 * so that the sum of m_k over any rectangle costs four reads.
 *
 * Two precisions:
 *  - float: m_k = z^k in float. Fast; its error grows with the table's
 *    magnitude (docs/moment_table.md gives the measured worst case).
 *  - exact: depth quantized to q = round(z * 65535) and the moments to
 *    m_1 = q, m_{k+1} = round(m_k * q / 65536) (integer, so every backend agrees
 *    bit for bit), summed in uint32 that wrap modulo 2^32. Every m_k <= 65535,
 *    so the sum over a window of A texels is < 2^32 and therefore exact,
 *    whatever the wrapped table values are, while A <= 65537: windows up to
 *    255 x 255 texels (radius 127). The host rejects larger windows.
 *    Decoding: E[z] = S_1 / (65535 A); E[z^{k+1}] = E-sum of m_{k+1} * 65536^k / 65535^(k+1) / A.
 *
 * Layout: see SatParams in kernels/params.h (row y at table + (y + 1) * pitch,
 * a zero row before it and a zero padding column after every row). Boundary:
 * queries take exclusive corners in [0, width] x [0, height]; the caller clips.
 *
 * Build schedule (the host's): the map is cut into blocks; a block needs the
 * row sums to its left (`carry`, per row and moment) and the column sums above
 * it (`columns`, per column and moment), and leaves both updated for its right
 * and lower neighbours. The SIMD backend runs the blocks as a wavefront; the
 * OpenCL backend runs bands of rows in parallel, each starting from zero
 * columns, then adds every band's column totals to the bands below.
 */
#ifndef PENUMBRA_MOMENT_TABLE_H
#define PENUMBRA_MOMENT_TABLE_H

#define PN_EXACT_STEPS 65535.0f /* quantization steps of depth in exact tables */
#define PN_EXACT_MAX_AREA 65537  /* texels: the largest window whose sums stay exact */

/* ---- build ------------------------------------------------------------- */

/* Depths the table cannot take: outside [0, 1], NaN and infinities included. */
PN_FN pn_mask sat_depth_outside(pn_float z)
{
    return pn_not(pn_and(z >= 0.0f, z <= 1.0f));
}

/* Scans rows [y0, y1) of columns [x0, x1) of the depth map into the float table.
 * x0 and x1 - x0 are multiples of every lane count (64), or x1 is the width.
 * `carry` holds, per moment and row, the row's sum left of x0 (updated to x1);
 * row `column_row` of `columns` holds the column sums above y0 (updated to y1).
 * A depth outside [0, 1] (NaN and infinities included) sets bad_rows[y]. */
PN_FN void sat_rows_float(PN_GLOBAL const float* depth, PN_GLOBAL float* table,
                          PN_GLOBAL float* carry, PN_GLOBAL float* columns, int column_row,
                          PN_GLOBAL int* bad_rows, const SatParams p, int moments, int x0, int x1, int y0, int y1)
{
    for (int y = y0; y < y1; ++y) {
        pn_float row_sum[4];
        for (int k = 0; k < moments; ++k) row_sum[k] = carry[k * p.depth.height + y];
        pn_mask bad = sat_depth_outside(0.0f);
        PN_FOR_STRIPS(x, x0, x1)
        {
            const pn_float z = pn_load(depth, p.depth, x, y);
            bad = pn_or(bad, sat_depth_outside(z));
            pn_float m = z;
            for (int k = 0; k < moments; ++k) {
                PN_GLOBAL float* column = PN_PLANE(columns, p.columns, k);
                const pn_float row_prefix = pn_scan_add(m) + row_sum[k];
                const pn_float sum = pn_load(column, p.columns, x, column_row) + row_prefix;
                pn_store(column, p.columns, x, column_row, sum);
                pn_store_stream(PN_PLANE(table, p.table, k), p.table, x, y + 1, sum);
                row_sum[k] = pn_last(row_prefix);
                m = m * z;
            }
        }
        for (int k = 0; k < moments; ++k) carry[k * p.depth.height + y] = pn_last_value(row_sum[k]);
        pn_flag_any(bad_rows, y, bad);
    }
}

/* The moment count as a literal lets the compiler unroll the per-moment loop
 * and keep the row sums in registers (measured: docs/moment_table.md). */
PN_FN void sat_block_float(PN_GLOBAL const float* depth, PN_GLOBAL float* table,
                           PN_GLOBAL float* carry, PN_GLOBAL float* columns, int column_row,
                           PN_GLOBAL int* bad_rows, const SatParams p, int x0, int x1, int y0, int y1)
{
    if (p.moments == 2)
        sat_rows_float(depth, table, carry, columns, column_row, bad_rows, p, 2, x0, x1, y0, y1);
    else
        sat_rows_float(depth, table, carry, columns, column_row, bad_rows, p, 4, x0, x1, y0, y1);
}

/* Exact moments of one strip: m_1 = q = round(z * 65535), m_{k+1} =
 * round(m_k * q / 65536). m_k * q <= 65535^2 < 2^32 - 2^15, so no step wraps. */
PN_FN pn_uint sat_exact_next_moment(pn_uint m, pn_uint q)
{
    return pn_ushr(m * q + (pn_uint)32768u, 16);
}

PN_FN void sat_rows_exact(PN_GLOBAL const float* depth, PN_GLOBAL uint* table,
                          PN_GLOBAL uint* carry, PN_GLOBAL uint* columns, int column_row,
                          PN_GLOBAL int* bad_rows, const SatParams p, int moments, int x0, int x1, int y0, int y1)
{
    for (int y = y0; y < y1; ++y) {
        pn_uint row_sum[4];
        for (int k = 0; k < moments; ++k) row_sum[k] = carry[k * p.depth.height + y];
        pn_mask bad = sat_depth_outside(0.0f);
        PN_FOR_STRIPS(x, x0, x1)
        {
            const pn_float z = pn_load(depth, p.depth, x, y);
            bad = pn_or(bad, sat_depth_outside(z));
            const pn_uint q = pn_float_to_uint(pn_floor(z * PN_EXACT_STEPS + 0.5f));
            pn_uint m = q;
            for (int k = 0; k < moments; ++k) {
                PN_GLOBAL uint* column = PN_PLANE(columns, p.columns, k);
                const pn_uint row_prefix = pn_uscan_add(m) + row_sum[k];
                const pn_uint sum = pn_uload(column, p.columns, x, column_row) + row_prefix;
                pn_ustore(column, p.columns, x, column_row, sum);
                pn_ustore_stream(PN_PLANE(table, p.table, k), p.table, x, y + 1, sum);
                row_sum[k] = pn_ulast(row_prefix);
                m = sat_exact_next_moment(m, q);
            }
        }
        for (int k = 0; k < moments; ++k) carry[k * p.depth.height + y] = pn_ulast_value(row_sum[k]);
        pn_flag_any(bad_rows, y, bad);
    }
}

/* The moment count as a literal lets the compiler unroll the per-moment loop
 * and keep the row sums in registers (measured: docs/moment_table.md). */
PN_FN void sat_block_exact(PN_GLOBAL const float* depth, PN_GLOBAL uint* table,
                           PN_GLOBAL uint* carry, PN_GLOBAL uint* columns, int column_row,
                           PN_GLOBAL int* bad_rows, const SatParams p, int x0, int x1, int y0, int y1)
{
    if (p.moments == 2)
        sat_rows_exact(depth, table, carry, columns, column_row, bad_rows, p, 2, x0, x1, y0, y1);
    else
        sat_rows_exact(depth, table, carry, columns, column_row, bad_rows, p, 4, x0, x1, y0, y1);
}

/* Banded schedule, pass 1: band `pn_task` of `band_height` rows becomes a
 * table of its own (zero carries, zero columns in row `pn_task` of `columns`). */
PN_KERNEL void sat_bands_float(PN_GLOBAL const float* depth, PN_GLOBAL float* table, PN_GLOBAL float* carry,
                               PN_GLOBAL float* columns, PN_GLOBAL int* bad_rows, const SatParams p, PN_TASK_ARGS)
{
    const int bands = (p.depth.height + p.band_height - 1) / p.band_height;
    PN_TASK_BEGIN(bands);
    const int y0 = pn_task * p.band_height;
    const int y1 = y0 + p.band_height < p.depth.height ? y0 + p.band_height : p.depth.height;
    sat_block_float(depth, table, carry, columns, pn_task, bad_rows, p, 0, p.depth.width, y0, y1);
}

PN_KERNEL void sat_bands_exact(PN_GLOBAL const float* depth, PN_GLOBAL uint* table, PN_GLOBAL uint* carry,
                               PN_GLOBAL uint* columns, PN_GLOBAL int* bad_rows, const SatParams p, PN_TASK_ARGS)
{
    const int bands = (p.depth.height + p.band_height - 1) / p.band_height;
    PN_TASK_BEGIN(bands);
    const int y0 = pn_task * p.band_height;
    const int y1 = y0 + p.band_height < p.depth.height ? y0 + p.band_height : p.depth.height;
    sat_block_exact(depth, table, carry, columns, pn_task, bad_rows, p, 0, p.depth.width, y0, y1);
}

/* Banded schedule, pass 2, per pixel: adds the column totals of every band
 * above this pixel's band (an exclusive sum over `columns` rows). */
PN_KERNEL void sat_join_bands_float(PN_GLOBAL float* table, PN_GLOBAL const float* columns,
                                    const SatParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.depth.width, p.depth.height);
    const int band = pn_y / p.band_height;
    if (band == 0) return;
    for (int k = 0; k < p.moments; ++k) {
        PN_GLOBAL const float* column = PN_PLANE(columns, p.columns, k);
        pn_float above = 0.0f;
        for (int b = 0; b < band; ++b) above = above + pn_load(column, p.columns, pn_x, b);
        PN_GLOBAL float* plane = PN_PLANE(table, p.table, k);
        pn_store(plane, p.table, pn_x, pn_y + 1, pn_load(plane, p.table, pn_x, pn_y + 1) + above);
    }
}

PN_KERNEL void sat_join_bands_exact(PN_GLOBAL uint* table, PN_GLOBAL const uint* columns,
                                    const SatParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.depth.width, p.depth.height);
    const int band = pn_y / p.band_height;
    if (band == 0) return;
    for (int k = 0; k < p.moments; ++k) {
        PN_GLOBAL const uint* column = PN_PLANE(columns, p.columns, k);
        pn_uint above = 0u;
        for (int b = 0; b < band; ++b) above = above + pn_uload(column, p.columns, pn_x, b);
        PN_GLOBAL uint* plane = PN_PLANE(table, p.table, k);
        pn_ustore(plane, p.table, pn_x, pn_y + 1, pn_uload(plane, p.table, pn_x, pn_y + 1) + above);
    }
}

/* ---- queries ----------------------------------------------------------- */

/* Element index of exclusive corner (x, y), x in [0, width], y in [0, height]:
 * the inclusive sum S(x - 1, y - 1), stored in row y at column x - 1. */
PN_FN pn_int sat_corner_index(pn_dims t, pn_int x, pn_int y)
{
    return y * t.pitch + x - 1;
}

/* Sum over the texels [x0, x1) x [y0, y1) of one plane. */
PN_FN pn_float sat_box_sum_float(PN_GLOBAL const float* plane, pn_dims t, pn_int x0, pn_int x1, pn_int y0,
                                 pn_int y1)
{
    const pn_float s00 = pn_gather(plane, sat_corner_index(t, x0, y0));
    const pn_float s10 = pn_gather(plane, sat_corner_index(t, x1, y0));
    const pn_float s01 = pn_gather(plane, sat_corner_index(t, x0, y1));
    const pn_float s11 = pn_gather(plane, sat_corner_index(t, x1, y1));
    return (s11 - s01) - (s10 - s00);
}

/* The same over an exact table: the wrapped differences are the exact sum. */
PN_FN pn_float sat_box_sum_exact(PN_GLOBAL const uint* plane, pn_dims t, pn_int x0, pn_int x1, pn_int y0,
                                 pn_int y1)
{
    const pn_uint s00 = pn_ugather(plane, sat_corner_index(t, x0, y0));
    const pn_uint s10 = pn_ugather(plane, sat_corner_index(t, x1, y0));
    const pn_uint s01 = pn_ugather(plane, sat_corner_index(t, x0, y1));
    const pn_uint s11 = pn_ugather(plane, sat_corner_index(t, x1, y1));
    return pn_uint_to_float((s11 - s01) - (s10 - s00));
}

/* Scale that turns an exact table's sum of m_k into a sum of z^k:
 * m_1 = 65535 z, and each further moment carries another factor 65535/65536. */
PN_FN float sat_exact_moment_scale(int k)
{
    float scale = 1.0f / PN_EXACT_STEPS;
    for (int i = 1; i < k; ++i) scale = scale * (65536.0f / PN_EXACT_STEPS);
    return scale;
}

/* A window with fractional edges, in exclusive-corner coordinates clipped to
 * the map: the sum over it is the bilinear interpolation of the table at its
 * corners. Per axis, with a = floor(t), f = t - a,
 *     F(t1) - F(t0) = [S(a1) - S(a0)] + f1 [S(a1 + 1) - S(a1)] - f0 [S(a0 + 1) - S(a0)],
 * three integer intervals (the body and two one-texel slivers); in 2D their
 * products are nine integer rectangles, each exact on an exact table. */
typedef struct {
    pn_int x[4];  /* a0, a0 + 1, a1, a1 + 1 (clamped to the width) */
    pn_int y[4];
    pn_float wx[3]; /* weights of body, right sliver, left sliver */
    pn_float wy[3];
} SatFractionalWindow;

PN_FN void sat_fractional_axis(pn_float t0, pn_float t1, int size, pn_int* corner, pn_float* weight)
{
    const pn_float a0 = pn_floor(t0);
    const pn_float a1 = pn_floor(t1);
    corner[0] = pn_to_int(a0);
    corner[1] = pn_to_int(pn_min(a0 + 1.0f, (float)size));
    corner[2] = pn_to_int(a1);
    corner[3] = pn_to_int(pn_min(a1 + 1.0f, (float)size));
    weight[0] = 1.0f;
    weight[1] = t1 - a1;
    weight[2] = a0 - t0;
}

PN_FN SatFractionalWindow sat_fractional_window(pn_dims t, pn_float x0, pn_float x1, pn_float y0, pn_float y1)
{
    SatFractionalWindow w;
    sat_fractional_axis(x0, x1, t.width, w.x, w.wx);
    sat_fractional_axis(y0, y1, t.height, w.y, w.wy);
    return w;
}

/* Interval i of an axis: 0 body [a0, a1], 1 right sliver [a1, a1+1], 2 left sliver [a0, a0+1]. */
PN_FN int sat_interval_lo(int i) { return i == 0 ? 0 : (i == 1 ? 2 : 0); }
PN_FN int sat_interval_hi(int i) { return i == 0 ? 2 : (i == 1 ? 3 : 1); }

PN_FN pn_float sat_fractional_sum_float(PN_GLOBAL const float* plane, pn_dims t, SatFractionalWindow w)
{
    pn_float s[4][4];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) s[j][i] = pn_gather(plane, sat_corner_index(t, w.x[i], w.y[j]));
    pn_float total = 0.0f;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            const int xl = sat_interval_lo(i), xh = sat_interval_hi(i);
            const int yl = sat_interval_lo(j), yh = sat_interval_hi(j);
            const pn_float rect = (s[yh][xh] - s[yh][xl]) - (s[yl][xh] - s[yl][xl]);
            total = total + w.wx[i] * w.wy[j] * rect;
        }
    return total;
}

PN_FN pn_float sat_fractional_sum_exact(PN_GLOBAL const uint* plane, pn_dims t, SatFractionalWindow w)
{
    pn_uint s[4][4];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) s[j][i] = pn_ugather(plane, sat_corner_index(t, w.x[i], w.y[j]));
    pn_float total = 0.0f;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            const int xl = sat_interval_lo(i), xh = sat_interval_hi(i);
            const int yl = sat_interval_lo(j), yh = sat_interval_hi(j);
            const pn_uint rect = (s[yh][xh] - s[yh][xl]) - (s[yl][xh] - s[yl][xl]);
            total = total + w.wx[i] * w.wy[j] * pn_uint_to_float(rect);
        }
    return total;
}

#endif
