/* The receiver's own plane as the kernels read it: depth slopes dz/du, dz/dv
 * (depth per unit of texture coordinate) and the flag that they hold, the
 * receivers' planes PN_PCF_PLANE_DZDU, _DZDV and _OK (kernels/params.h), which
 * the host appends (host/src/receiver_plane.cpp: finite differences on the
 * receivers' grid, or the receivers' own channels dzdu, dzdv). One reader for
 * the two families that bias by that plane: the percentage-closer family
 * (kernels/depth_bias.h) and moment soft shadows (kernels/msm_soft.h).
 *
 * Non-finite values flag the row (bad_rows) and are read as 0, so that no
 * lane forms a NaN or an out-of-range index; the host reports the row.
 */
#ifndef PENUMBRA_RECEIVER_SLOPE_H
#define PENUMBRA_RECEIVER_SLOPE_H

typedef struct {
    pn_float dzdu, dzdv;
    pn_mask holds; /* the derivatives hold here (no depth discontinuity across them) */
} ReceiverSlope;

/* Receiver plane c at (x, y), read as 0 where it is not finite (and the row flagged). */
PN_FN pn_float load_checked_plane(PN_GLOBAL const float* receivers, pn_dims d, int c, int x, int y,
                                  PN_GLOBAL int* bad_rows)
{
    const pn_float value = pn_load(PN_PLANE(receivers, d, c), d, x, y);
    const pn_mask finite = pn_finite(value);
    pn_flag_any(bad_rows, y, pn_not(finite));
    return pn_select(finite, value, 0.0f);
}

/* A level plane that never holds: what a receiver without derivatives gets. */
PN_FN ReceiverSlope no_receiver_slope(void)
{
    ReceiverSlope s;
    s.dzdu = 0.0f;
    s.dzdv = 0.0f;
    s.holds = s.dzdu != s.dzdu; /* all false */
    return s;
}

PN_FN ReceiverSlope load_receiver_slope(PN_GLOBAL const float* receivers, pn_dims d, int x, int y,
                                        PN_GLOBAL int* bad_rows)
{
    ReceiverSlope s;
    s.dzdu = load_checked_plane(receivers, d, PN_PCF_PLANE_DZDU, x, y, bad_rows);
    s.dzdv = load_checked_plane(receivers, d, PN_PCF_PLANE_DZDV, x, y, bad_rows);
    s.holds = load_checked_plane(receivers, d, PN_PCF_PLANE_OK, x, y, bad_rows) > 0.5f;
    return s;
}

#endif
