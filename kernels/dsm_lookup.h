/* Deep shadow map lookup (Lokovic & Veach, "Deep Shadow Maps", SIGGRAPH 2000,
 * "Lookups"): the filtered visibility of a neighbourhood of deep pixels,
 *     V(u, v, z) = sum_k w_k V_k(z) / sum_k w_k,
 * each pixel's V_k(z) found by a search through its vertices.
 *
 * Inputs: the map's three arrays (penumbra/deep_shadow_map.h: offsets,
 * depths, transmittances; checked on the host), receivers (planes u, v, z:
 * texture coordinates, light depth), DsmParams. Output: one plane, in [0, 1].
 *
 * One pixel, V_k(z - bias): i = the first of its vertices with depth >= z
 * (lower_bound, by bisection or front to back, DsmParams.search); 1 if i is
 * the first vertex (or none), the last t if there is none at or beyond z,
 * else t_{i-1} + (t_i - t_{i-1}) (z - z_{i-1}) / (z_i - z_{i-1}), exactly t_i
 * at z = z_i and clamped into [t_i, t_{i-1}] so that float rounding can neither
 * leave the segment nor make V rise across a vertex. At a step (two vertices
 * at one depth) V is the value before it (a surface does not shadow itself),
 * the convention of penumbra/deep_shadow_map.h.
 *
 * Filters and footprint (u, v clamped into [0, 1]; texel i covers
 * [i, i + 1) / W, its centre at (i + 1/2) / W):
 *   PN_DSM_BOX   the (2r+1)^2 pixels centred on the pixel containing (u, v),
 *                equal weights: the `penumbra shade` window of PCF and VSM,
 *                so that r means the same in every method; r = 0 is the
 *                nearest pixel.
 *   PN_DSM_TENT  the tent of half-width R = r + 1 texels centred on (u, v),
 *                separable, w = (R - |x_i - s|)(R - |y_j - t|) with
 *                (s, t) = (u W - 1/2, v H - 1/2): the (2r+2)^2 pixels it
 *                covers. r = 0 is bilinear interpolation of the four nearest
 *                pixels, the texture filter the paper's lookup compares with.
 * Both clip to the map and divide by the weight inside, so no pixel counts
 * twice at an edge. Weights do not depend on z and are >= 0, so the result is
 * monotone non-increasing in z as each V_k is (float rounding is monotone).
 *
 * Bounds: every index is clamped into the arrays (DsmParams.vertices), so a
 * damaged map cannot make a lane read outside them; a valid one is unchanged.
 * Non-finite receivers flag their row and read as 0 (kernels/depth_bias.h).
 */
#ifndef PENUMBRA_DSM_LOOKUP_H
#define PENUMBRA_DSM_LOOKUP_H

/* Bisection by powers of two: after the step of 2^k every vertex before
 * `pos` lies in front of z. The steps are uniform, from the map's longest
 * pixel down; a step no lane can take costs a compare, not a gather. */
PN_FN pn_int dsm_search_binary(PN_GLOBAL const float* depths, DsmParams p, pn_int begin, pn_int end, pn_float z)
{
    pn_int pos = begin;
    for (int step = p.search_top; step > 0; step = step / 2) {
        const pn_int probe = pos + (step - 1);
        const pn_mask inside = pn_iless(probe, end);
        if (!pn_any(inside)) continue;
        const pn_float d = pn_gather(depths, pn_imin(probe, p.last_vertex));
        pos = pn_iselect(pn_and(inside, d < z), pos + step, pos);
    }
    return pos;
}

/* Front to back: the loop runs while any lane is still in front of z (the
 * lanes' trip counts differ; a lane that is done is masked off). */
PN_FN pn_int dsm_search_linear(PN_GLOBAL const float* depths, DsmParams p, pn_int begin, pn_int end, pn_float z)
{
    pn_int pos = begin;
    pn_mask active = pn_iless(pos, end);
    while (pn_any(active)) {
        const pn_float d = pn_gather(depths, pn_imin(pos, p.last_vertex));
        active = pn_and(active, d < z);
        pos = pn_iselect(active, pos + 1, pos);
        active = pn_and(active, pn_iless(pos, end));
    }
    return pos;
}

