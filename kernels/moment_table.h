/* Summed-area tables of depth moments: build and box queries.
 *
 * Computes, for a depth map z(i, j) in [0, 1] (converted where it is loaded
 * from the map's convention, kernels/depth_convention.h), the inclusive sums
 *     S_k(x, y) = sum_{i <= x, j <= y} m_k(i, j),  m_k = z^k, k = 1 .. moments
 * (Crow 1984; as used for variance shadow maps by Lauritzen, GPU Gems 3 ch. 8),
 * so that the sum of m_k over any rectangle costs four reads.
 *
 * Two precisions:
 *  - exact (the default): "limb" tables. Each per-texel value v in [0, 1]
 *    (z^k, or EVSM's warps, computed in double from the float32 depth) is
 *    rounded to 16 L bits, v_q = round(v 2^(16L)) / 2^(16L) (error at most
 *    2^-(16L+1): 1.2e-10 for L = 2, 1.8e-15 for L = 3), and split into L
 *    16-bit limbs, most significant first; each limb is summed in wrapping
 *    uint32 (value k, limb l: "plane" k L + l of the carries and columns).
 *    Storage: limbs 0 and 1 of value k are interleaved in one pair plane
 *    (PN_PLANE k L, two plane pitches: element 2 i + l for corner index i), so
 *    that one 64-bit gather fetches both limbs of a corner and a fractional
 *    window's corner pair (a, a + 1) is 16 contiguous bytes; limb 2 of a
 *    3-limb table has the plane after (PN_PLANE k L + 2).
 *    Limb 0 is at most 65536 (v = 1), the others at most 65535, so a wrapped
 *    window difference of a limb plane is the exact limb sum while the
 *    window holds A <= 65535 texels (255 x 255 = 65025 is the largest used),
 *    on maps of any size. A window's mean of v is
 *        E[v] = (sum_l S_l 2^(-16 (l + 1))) / A,
 *    formed in double: for L = 2 the bracket is an exact integer multiple of
 *    2^-32 below 2^17 (exact in double); for L = 3 it rounds once, at 2^-53
 *    relative. docs/moment_table.md has the error analysis.
 *  - float: m_k = z^k in float. Fast; its error grows with the table's
 *    magnitude (docs/moment_table.md gives the measured worst case).
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

#define PN_EXACT_MAX_AREA 65535  /* texels: the largest window whose limb sums stay exact */
#define PN_MAX_PLANES 12         /* 4 values x 3 limbs */

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
 * A depth outside its convention's range (NaN and infinities included) sets bad_rows[y]. */
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
            const pn_float stored = pn_load(depth, p.depth, x, y);
            bad = pn_or(bad, depth_outside(stored, p.convention));
            const pn_float z = depth_checked_to_normalized(stored, p.convention);
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

/* The values of one strip (double, from the float32 depth clamped into
 * [0, 1]): z, z^2 (, z^3, z^4), or EVSM's warps w+ = e^{c+ (z - 1)}, w+^2
 * (, |w-| = e^{-c- z}, w-^2) (kernels/exponential_warp.h). `encoding` is
 * PN_TABLE_POWERS or PN_TABLE_EVSM. The table build and the direct window
 * sums (kernels/box_window.h) both take their values from here, so that a
 * window summed either way sums the same doubles. */
PN_FN void texel_values(pn_float z, int encoding, float c_positive, float c_negative, int moments, pn_double* v)
{
    const pn_double d = pn_to_double(pn_clamp(z, 0.0f, 1.0f));
    if (encoding == PN_TABLE_EVSM) {
        v[0] = pn_dexp((double)c_positive * (d - 1.0));
        v[1] = v[0] * v[0];
        if (moments == 4) {
            v[2] = pn_dexp(-(double)c_negative * d);
            v[3] = v[2] * v[2];
        }
        return;
    }
    v[0] = d;
    for (int k = 1; k < moments; ++k) v[k] = v[k - 1] * d;
}

PN_FN void sat_texel_values(pn_float z, const SatParams p, int moments, pn_double* v)
{
    texel_values(z, p.encoding, p.exponent_positive, p.exponent_negative, moments, v);
}

