/* Summed-area tables of encoded texels: the four optimized moments of MSM
 * (kernels/moment_quantize.h) or the exponential warps of EVSM
 * (kernels/exponential_warp.h), and the window means read from them.
 *
 * Per texel, depth z in [0, 1] becomes `channels` values v_k in [0, 1]; the
 * table holds their inclusive sums with the layout of kernels/moment_table.h
 * (row y at table + (y + 1) * pitch, zero row and column before), so that
 * table's box and fractional queries apply unchanged.
 *  - exact tables: q_k = round(v_k * 65535) summed in wrapping uint32. Every
 *    q_k <= 65535, so a window of at most 65537 texels (255 x 255) has an
 *    exact sum (the argument of moment_table.h); its mean is sum / (65535 A).
 *  - float tables: v_k, or with `quantize` v_k rounded to a 16-bit step,
 *    summed in float (the float table's error: docs/moment_table.md).
 * A depth outside [0, 1] (NaN and infinities included) flags its row.
 *
 * Schedule (the host's, both backends): bands of `band_height` rows are
 * scanned in parallel, each from zero, each leaving its column totals in row
 * `band` of `columns`; then sat_join_bands_* (moment_table.h) adds the totals
 * of the bands above to every pixel.
 */
#ifndef PENUMBRA_ENCODED_TABLE_H
#define PENUMBRA_ENCODED_TABLE_H

PN_FN void encode_texel(pn_float z, const EncodedSatParams p, pn_float* v)
{
    if (p.encoding == PN_ENCODE_MSM)
        msm_encode_optimized(z, v);
    else
        evsm_encode(z, p.exponent_positive, p.exponent_negative, p.channels, v);
    if (p.quantize)
        for (int k = 0; k < p.channels; ++k) v[k] = msm_quantize_step(v[k]);
}

PN_FN pn_uint encoded_step(pn_float v)
{
    return pn_float_to_uint(pn_floor(pn_clamp(v, 0.0f, 1.0f) * PN_QUANTIZE_STEPS + 0.5f));
}

/* A texel's encoded value v_k as the table sums it: v_k itself (float), or
 * its 16-bit step (exact). */
PN_FN pn_float encoded_summand_float(pn_float v) { return v; }
PN_FN pn_uint encoded_summand_exact(pn_float v) { return encoded_step(v); }

/* Rows [y0, y1) of one band, either variant: per channel, the strip's
 * in-register prefix sum plus the row's carried sum, plus the band's running
 * column sums (row `band` of `columns`). */
#define PN_ENCODED_BAND(variant, T)                                                                                \
PN_FN void encoded_band_##variant(PN_GLOBAL const float* depth, PN_GLOBAL T* table, PN_GLOBAL T* columns,          \
                                  PN_GLOBAL int* bad_rows, const EncodedSatParams p, int band, int y0, int y1)     \
{                                                                                                                  \
    for (int y = y0; y < y1; ++y) {                                                                                \
        pn_sum_##variant row_sum[4];                                                                               \
        for (int k = 0; k < p.channels; ++k) row_sum[k] = (T)0;                                                    \
        pn_mask bad = sat_depth_outside(0.0f);                                                                     \
        DepthStrip next = depth_strip(depth, p.depth, 0, y, p.convention);                                         \
        PN_FOR_STRIPS(x, 0, p.depth.width)                                                                         \
        {                                                                                                          \
            const DepthStrip here = next;                                                                          \
            next = depth_strip(depth, p.depth, PN_STRIP_AFTER(x), y, p.convention);                                \
            bad = pn_or(bad, depth_outside(here.stored, p.convention));                                            \
            pn_float v[4];                                                                                         \
            encode_texel(pn_clamp(here.unclamped, 0.0f, 1.0f), p, v);                                              \
            for (int k = 0; k < p.channels; ++k) {                                                                 \
                PN_GLOBAL T* column = PN_PLANE(columns, p.columns, k);                                             \
                const pn_sum_##variant row_prefix =                                                                \
                    pn_sum_scan_##variant(encoded_summand_##variant(v[k])) + row_sum[k];                           \
                const pn_sum_##variant sum = pn_sum_load_##variant(column, p.columns, x, band) + row_prefix;      \
                pn_sum_store_##variant(column, p.columns, x, band, sum);                                           \
                pn_sum_store_##variant(PN_PLANE(table, p.table, k), p.table, x, y + 1, sum);                      \
                row_sum[k] = pn_sum_last_##variant(row_prefix);                                                    \
            }                                                                                                      \
        }                                                                                                          \
        pn_flag_any(bad_rows, y, bad);                                                                             \
    }                                                                                                              \
}
PN_TABLE_VARIANTS(PN_ENCODED_BAND)

/* Pass 1: band `pn_task` becomes a table of its own. Lanes past the width
 * add encoded zeros to the row sums, but only after the row's last pixel. */
#define PN_ENCODED_BANDS_KERNEL(variant, T)                                                                    \
PN_KERNEL void encoded_bands_##variant(PN_GLOBAL const float* depth, PN_GLOBAL T* table, PN_GLOBAL T* columns, \
                                       PN_GLOBAL int* bad_rows, const EncodedSatParams p, PN_TASK_ARGS)        \
{                                                                                                              \
    PN_TASK_BEGIN((p.depth.height + p.band_height - 1) / p.band_height);                                       \
    const int y0 = pn_task * p.band_height;                                                                    \
    const int y1 = y0 + p.band_height < p.depth.height ? y0 + p.band_height : p.depth.height;                  \
    encoded_band_##variant(depth, table, columns, bad_rows, p, pn_task, y0, y1);                               \
}
PN_TABLE_VARIANTS(PN_ENCODED_BANDS_KERNEL)

/* ---- window means ----------------------------------------------------- */

/* The area of a texel window, as the mean's divisor. */
PN_FN pn_float texel_window_area(TexelWindow w)
{
    return pn_int_to_float((w.x1 - w.x0) * (w.y1 - w.y0));
}

/* Mean of plane k over the texels of `w` (`area` texels), float table. */
PN_FN pn_double encoded_box_mean_float(PN_GLOBAL const float* table, pn_dims t, int k, TexelWindow w, pn_float area)
{
    return pn_to_double(sat_box_sum_float(PN_PLANE(table, t, k), t, w.x0, w.x1, w.y0, w.y1) / area);
}

/* The same over a fractional window (kernels/moment_table.h) of `area` texels. */
PN_FN pn_double encoded_fractional_mean_float(PN_GLOBAL const float* table, pn_dims t, int k, SatFractionalWindow w,
                                              pn_float area)
{
    return pn_to_double(sat_fractional_sum_float(PN_PLANE(table, t, k), t, w) / area);
}

#endif