/* V(z) of pixel `pixel` (an index in [0, width*height), every lane). */
PN_FN pn_float dsm_pixel_visibility(PN_GLOBAL const uint* offsets, PN_GLOBAL const float* depths,
                                    PN_GLOBAL const float* transmittances, DsmParams p, pn_int pixel, pn_float z)
{
    pn_uint first, second;
    pn_ugather_pair(offsets, pixel, &first, &second);
    const pn_int begin = pn_iclamp(pn_uint_to_index(first), 0, p.vertices);
    const pn_int end = pn_iclamp(pn_uint_to_index(second), begin, p.vertices);
    pn_int i;
    if (p.search == PN_DSM_LINEAR)
        i = dsm_search_linear(depths, p, begin, end, z);
    else
        i = dsm_search_binary(depths, p, begin, end, z);
    const pn_int before = pn_iclamp(i - 1, 0, p.last_vertex), at = pn_imin(i, p.last_vertex);
    const pn_float z0 = pn_gather(depths, before), z1 = pn_gather(depths, at);
    const pn_float t0 = pn_gather(transmittances, before), t1 = pn_gather(transmittances, at);
    /* Lanes between two vertices have z0 < z <= z1; the others discard this. */
    const pn_float along = pn_clamp(t0 + (t1 - t0) * ((z - z0) / (z1 - z0)), t1, t0);
    const pn_float inner = pn_select(z >= z1, t1, along);
    return pn_select(pn_iless(begin, i), pn_select(pn_iless(i, end), inner, t0), 1.0f);
}

/* The tap at texel x on one axis of `size` texels: its weight (0 outside the
 * map) for the filter centred on s (tent) or on the texel of offset 0 (box). */
PN_FN pn_float dsm_axis_weight(DsmParams p, pn_float x, pn_float s, int size)
{
    pn_float w = 1.0f;
    if (p.filter == PN_DSM_TENT) w = (float)(p.radius + 1) - pn_abs(x - s);
    return pn_select(pn_and(x >= 0.0f, x < (float)size), w, 0.0f);
}

/* The texel of tap offset 0 on one axis (texture coordinate c in [0, 1]):
 * box, the texel containing c (clamped); tent, the texel left of c's
 * continuous position s = c size - 1/2. */
PN_FN pn_float dsm_axis_origin(DsmParams p, pn_float c, int size)
{
    if (p.filter == PN_DSM_TENT) return pn_floor(c * (float)size - 0.5f);
    return pn_clamp(pn_floor(c * (float)size), 0.0f, (float)size - 1.0f);
}

PN_KERNEL void dsm_lookup(PN_GLOBAL const uint* offsets, PN_GLOBAL const float* depths,
                          PN_GLOBAL const float* transmittances, PN_GLOBAL const float* receivers,
                          PN_GLOBAL float* out, PN_GLOBAL int* bad_rows, const DsmParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const pn_float u = pn_clamp(pcf_checked_plane(receivers, p.receivers, 0, pn_x, pn_y, bad_rows), 0.0f, 1.0f);
    const pn_float v = pn_clamp(pcf_checked_plane(receivers, p.receivers, 1, pn_x, pn_y, bad_rows), 0.0f, 1.0f);
    const pn_float z = pcf_checked_plane(receivers, p.receivers, 2, pn_x, pn_y, bad_rows) - p.bias;
    const int w = p.map.width, h = p.map.height;
    const pn_float s = u * (float)w - 0.5f, t = v * (float)h - 0.5f;
    const pn_float ox = dsm_axis_origin(p, u, w), oy = dsm_axis_origin(p, v, h);
    const int last = p.filter == PN_DSM_TENT ? p.radius + 1 : p.radius;
    pn_float sum = 0.0f, total = 0.0f;
    for (int dy = -p.radius; dy <= last; ++dy) {
        const pn_float y = oy + (float)dy;
        const pn_float wy = dsm_axis_weight(p, y, t, h);
        const pn_int row = pn_to_int(pn_clamp(y, 0.0f, (float)h - 1.0f)) * w;
        for (int dx = -p.radius; dx <= last; ++dx) {
            const pn_float x = ox + (float)dx;
            const pn_float weight = wy * dsm_axis_weight(p, x, s, w);
            if (!pn_any(weight > 0.0f)) continue;
            const pn_int pixel = row + pn_to_int(pn_clamp(x, 0.0f, (float)w - 1.0f));
            sum = sum + weight * dsm_pixel_visibility(offsets, depths, transmittances, p, pixel, z);
            total = total + weight;
        }
    }
    pn_store(out, p.out, pn_x, pn_y, pn_saturate(sum / total));
}

#endif