/* The `limbs` 16-bit limbs of v in [0, 1] rounded to 16 limbs bits, most
 * significant first. Adding half a step rounds to nearest; each step then
 * takes the next 16 bits (multiplying by 2^16 and removing the integer part
 * are exact in double). */
PN_FN void sat_limbs(pn_double v, int limbs, pn_uint* out)
{
    double half_step = 0.5;
    for (int l = 0; l < limbs; ++l) half_step = half_step * (1.0 / 65536.0);
    pn_double rest = v + half_step;
    for (int l = 0; l < limbs; ++l) {
        rest = rest * 65536.0;
        const pn_double limb = pn_dfloor(rest);
        out[l] = pn_double_to_uint(limb);
        rest = rest - limb;
    }
}

/* sat_limbs(z, 2, out) for the depth itself (z in [0, 1] as read), at the
 * width of a float batch instead of two double batches: the same integers,
 * q = floor(z 2^32 + 1/2) split at 2^16, every step exact in float.
 * t = z 2^32 is a power-of-two scaling; t - floor(t) is exact (t >= 2^23 is
 * already an integer, and then no carry is added); below that floor(t) + 1
 * <= 2^23 is exact; l0 = floor(q 2^-16), and q - l0 2^16, an integer below
 * 2^16, is the exact difference of two floats. Ties round up, as in sat_limbs. */
PN_FN void sat_depth_limbs2(pn_float z, pn_uint* out)
{
    const pn_float t = z * 4294967296.0f;
    const pn_float whole = pn_floor(t);
    const pn_float q = pn_select(t - whole >= 0.5f, whole + 1.0f, whole);
    const pn_float l0 = pn_floor(q * (1.0f / 65536.0f));
    out[0] = pn_float_to_uint(l0);
    out[1] = pn_float_to_uint(q - l0 * 65536.0f);
}

/* `depth_in_float`: value 0 is the depth itself with 2 limbs (a VSM table),
 * whose limbs sat_depth_limbs2 forms at float width (measured:
 * docs/moment_table.md); the other values go through double. */
PN_FN void sat_rows_exact(PN_GLOBAL const float* depth, PN_GLOBAL uint* table,
                          PN_GLOBAL uint* carry, PN_GLOBAL uint* columns, int column_row,
                          PN_GLOBAL int* bad_rows, const SatParams p, int moments, int limbs, int depth_in_float,
                          int x0, int x1, int y0, int y1)
{
    const int planes = moments * limbs;
    for (int y = y0; y < y1; ++y) {
        pn_uint row_sum[PN_MAX_PLANES];
        for (int k = 0; k < planes; ++k) row_sum[k] = carry[k * p.depth.height + y];
        pn_mask bad = sat_depth_outside(0.0f);
        DepthStrip next = depth_strip(depth, p.depth, x0, y, p.convention);
        PN_FOR_STRIPS(x, x0, x1)
        {
            const DepthStrip here = next;
            next = depth_strip(depth, p.depth, PN_STRIP_AFTER(x), y, p.convention);
            bad = pn_or(bad, depth_outside(here.stored, p.convention));
            const pn_float z = here.unclamped;  /* both clamp it next */
            pn_double v[4];
            sat_texel_values(z, p, moments, v);
            pn_uint q[PN_MAX_PLANES];
            if (depth_in_float) sat_depth_limbs2(pn_clamp(z, 0.0f, 1.0f), q);
            for (int k = depth_in_float; k < moments; ++k) sat_limbs(v[k], limbs, q + k * limbs);
            pn_uint sum[PN_MAX_PLANES];
            for (int k = 0; k < planes; ++k) {
                PN_GLOBAL uint* column = PN_PLANE(columns, p.columns, k);
                const pn_uint row_prefix = pn_uscan_add(q[k]) + row_sum[k];
                sum[k] = pn_uload(column, p.columns, x, column_row) + row_prefix;
                pn_ustore(column, p.columns, x, column_row, sum[k]);
                row_sum[k] = pn_ulast(row_prefix);
            }
            for (int k = 0; k < moments; ++k) {
                pn_ustore_pair_stream(PN_PLANE(table, p.table, k * limbs), p.table, x, y + 1, sum[k * limbs],
                                      sum[k * limbs + 1]);
                if (limbs == 3)
                    pn_ustore_stream(PN_PLANE(table, p.table, k * limbs + 2), p.table, x, y + 1, sum[k * limbs + 2]);
            }
        }
        for (int k = 0; k < planes; ++k) carry[k * p.depth.height + y] = pn_ulast_value(row_sum[k]);
        pn_flag_any(bad_rows, y, bad);
    }
}

