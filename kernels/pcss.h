/* Percentage-closer soft shadows (Fernando 2005, "Percentage-Closer Soft
 * Shadows", SIGGRAPH sketch; the real-time shadow notes' three steps).
 *
 * Per receiver (u, v, z), u and v clamped into [0, 1], at the continuous
 * texel position (u W, v H), with light_size L in texture units (the scene's
 * light_size, docs/reference.md):
 *  1. Blocker search over the disc of diameter L: Fernando's search width
 *     L (z - near) / z, with the estimate's light and near plane both at
 *     z = 0 (the model w = L (z - z_b) / z_b measures depths from there), is
 *     L for every receiver; the same window VSSM searches (kernels/vssm.h).
 *     A tap blocks when its depth < z - beta (beta: the family's bias,
 *     kernels/depth_bias.h, at the texel it reads); z_b is the plain mean of
 *     the blocking taps' depths. No blocking tap: fully lit (1).
 *  2. Penumbra width w = L (z - z_b) / z_b (texture units), z_b floored at
 *     1e-4 z (a blocker at the light's plane would give an infinite width).
 *  3. PCF over the disc of diameter w: the fraction of taps with depth
 *     >= z - beta. The width is used as computed, not rounded to whole
 *     texels: the taps sit at fractional offsets and each reads the texel
 *     that contains it.
 * Both passes use the Hammersley disc with uniform density
 * (kernels/hammersley.h), blocker_samples and filter_samples taps; tap 0 is
 * the receiver's own texel, so L = 0 is a hard shadow equal to pcf r=0.
 * Taps outside the map read the nearest edge texel (clamp to edge).
 * Output: visibility in [0, 1]. Cost: blocker_samples + filter_samples
 * fetches per receiver, blocker_samples alone where no receiver of a strip
 * (an OpenCL work-item) finds a blocker (docs/soft_pcf.md). Keep in sync with tests/support/soft_pcf_reference.cpp.
 * The map is read through a DirectMap (kernels/params.h): on the CPU a band
 * of rows converted once; a strip whose filter discs outgrow the band is
 * left to the schedule (hammersley_disc_leaves_band).
 */
#ifndef PENUMBRA_PCSS_H
#define PENUMBRA_PCSS_H

#define PN_PCSS_MIN_OCCLUDER 1e-4f /* z_b floor, as a fraction of z */

/* Step 1: the plain mean depth of the blocking taps; `found` marks lanes with one. */
PN_FN pn_float pcss_blocker_depth(PN_GLOBAL const float* depth, const SoftPcfParams p, DirectMap held, PcfReceiver r,
                                  pn_mask* found)
{
    return hammersley_blocker_depth(depth, p.depth, held, p.bias, r, 0.5f * p.light_size, p.blocker_samples, 1, 0.0f,
                                    0.0f, found);
}

/* Step 2: the filter disc's radius, w / 2, in texture units. */
PN_FN pn_float pcss_filter_radius(const SoftPcfParams p, pn_float z, pn_float z_blocker)
{
    const pn_float occluder = pn_max(z_blocker, z * PN_PCSS_MIN_OCCLUDER);
    return 0.5f * p.light_size * (z - occluder) / occluder;
}

PN_KERNEL void pcss(PN_GLOBAL const float* depth, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                    PN_GLOBAL int* bad_rows, const SoftPcfParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const PcfReceiver r =
        pcf_load_receiver(receivers, p.receivers, p.depth, p.bias, p.convention, pn_x, pn_y, bad_rows);
    const DirectMap held = direct_map(p.direct, p.depth, p.convention);
    pn_mask found;
    const pn_float z_blocker = pcss_blocker_depth(depth, p, held, r, &found);
    if (!pn_any(found)) { /* no blocker in any lane: lit, the filter's answer unused */
        pn_store(out, p.out, pn_x, pn_y, 1.0f);
        return;
    }
    const pn_float radius = pcss_filter_radius(p, r.z, z_blocker);
    if (hammersley_disc_leaves_band(held, p.depth, r, radius, pn_and(found, pn_active))) {
        hammersley_store_rerun(out, p.out, pn_x, pn_y);
        return;
    }
    const pn_float visibility =
        hammersley_disc_visibility(depth, p.depth, held, p.bias, r, radius, p.filter_samples, 0.0f);
    pn_store(out, p.out, pn_x, pn_y, pn_select(found, visibility, 1.0f));
}

#endif
