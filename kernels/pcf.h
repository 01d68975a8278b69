/* Percentage-closer filtering with a box window (Reeves, Salesin & Cook,
 * "Rendering antialiased shadows with depth maps", Siggraph 1987).
 *
 * Per receiver (u, v, z): the window is the (2r+1) x (2r+1) block of texels
 * centred on the texel containing (u, v) (u, v clamped into the map), clipped
 * to the map: the `penumbra shade` window contract, the same block as
 * kernels/box_window.h's texel_window. The visibility is the fraction of the
 * window's texels that are lit (kernels/depth_bias.h: depth >= z - beta),
 * in [0, 1]; every texel weighs the same. Inputs: the shadow map, one plane
 * of depths; receivers per PcfParams. Output: one plane of visibility.
 *
 * Two paths with one result: a strip whose windows all lie inside the map
 * reads its taps at uniform offsets from each lane's window origin (no
 * clamping, no edge masks); a strip touching an edge masks the taps outside
 * the map and divides by the clipped window's area.
 */
#ifndef PENUMBRA_PCF_H
#define PENUMBRA_PCF_H

/* The texel containing the receiver, as floats (exact integers), clamped. */
PN_FN pn_float pcf_texel(pn_float t, int size)
{
    return pn_clamp(pn_floor(t * (float)size), 0.0f, (float)size - 1.0f);
}

/* What a tap adds: 1 when lit (pcf), or its depth (pcf_gather, the
 * benchmark's gather limit: the same fetches with no comparison). */
PN_FN pn_float pcf_box_tap(pn_float d, PcfParams p, PcfReceiver r, pn_float x, pn_float y, int compare)
{
    return compare ? pcf_tap_lit(d, r, p.bias, p.convention, p.depth, x, y) : d;
}

/* Lit taps of windows that lie inside the map. */
PN_FN pn_float pcf_box_inside(PN_GLOBAL const float* depth, PcfParams p, PcfReceiver r, pn_float tx, pn_float ty,
                              int compare)
{
    const int radius = p.radius;
    const pn_int origin = pn_to_int(ty) * p.depth.pitch + pn_to_int(tx);
    pn_float lit = 0.0f;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            const pn_float d = pn_gather(depth, origin + (dy * p.depth.pitch + dx));
            lit = lit + pcf_box_tap(d, p, r, tx + (float)dx, ty + (float)dy, compare);
        }
    return lit;
}

/* Lit taps of windows clipped by the map's edges. */
PN_FN pn_float pcf_box_clipped(PN_GLOBAL const float* depth, PcfParams p, PcfReceiver r, pn_float tx, pn_float ty,
                               int compare)
{
    const int radius = p.radius;
    const float w = (float)p.depth.width, h = (float)p.depth.height;
    const pn_int ix = pn_to_int(tx), iy = pn_to_int(ty);
    pn_float lit = 0.0f;
    for (int dy = -radius; dy <= radius; ++dy) {
        const pn_float y = ty + (float)dy;
        const pn_mask row_inside = pn_and(y >= 0.0f, y < h);
        for (int dx = -radius; dx <= radius; ++dx) {
            const pn_float x = tx + (float)dx;
            const pn_mask inside = pn_and(row_inside, pn_and(x >= 0.0f, x < w));
            const pn_float d = pn_fetch(depth, p.depth, ix + dx, iy + dy);
            const pn_float hit = pcf_box_tap(d, p, r, x, y, compare);
            lit = lit + pn_select(inside, hit, 0.0f);
        }
    }
    return lit;
}

/* The box filter's result: the mean of pcf_box_tap over the clipped window. */
PN_FN void pcf_box(PN_GLOBAL const float* depth, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                   PN_GLOBAL int* bad_rows, PcfParams p, int x, int y, int compare)
{
    const PcfReceiver r = pcf_load_receiver(receivers, p.receivers, p.depth, p.bias, p.convention, x, y, bad_rows);
    const pn_float tx = pcf_texel(r.u, p.depth.width), ty = pcf_texel(r.v, p.depth.height);
    const float radius = (float)p.radius, w = (float)p.depth.width, h = (float)p.depth.height;
    const pn_float x0 = pn_max(tx - radius, 0.0f), x1 = pn_min(tx + radius + 1.0f, w);
    const pn_float y0 = pn_max(ty - radius, 0.0f), y1 = pn_min(ty + radius + 1.0f, h);
    const pn_float area = (x1 - x0) * (y1 - y0);
    /* Every lane's window unclipped: its area is the full (2r+1)^2. */
    const pn_mask inside = (area == (2.0f * radius + 1.0f) * (2.0f * radius + 1.0f));
    const pn_float sum = pn_all(inside) ? pcf_box_inside(depth, p, r, tx, ty, compare)
                                        : pcf_box_clipped(depth, p, r, tx, ty, compare);
    pn_store(out, p.out, x, y, sum / area);
}

PN_KERNEL void pcf(PN_GLOBAL const float* depth, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                   PN_GLOBAL int* bad_rows, const PcfParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    pcf_box(depth, receivers, out, bad_rows, p, pn_x, pn_y, 1);
}

/* Not a shading method: the window's mean depth, the same gathers as pcf
 * without the comparison, so that bench/ can state pcf's taps/s as a share
 * of the gather limit it measures in the same run. */
PN_KERNEL void pcf_gather(PN_GLOBAL const float* depth, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                          PN_GLOBAL int* bad_rows, const PcfParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    pcf_box(depth, receivers, out, bad_rows, p, pn_x, pn_y, 0);
}

#endif