/* The value and limb counts as literals let the compiler unroll the
 * per-plane loops and keep the row sums in registers (measured:
 * docs/moment_table.md). */
PN_FN void sat_block_exact(PN_GLOBAL const float* depth, PN_GLOBAL uint* table,
                           PN_GLOBAL uint* carry, PN_GLOBAL uint* columns, int column_row,
                           PN_GLOBAL int* bad_rows, const SatParams p, int x0, int x1, int y0, int y1)
{
    const int powers = p.encoding == PN_TABLE_POWERS;
    if (p.moments == 2 && p.limbs == 2 && powers)
        sat_rows_exact(depth, table, carry, columns, column_row, bad_rows, p, 2, 2, 1, x0, x1, y0, y1);
    else if (p.moments == 2 && p.limbs == 2)
        sat_rows_exact(depth, table, carry, columns, column_row, bad_rows, p, 2, 2, 0, x0, x1, y0, y1);
    else if (p.moments == 4 && p.limbs == 2)
        sat_rows_exact(depth, table, carry, columns, column_row, bad_rows, p, 4, 2, 0, x0, x1, y0, y1);
    else if (p.moments == 2)
        sat_rows_exact(depth, table, carry, columns, column_row, bad_rows, p, 2, 3, 0, x0, x1, y0, y1);
    else
        sat_rows_exact(depth, table, carry, columns, column_row, bad_rows, p, 4, 3, 0, x0, x1, y0, y1);
}

/* Banded schedule, pass 1: band `pn_task` of `band_height` rows becomes a
 * table of its own (zero carries, zero columns in row `pn_task` of `columns`). */
#define PN_SAT_BANDS_KERNEL(variant, T)                                                                            \
PN_KERNEL void sat_bands_##variant(PN_GLOBAL const float* depth, PN_GLOBAL T* table, PN_GLOBAL T* carry,           \
                                   PN_GLOBAL T* columns, PN_GLOBAL int* bad_rows, const SatParams p, PN_TASK_ARGS) \
{                                                                                                                  \
    PN_TASK_BEGIN((p.depth.height + p.band_height - 1) / p.band_height);                                           \
    const int y0 = pn_task * p.band_height;                                                                        \
    const int y1 = y0 + p.band_height < p.depth.height ? y0 + p.band_height : p.depth.height;                      \
    sat_block_##variant(depth, table, carry, columns, pn_task, bad_rows, p, 0, p.depth.width, y0, y1);             \
}
PN_TABLE_VARIANTS(PN_SAT_BANDS_KERNEL)

/* Banded schedule, pass 2, per pixel: adds the column totals of every band
 * above this pixel's band (an exclusive sum over `columns` rows), band > 0,
 * to the strip at (x, y + 1) of every plane. */
PN_FN void sat_join_add_float(PN_GLOBAL float* table, PN_GLOBAL const float* columns, const SatParams p, int x, int y,
                              int band)
{
    for (int k = 0; k < p.moments * p.limbs; ++k) {
        PN_GLOBAL const float* column = PN_PLANE(columns, p.columns, k);
        pn_float above = 0.0f;
        for (int b = 0; b < band; ++b) above = above + pn_load(column, p.columns, x, b);
        PN_GLOBAL float* plane = PN_PLANE(table, p.table, k);
        pn_store(plane, p.table, x, y + 1, pn_load(plane, p.table, x, y + 1) + above);
    }
}

