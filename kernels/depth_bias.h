/* Depth bias of the percentage-closer family: how a tap's stored depth is
 * compared with the receiver. One file for every method of the family (pcf,
 * pcf_gauss, pcf_disc, and pcss / burley), so the modes mean the same in all.
 *
 * A tap at texel (tx, ty) of the map is lit when
 *     depth(tx, ty) >= z - beta,
 * z the receiver's light depth, beta the bias (depth units) of PcfBias.mode:
 *
 *   PN_BIAS_CONSTANT        beta = depth_bias, unclamped (the `shade` window
 *                           contract: depth >= z - depth_bias).
 *   PN_BIAS_SLOPE           beta = clamp(depth_bias + slope_scale * s, low, high),
 *                           s = |dz/du| / W + |dz/dv| / H: the depth change of
 *                           the receiver's plane across one texel (both axes),
 *                           the classic slope-scaled bias written in texels of
 *                           the map rather than pixels of the depth pass.
 *   PN_BIAS_RECEIVER_PLANE  per tap, the depth of the receiver's plane at the
 *                           tap's texel centre (Isidoro, "Receiver plane depth
 *                           bias", GDC 2006):
 *                               z_plane = z + dz/du * du + dz/dv * dv,
 *                           (du, dv) = the texel centre ((tx + 1/2) / W,
 *                           (ty + 1/2) / H) minus the receiver's (u, v); the
 *                           bias is what that subtracts from z, plus the base,
 *                           clamped as Toy Story 3 found necessary (level
 *                           surfaces still need a minimum, grazing ones get a
 *                           huge bias that needs a maximum; Siggraph 2010
 *                           course notes, "Dynamic depth bias"):
 *                               beta = clamp(depth_bias - (dz/du du + dz/dv dv), low, high).
 *
 * The derivatives (planes PN_PCF_PLANE_DZDU, _DZDV of the receivers, depth per
 * unit of texture coordinate, read by kernels/receiver_slope.h) come from the host: finite differences on the
 * receivers' grid or channels of the receivers' file (host/src/receiver_plane.cpp
 * states the discontinuity test). Where they cross a depth discontinuity the
 * plane flag (PN_PCF_PLANE_OK) is 0 and the tap falls back to beta = depth_bias,
 * as Toy Story 3 falls back to a static bias where derivatives cross cascades.
 *
 * Non-finite receiver values flag the row (bad_rows) and are read as 0, so
 * that no lane forms a NaN or an out-of-range index (load_checked_plane,
 * kernels/receiver_slope.h); the host reports the row.
 */
#ifndef PENUMBRA_DEPTH_BIAS_H
#define PENUMBRA_DEPTH_BIAS_H

typedef struct {
    pn_float u, v;          /* texture coordinates, clamped into [0, 1] */
    pn_float z;             /* light depth */
    pn_float dzdu, dzdv;    /* receiver-plane mode: the plane's slopes, else 0 */
    pn_float reference;     /* z - beta for a tap-independent beta (constant, slope, fallback) */
    pn_float threshold;     /* the reference in the map's convention (depth_threshold) */
    pn_mask plane;          /* receiver-plane mode: the derivatives hold here */
} PcfReceiver;

/* The receivers of the strip at (x, y) with the bias each tap will need;
 * `map` is the shadow map's geometry (W, H). z and its slopes are converted
 * from convention `c` (kernels/depth_convention.h): the bias, like every tap
 * the kernels compare, is in normalised linear depth. */
PN_FN PcfReceiver pcf_load_receiver(PN_GLOBAL const float* receivers, pn_dims d, pn_dims map, PcfBias b,
                                    DepthConversion c, int x, int y, PN_GLOBAL int* bad_rows)
{
    PcfReceiver r;
    r.u = pn_clamp(load_checked_plane(receivers, d, 0, x, y, bad_rows), 0.0f, 1.0f);
    r.v = pn_clamp(load_checked_plane(receivers, d, 1, x, y, bad_rows), 0.0f, 1.0f);
    r.z = depth_to_normalized(load_checked_plane(receivers, d, 2, x, y, bad_rows), c);
    r.reference = r.z - b.depth_bias;
    const ReceiverSlope s = b.mode == PN_BIAS_CONSTANT ? no_receiver_slope()
                                                       : load_receiver_slope(receivers, d, x, y, bad_rows);
    const pn_float slope_factor = depth_slope_factor(r.z, c);
    r.dzdu = s.dzdu * slope_factor;
    r.dzdv = s.dzdv * slope_factor;
    r.plane = s.holds;
    if (b.mode == PN_BIAS_SLOPE) {
        const pn_float step = pn_abs(r.dzdu) / (float)map.width + pn_abs(r.dzdv) / (float)map.height;
        const pn_float beta = pn_clamp(b.depth_bias + b.slope_scale * step, b.low, b.high);
        r.reference = pn_select(r.plane, r.z - beta, r.reference);
    }
    r.threshold = depth_threshold(r.reference, c);
    return r;
}

/* The depth a tap at texel (tx, ty) (integers held in floats) must reach to
 * count as lit: depth >= pcf_tap_reference(...). */
PN_FN pn_float pcf_tap_reference(PcfReceiver r, PcfBias b, pn_dims map, pn_float tx, pn_float ty)
{
    if (b.mode != PN_BIAS_RECEIVER_PLANE) return r.reference;
    const pn_float du = (tx + 0.5f) / (float)map.width - r.u;
    const pn_float dv = (ty + 0.5f) / (float)map.height - r.v;
    const pn_float beta = pn_clamp(b.depth_bias - (r.dzdu * du + r.dzdv * dv), b.low, b.high);
    return pn_select(r.plane, r.z - beta, r.reference);
}

/* 1 where the tap is lit, else 0. */
PN_FN pn_float pcf_lit(pn_float depth, pn_float reference)
{
    return pn_select(depth >= reference, 1.0f, 0.0f);
}

/* pcf_lit for a tap of the map's stored depth at texel (tx, ty): the
 * reference moved into the map's convention once per receiver
 * (depth_threshold), or per tap where the receiver's plane moves it; the
 * taps themselves are never converted (measured: docs/integration.md,
 * "Depth conventions"). */
PN_FN pn_float pcf_tap_lit(pn_float stored, PcfReceiver r, PcfBias b, DepthConversion c, pn_dims map, pn_float tx,
                           pn_float ty)
{
    if (b.mode != PN_BIAS_RECEIVER_PLANE) return depth_lit(stored, r.threshold, c);
    return depth_lit(stored, depth_threshold(pcf_tap_reference(r, b, map, tx, ty), c), c);
}

#endif
