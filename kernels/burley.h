/* Single-map soft shadows with the bias cone (Burley, "Shadow Map Bias Cone
 * and Improved Soft Shadows", Walt Disney Feature Animation; sections 2-3).
 *
 * Per receiver (u, v, z), u and v clamped into [0, 1], at the continuous
 * texel position (u W, v H); radii in texture units:
 *  - The bias cone (section 2): a tap at distance r from the centre is
 *    compared at z - base_bias - bias_slope * r (base_bias: the family's
 *    bias, kernels/depth_bias.h, whose constant mode is Burley's), so the taps lie on a cone
 *    whose tip (bias base_bias, near 0) is the receiver and which opens
 *    towards the light; a tilted receiver does not cut through it unless its
 *    depth changes faster than the slope per texture unit (2.0 by default,
 *    the paper's). The slope is bias_slope + bias_slope_per_depth * z (z
 *    clamped into [0, 1]): a texture unit's world width grows with depth
 *    under a perspective light, so a slope in world units (the paper's
 *    shadow space: depth per lateral distance) is affine in z here
 *    (penumbra/soft_pcf.h, world_cone). The paper writes p.z + bias with its
 *    depths growing towards the light; here z grows away from it (lit where
 *    depth >= the comparison depth, as in pcf), so the cone subtracts.
 *  - Depth pass (sampleDepth, note 4): blocker_samples Hammersley taps with
 *    radius y times max_radius R (concentrated at the centre); each blocking
 *    tap weighs 1 - 0.9 r / R (linear falloff: near, central occluders win
 *    over far ones, section 3.1); z_b = sum(weight depth) / sum(weight).
 *    No blocking tap: fully lit (the paper tests sz > 0; a blocker at depth
 *    exactly 0 counts here).
 *  - Filter radius min_radius + (max_radius - min_radius) (1 - z_b / z).
 *  - Blur pass (sampleBlur, note 3): filter_samples taps of uniform density
 *    (radius sqrt(y)) on the cone; occlusion = the fraction blocked.
 *  - Opacity falloff (section 3.3), optional: with falloff > 0 the shadow's
 *    opacity is clamp(1 - (z - z_b) / falloff, 0, 1), fading shadows whose
 *    occluder is far; visibility = 1 - occlusion * opacity.
 * Output: visibility in [0, 1]. Cost: blocker_samples + filter_samples
 * fetches, blocker_samples alone where no receiver of a strip finds a
 * blocker (as kernels/pcss.h). Keep in sync with tests/support/soft_pcf_reference.cpp. The map
 * is read through a DirectMap, as in kernels/pcss.h.
 */
#ifndef PENUMBRA_BURLEY_H
#define PENUMBRA_BURLEY_H

/* The cone's slope at this receiver, depth per texture unit. */
PN_FN pn_float burley_cone_slope(const SoftPcfParams p, PcfReceiver r)
{
    return p.bias_slope + p.bias_slope_per_depth * pn_clamp(r.z, 0.0f, 1.0f);
}

/* sampleDepth: the cone-weighted mean depth of the blocking taps, the taps
 * concentrated at the centre (radius y), each compared on the cone and
 * weighted 1 - 0.9 r / R (r / R = y). */
PN_FN pn_float burley_blocker_depth(PN_GLOBAL const float* depth, const SoftPcfParams p, DirectMap held,
                                    PcfReceiver r, pn_float cone_slope, pn_mask* found)
{
    return hammersley_blocker_depth(depth, p.depth, held, p.bias, r, p.max_radius, p.blocker_samples, 0, cone_slope,
                                    0.9f, found);
}

/* Section 3.3: the shadow fades as its occluder gets farther. */
PN_FN pn_float burley_opacity(const SoftPcfParams p, pn_float z, pn_float z_blocker)
{
    if (!(p.falloff > 0.0f)) return 1.0f;
    return pn_clamp(1.0f - (z - z_blocker) / p.falloff, 0.0f, 1.0f);
}

PN_KERNEL void burley(PN_GLOBAL const float* depth, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                      PN_GLOBAL int* bad_rows, const SoftPcfParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const PcfReceiver r =
        pcf_load_receiver(receivers, p.receivers, p.depth, p.bias, p.convention, pn_x, pn_y, bad_rows);
    const DirectMap held = direct_map(p.direct, p.depth, p.convention);
    const pn_float cone_slope = burley_cone_slope(p, r);
    pn_mask found;
    const pn_float z_blocker = burley_blocker_depth(depth, p, held, r, cone_slope, &found);
    if (!pn_any(found)) { /* no blocker in any lane: lit, the filter's answer unused */
        pn_store(out, p.out, pn_x, pn_y, 1.0f);
        return;
    }
    /* found implies z > z_blocker >= 0 for a valid map; the floor keeps the
     * lanes without a blocker (whose result is discarded) finite. */
    const pn_float radius =
        p.min_radius + (p.max_radius - p.min_radius) * (1.0f - z_blocker / pn_max(r.z, 1e-30f));
    /* At most max_radius (and a rounding) for z_b <= z, so inside the band
     * in practice; a blocker beyond the receiver (a negative bias) may
     * widen it. */
    if (hammersley_disc_leaves_band(held, p.depth, r, radius, pn_and(found, pn_active))) {
        hammersley_store_rerun(out, p.out, pn_x, pn_y);
        return;
    }
    const pn_float occlusion =
        1.0f - hammersley_disc_visibility(depth, p.depth, held, p.bias, r, radius, p.filter_samples, cone_slope);
    const pn_float visibility = 1.0f - occlusion * burley_opacity(p, r.z, z_blocker);
    pn_store(out, p.out, pn_x, pn_y, pn_select(found, visibility, 1.0f));
}

#endif