/* The same on an exact table, each moment's limbs as laid out at the top of this file. */
PN_FN void sat_join_add_exact(PN_GLOBAL uint* table, PN_GLOBAL const uint* columns, const SatParams p, int x, int y,
                              int band)
{
    pn_uint above[PN_MAX_PLANES];
    for (int k = 0; k < p.moments * p.limbs; ++k) {
        PN_GLOBAL const uint* column = PN_PLANE(columns, p.columns, k);
        above[k] = 0u;
        for (int b = 0; b < band; ++b) above[k] = above[k] + pn_uload(column, p.columns, x, b);
    }
    for (int k = 0; k < p.moments; ++k) {
        if (p.limbs == 1) {
            PN_GLOBAL uint* plane = PN_PLANE(table, p.table, k);
            pn_ustore(plane, p.table, x, y + 1, pn_uload(plane, p.table, x, y + 1) + above[k]);
            continue;
        }
        /* The limb tables' layout (top of this file): a pair plane, then limb 2. */
        PN_GLOBAL uint* pair = PN_PLANE(table, p.table, k * p.limbs);
        pn_uint first, second;
        pn_uload_pair(pair, p.table, x, y + 1, &first, &second);
        pn_ustore_pair_stream(pair, p.table, x, y + 1, first + above[k * p.limbs], second + above[k * p.limbs + 1]);
        if (p.limbs == 3) {
            PN_GLOBAL uint* plane = PN_PLANE(table, p.table, k * p.limbs + 2);
            pn_ustore(plane, p.table, x, y + 1, pn_uload(plane, p.table, x, y + 1) + above[k * p.limbs + 2]);
        }
    }
}

#define PN_SAT_JOIN_BANDS_KERNEL(variant, T)                                                               \
PN_KERNEL void sat_join_bands_##variant(PN_GLOBAL T* table, PN_GLOBAL const T* columns, const SatParams p, \
                                        PN_PIXEL_ARGS)                                                     \
{                                                                                                          \
    PN_PIXEL_BEGIN(p.depth.width, p.depth.height);                                                         \
    const int band = pn_y / p.band_height;                                                                 \
    if (band == 0) return;                                                                                 \
    sat_join_add_##variant(table, columns, p, pn_x, pn_y, band);                                           \
}
PN_TABLE_VARIANTS(PN_SAT_JOIN_BANDS_KERNEL)

/* ---- queries ----------------------------------------------------------- */

/* Element index of exclusive corner (x, y), x in [0, width], y in [0, height]:
 * the inclusive sum S(x - 1, y - 1), stored in row y at column x - 1. */
PN_FN pn_int sat_corner_index(pn_dims t, pn_int x, pn_int y)
{
    return y * t.pitch + x - 1;
}

/* Sum over the texels [x0, x1) x [y0, y1) of one plane; on a uint table
 * the wrapped difference, exact while the true sum is below 2^32. */
#define PN_SAT_BOX_SUM(variant, T)                                                                            \
PN_FN pn_sum_##variant sat_box_sum_##variant(PN_GLOBAL const T* plane, pn_dims t, pn_int x0, pn_int x1,       \
                                             pn_int y0, pn_int y1)                                            \
{                                                                                                             \
    const pn_sum_##variant s00 = pn_sum_gather_##variant(plane, sat_corner_index(t, x0, y0));                 \
    const pn_sum_##variant s10 = pn_sum_gather_##variant(plane, sat_corner_index(t, x1, y0));                 \
    const pn_sum_##variant s01 = pn_sum_gather_##variant(plane, sat_corner_index(t, x0, y1));                 \
    const pn_sum_##variant s11 = pn_sum_gather_##variant(plane, sat_corner_index(t, x1, y1));                 \
    return (s11 - s01) - (s10 - s00);                                                                         \
}
PN_TABLE_VARIANTS(PN_SAT_BOX_SUM)

/* The same over a pair plane: both limbs of the four corners, one 64-bit
 * gather element per corner and lane, subtracted as gathered (pn_upair). */
PN_FN pn_upair sat_box_sum_pair(PN_GLOBAL const uint* pair, pn_dims t, pn_int x0, pn_int x1, pn_int y0, pn_int y1)
{
    const pn_upair a = pn_ugather_upair(pair, sat_corner_index(t, x0, y0) * 2);
    const pn_upair b = pn_ugather_upair(pair, sat_corner_index(t, x1, y0) * 2);
    const pn_upair c = pn_ugather_upair(pair, sat_corner_index(t, x0, y1) * 2);
    const pn_upair d = pn_ugather_upair(pair, sat_corner_index(t, x1, y1) * 2);
    return (d - c) - (b - a);
}

/* sat_box_sum_pair of two pair planes at once (values 0 and 1), each
 * corner's index extracted once for both (pn_ugather_upair_both). */
PN_FN void sat_box_sum_pairs(PN_GLOBAL const uint* pair_a, PN_GLOBAL const uint* pair_b, pn_dims t, pn_int x0,
                             pn_int x1, pn_int y0, pn_int y1, pn_upair* sums)
{
    pn_upair a[4], b[4];
    pn_ugather_upair_both(pair_a, pair_b, sat_corner_index(t, x0, y0) * 2, &a[0], &b[0]);
    pn_ugather_upair_both(pair_a, pair_b, sat_corner_index(t, x1, y0) * 2, &a[1], &b[1]);
    pn_ugather_upair_both(pair_a, pair_b, sat_corner_index(t, x0, y1) * 2, &a[2], &b[2]);
    pn_ugather_upair_both(pair_a, pair_b, sat_corner_index(t, x1, y1) * 2, &a[3], &b[3]);
    sums[0] = (a[3] - a[2]) - (a[1] - a[0]);
    sums[1] = (b[3] - b[2]) - (b[1] - b[0]);
}

/* The value of one step of limb 0: 2^-16 in limb tables; a table of one
 * limb per value holds 16-bit steps v * 65535 instead (kernels/encoded_table.h,
 * the opt-in 16-bit storages). */
PN_FN double sat_limb_unit(int limbs)
{
    return limbs == 1 ? 1.0 / 65535.0 : 1.0 / 65536.0;
}

/* Sum of value k of a limb table over the texels [x0, x1) x [y0, y1), in units
 * of `unit` per step of limb 0 (2^-16 for limb tables, each further limb
 * 2^-16 of the one before): sum_l S_l unit 2^(-16 l). Limbs 0 and 1 join
 * exactly (S_0 2^16 + S_1 < 2^49); a third limb adds one rounding. */
PN_FN pn_double sat_limb_box_sum(PN_GLOBAL const uint* table, pn_dims t, int limbs, int k, double unit, pn_int x0,
                                 pn_int x1, pn_int y0, pn_int y1)
{
    if (limbs == 1) return pn_uint_to_double(sat_box_sum_exact(PN_PLANE(table, t, k), t, x0, x1, y0, y1)) * unit;
    const pn_double total =
        pn_upair_join(sat_box_sum_pair(PN_PLANE(table, t, k * limbs), t, x0, x1, y0, y1)) * (unit * (1.0 / 65536.0));
    if (limbs == 2) return total;
    const pn_uint s2 = sat_box_sum_exact(PN_PLANE(table, t, k * limbs + 2), t, x0, x1, y0, y1);
    return total + pn_uint_to_double(s2) * (unit * (1.0 / 4294967296.0));
}

/* Values 0 and 1 of a 2-limb table over the texels [x0, x1) x [y0, y1) into
 * sums[0] and sums[1]: sat_limb_box_sum's doubles, both pair planes' corners
 * read together (VSM, VSSM's search; docs/moment_table.md, "Session 17");
 * other limb counts value by value. */
PN_FN void sat_limb_box_sums01(PN_GLOBAL const uint* table, pn_dims t, int limbs, double unit, pn_int x0, pn_int x1,
                               pn_int y0, pn_int y1, pn_double* sums)
{
    if (limbs != 2) {
        for (int k = 0; k < 2; ++k) sums[k] = sat_limb_box_sum(table, t, limbs, k, unit, x0, x1, y0, y1);
        return;
    }
    pn_upair pairs[2];
    sat_box_sum_pairs(PN_PLANE(table, t, 0), PN_PLANE(table, t, 2), t, x0, x1, y0, y1, pairs);
    for (int k = 0; k < 2; ++k) sums[k] = pn_upair_join(pairs[k]) * (unit * (1.0 / 65536.0));
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

/* The 4 x 4 corner values s[row][column] of a fractional window, of one uint
 * plane. Corners a and a + 1 of a row are adjacent elements: one pair gather
 * each. The pair reads a + 1 unclamped: at a1 = width that is the row's zero
 * padding (pitch > width), under the right sliver's weight t1 - a1 = 0. */
PN_FN void sat_fractional_corners(PN_GLOBAL const uint* plane, pn_dims t, SatFractionalWindow w, pn_uint s[4][4])
{
    for (int j = 0; j < 4; ++j) {
        pn_ugather_pair(plane, sat_corner_index(t, w.x[0], w.y[j]), &s[j][0], &s[j][1]);
        pn_ugather_pair(plane, sat_corner_index(t, w.x[2], w.y[j]), &s[j][2], &s[j][3]);
    }
}

/* The same for both limbs of a pair plane, kept whole: the corner pair
 * (a, a + 1) is 16 contiguous bytes, read as one (pn_ugather_upair2). */
PN_FN void sat_fractional_corners_pair(PN_GLOBAL const uint* pair, pn_dims t, SatFractionalWindow w, pn_upair s[4][4])
{
    for (int j = 0; j < 4; ++j)
        for (int c = 0; c < 4; c += 2) {
            const pn_int i = sat_corner_index(t, w.x[c], w.y[j]) * 2;
            pn_ugather_upair2(pair, i, &s[j][c], &s[j][c + 1]);
        }
}

/* Rectangle (i, j) of a fractional window (intervals i along x, j along y)
 * from one plane's 4 x 4 corner values: the wrapped difference, exact. */
PN_FN pn_uint sat_fractional_rect(pn_uint s[4][4], int i, int j)
{
    const int xl = sat_interval_lo(i), xh = sat_interval_hi(i);
    const int yl = sat_interval_lo(j), yh = sat_interval_hi(j);
    return (s[yh][xh] - s[yh][xl]) - (s[yl][xh] - s[yl][xl]);
}

/* The nine rectangles' values weighted over a fractional window: the weights
 * are exact in double (differences of float32 corners), the sum rounds at
 * 2^-53 relative. */
PN_FN pn_double sat_fractional_weighted_rects(pn_double rect[3][3], SatFractionalWindow w)
{
    pn_double total = 0.0;
    for (int j = 0; j < 3; ++j) {
        pn_double row = 0.0;
        for (int i = 0; i < 3; ++i) row = row + pn_to_double(w.wx[i]) * rect[j][i];
        total = total + pn_to_double(w.wy[j]) * row;
    }
    return total;
}

/* One plane's corner values weighted over a fractional window, in double
 * (every integer rectangle is exact). */
PN_FN pn_double sat_fractional_weighted(pn_uint s[4][4], SatFractionalWindow w)
{
    pn_double rect[3][3];
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) rect[j][i] = pn_uint_to_double(sat_fractional_rect(s, i, j));
    return sat_fractional_weighted_rects(rect, w);
}

/* The same for limbs 0 and 1 of a pair plane at once, in steps of limb 1:
 * each rectangle is subtracted as gathered, both limbs in one wrapping
 * subtraction, and joined, R0 2^16 + R1, an integer below 2^48 (exact in
 * double), so that the weighted sum is formed once instead of once per limb
 * and no lane is moved between the gather and the double arithmetic
 * (measured: docs/moment_table.md). */
PN_FN pn_double sat_fractional_weighted_pair(pn_upair s[4][4], SatFractionalWindow w)
{
    pn_double rect[3][3];
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            const int xl = sat_interval_lo(i), xh = sat_interval_hi(i);
            const int yl = sat_interval_lo(j), yh = sat_interval_hi(j);
            rect[j][i] = pn_upair_join((s[yh][xh] - s[yh][xl]) - (s[yl][xh] - s[yl][xl]));
        }
    return sat_fractional_weighted_rects(rect, w);
}

/* Row j of a fractional window in the pair planes of values 0 and 1 (a and
 * b): its three x intervals' wrapped differences s[hi(i)] - s[lo(i)], both
 * planes' corners read at once (pn_ugather_upair2_both). */
PN_FN void sat_fractional_row_pairs(PN_GLOBAL const uint* pair_a, PN_GLOBAL const uint* pair_b, pn_dims t,
                                    SatFractionalWindow w, int j, pn_upair* da, pn_upair* db)
{
    pn_upair a[4], b[4];
    for (int c = 0; c < 4; c += 2)
        pn_ugather_upair2_both(pair_a, pair_b, sat_corner_index(t, w.x[c], w.y[j]) * 2, a + c, b + c);
    for (int i = 0; i < 3; ++i) {
        da[i] = a[sat_interval_hi(i)] - a[sat_interval_lo(i)];
        db[i] = b[sat_interval_hi(i)] - b[sat_interval_lo(i)];
    }
}

/* One y interval's row of sat_fractional_weighted_rects: sum_i wx_i R_i with
 * R_i = hi[i] - lo[i] joined (the rectangle's exact integer, as
 * sat_fractional_weighted_pair forms it), in the same order. */
PN_FN pn_double sat_fractional_weighted_row(pn_upair* hi, pn_upair* lo, SatFractionalWindow w)
{
    pn_double row = 0.0;
    for (int i = 0; i < 3; ++i) row = row + pn_to_double(w.wx[i]) * pn_upair_join(hi[i] - lo[i]);
    return row;
}

/* Values 0 and 1 of a 2-limb table over a fractional window, into sums[0]
 * and sums[1]: sat_limb_fractional_sum's doubles (the same rectangles and
 * operations in the same order), with both pair planes read at once and the
 * rows read in the order the y intervals use them (left sliver rows 0, 1;
 * body 0, 2; right 2, 3), so that at most two rows' differences are live
 * (docs/moment_table.md, "Session 17"). */
PN_FN void sat_limb_fractional_sums01(PN_GLOBAL const uint* table, pn_dims t, double unit, SatFractionalWindow w,
                                      pn_double* sums)
{
    PN_GLOBAL const uint* pair_a = PN_PLANE(table, t, 0);
    PN_GLOBAL const uint* pair_b = PN_PLANE(table, t, 2);
    pn_upair a0[3], b0[3], a1[3], b1[3];
    sat_fractional_row_pairs(pair_a, pair_b, t, w, 0, a0, b0);
    sat_fractional_row_pairs(pair_a, pair_b, t, w, 1, a1, b1);
    const pn_double left_a = sat_fractional_weighted_row(a1, a0, w), left_b = sat_fractional_weighted_row(b1, b0, w);
    sat_fractional_row_pairs(pair_a, pair_b, t, w, 2, a1, b1);
    const pn_double body_a = sat_fractional_weighted_row(a1, a0, w), body_b = sat_fractional_weighted_row(b1, b0, w);
    sat_fractional_row_pairs(pair_a, pair_b, t, w, 3, a0, b0);
    const pn_double right_a = sat_fractional_weighted_row(a0, a1, w), right_b = sat_fractional_weighted_row(b0, b1, w);
    /* sat_fractional_weighted_rects' sum: body, right, left */
    const pn_double wy0 = pn_to_double(w.wy[0]), wy1 = pn_to_double(w.wy[1]), wy2 = pn_to_double(w.wy[2]);
    const double scale = unit * (1.0 / 65536.0);
    sums[0] = (((pn_double)0.0 + wy0 * body_a) + wy1 * right_a + wy2 * left_a) * scale;
    sums[1] = (((pn_double)0.0 + wy0 * body_b) + wy1 * right_b + wy2 * left_b) * scale;
}

/* Value k of a limb table over a fractional window (sat_limb_box_sum's units). */
PN_FN pn_double sat_limb_fractional_sum(PN_GLOBAL const uint* table, pn_dims t, int limbs, int k, double unit,
                                        SatFractionalWindow w)
{
    pn_uint s[4][4];
    if (limbs == 1) {
        sat_fractional_corners(PN_PLANE(table, t, k), t, w, s);
        return sat_fractional_weighted(s, w) * unit;
    }
    pn_upair pairs[4][4];
    sat_fractional_corners_pair(PN_PLANE(table, t, k * limbs), t, w, pairs);
    pn_double total = sat_fractional_weighted_pair(pairs, w) * (unit * (1.0 / 65536.0));
    if (limbs == 3) {
        sat_fractional_corners(PN_PLANE(table, t, k * limbs + 2), t, w, s);
        total = total + sat_fractional_weighted(s, w) * (unit * (1.0 / 4294967296.0));
    }
    return total;
}

#endif
