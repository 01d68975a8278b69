/* The cascaded shadow mask of Toy Story 3 (Siggraph 2010 course notes,
 * "Deferred shadow shader steps"): per view pixel, from its world position,
 *   1. cascade selection: the finest cascade whose bounding box holds the
 *      pixel's PCF footprint (Zhang, Zapriagaev and Bentham 2009, "Practical
 *      Cascaded Shadow Maps", the notes' choice), or the first split whose far
 *      view depth lies beyond the pixel (PN_CASCADE_SELECT_SPLIT);
 *   2. the dynamic depth bias: the receiver's plane in the chosen cascade
 *      (Isidoro 2006) from its neighbours' positions, invalidated where a
 *      neighbour lies in another cascade (or is no surface): there a static
 *      bias scaled to the cascade; both clamped to the cascade's [min, max]:
 *          beta = clamp(min - (dz/du du + dz/dv dv), min, max)   plane holds
 *          beta = clamp(static, min, max)                        elsewhere,
 *      (du, dv) the tap's texel centre less the receiver's (u, v): the minimum
 *      is the margin above the plane as well as the floor;
 *   3. the 4x4 Gaussian PCF of kernels/pcf_gauss.h in that cascade's map.
 *
 * Inputs (CascadeParams, kernels/params.h): receivers, PN_CASCADE_PLANES
 * planes (world x, y, z; view depth; surface flag, 1 where the pixel sees a
 * surface); the maps, one plane holding the k cascades stacked (cascade c in
 * rows [c H, (c+1) H), depths in [0, 1]); each cascade's affine light
 * coordinates u = dot(p, axis_u) u_scale[c] + u_offset[c] (and v, z alike).
 * Output plane 0: visibility in [0, 1] (1 where no cascade holds the pixel or
 * it sees no surface); plane 1: the cascade used, -1 for none.
 *
 * Derivatives: the notes take ddx/ddy of the light coordinates; on a grid of
 * receivers that is the difference to the right (or left) and lower (or
 * upper) neighbour, the one of the two with the smaller view-depth step, so
 * that a silhouette's far side is not taken for the plane. Every texel read
 * is clamp-to-edge inside its cascade (pcf_gauss.h's policy).
 */
#ifndef PENUMBRA_CASCADES_H
#define PENUMBRA_CASCADES_H

/* values[c] for each lane's cascade c (0 .. PN_CASCADES_MAX - 1). */
PN_FN pn_float cascade_value(const float* values, pn_float c)
{
    pn_float v = values[0];
    for (int k = 1; k < PN_CASCADES_MAX; ++k) v = pn_select(c == (float)k, values[k], v);
    return v;
}

typedef struct {
    pn_float x, y, z;  /* world position */
    pn_float depth;    /* view depth */
    pn_mask surface;   /* the pixel sees a surface */
} CascadeReceiver;

PN_FN CascadeReceiver load_cascade_receiver(PN_GLOBAL const float* receivers, pn_dims d, int x, int y,
                                            PN_GLOBAL int* bad_rows)
{
    CascadeReceiver r;
    r.x = load_checked_plane(receivers, d, 0, x, y, bad_rows);
    r.y = load_checked_plane(receivers, d, 1, x, y, bad_rows);
    r.z = load_checked_plane(receivers, d, 2, x, y, bad_rows);
    r.depth = load_checked_plane(receivers, d, 3, x, y, bad_rows);
    r.surface = load_checked_plane(receivers, d, 4, x, y, bad_rows) > 0.5f;
    return r;
}

/* The strip at (x, y) clamped to the image (a neighbour), unchecked: the
 * pixel's own row check covers every value of the image once. */
PN_FN CascadeReceiver load_cascade_neighbour(PN_GLOBAL const float* receivers, pn_dims d, int x, int y)
{
    CascadeReceiver r;
    r.x = pn_load_clamped(PN_PLANE(receivers, d, 0), d, x, y);
    r.y = pn_load_clamped(PN_PLANE(receivers, d, 1), d, x, y);
    r.z = pn_load_clamped(PN_PLANE(receivers, d, 2), d, x, y);
    r.depth = pn_load_clamped(PN_PLANE(receivers, d, 3), d, x, y);
    r.surface = pn_load_clamped(PN_PLANE(receivers, d, 4), d, x, y) > 0.5f;
    pn_mask finite = pn_and(pn_and(pn_finite(r.x), pn_finite(r.y)), pn_and(pn_finite(r.z), pn_finite(r.depth)));
    r.surface = pn_and(r.surface, finite);
    return r;
}

typedef struct {
    pn_float u, v, z;
} CascadePoint;

PN_FN pn_float cascade_axis(const float* axis, CascadeReceiver r)
{
    return r.x * axis[0] + r.y * axis[1] + r.z * axis[2];
}

/* The receiver in cascade c's coordinates. */
PN_FN CascadePoint cascade_point(const CascadeParams* p, CascadeReceiver r, pn_float c)
{
    CascadePoint q;
    q.u = cascade_axis(p->axis_u, r) * cascade_value(p->u_scale, c) + cascade_value(p->u_offset, c);
    q.v = cascade_axis(p->axis_v, r) * cascade_value(p->v_scale, c) + cascade_value(p->v_offset, c);
    q.z = cascade_axis(p->axis_z, r) * cascade_value(p->z_scale, c) + cascade_value(p->z_offset, c);
    return q;
}

/* The cascade for each lane, -1 where none holds it. Box: the first c whose
 * [margin, 1 - margin]^2 x [0, 1] holds the point (the margin keeps the PCF
 * footprint inside the map). Split: the first c with depth <= split_far[c]. */
PN_FN pn_float select_cascade(const CascadeParams* p, CascadeReceiver r)
{
    pn_float chosen = -1.0f;
    for (int c = p->cascades - 1; c >= 0; --c) {
        pn_mask holds;
        if (p->select == PN_CASCADE_SELECT_SPLIT) {
            holds = r.depth <= p->split_far[c];
        } else {
            const pn_float cf = (float)c;
            const CascadePoint q = cascade_point(p, r, cf);
            const float lo = p->margin[c], hi = 1.0f - p->margin[c];
            holds = pn_and(pn_and(pn_and(q.u >= lo, q.u <= hi), pn_and(q.v >= lo, q.v <= hi)),
                           pn_and(q.z >= 0.0f, q.z <= 1.0f));
        }
        chosen = pn_select(holds, (float)c, chosen);
    }
    return pn_select(r.surface, chosen, -1.0f);
}

/* One neighbour's step in cascade c's coordinates, and whether it may stand
 * for the receiver's plane (a surface in the same cascade). */
typedef struct {
    pn_float du, dv, dz, step;  /* step: |view depth difference| */
    pn_mask usable;
} CascadeStep;

PN_FN CascadeStep cascade_step(const CascadeParams* p, CascadeReceiver r, CascadePoint q, pn_float c,
                               CascadeReceiver n)
{
    CascadeStep s;
    const CascadePoint m = cascade_point(p, n, c);
    s.du = m.u - q.u;
    s.dv = m.v - q.v;
    s.dz = m.z - q.z;
    s.step = pn_abs(n.depth - r.depth);
    s.usable = pn_and(n.surface, select_cascade(p, n) == c);
    return s;
}

/* Of the two neighbours along one axis, the usable one with the smaller step. */
PN_FN CascadeStep pick_step(CascadeStep forward, CascadeStep backward)
{
    const pn_mask take_back = pn_and(backward.usable, pn_or(pn_not(forward.usable), backward.step < forward.step));
    CascadeStep s;
    s.du = pn_select(take_back, backward.du, forward.du);
    s.dv = pn_select(take_back, backward.dv, forward.dv);
    s.dz = pn_select(take_back, backward.dz, forward.dz);
    s.step = pn_select(take_back, backward.step, forward.step);
    s.usable = pn_or(forward.usable, backward.usable);
    return s;
}

/* The receiver plane dz/du, dz/dv from two steps (Isidoro 2006: invert the
 * 2x2 Jacobian of (u, v) over the two screen axes). */
PN_FN ReceiverSlope cascade_slope(CascadeStep a, CascadeStep b)
{
    const pn_float det = a.du * b.dv - a.dv * b.du;
    const pn_mask solvable = pn_and(pn_and(a.usable, b.usable), pn_abs(det) > 1e-12f);
    const pn_float safe = pn_select(solvable, det, 1.0f);
    ReceiverSlope s;
    s.dzdu = pn_select(solvable, (a.dz * b.dv - b.dz * a.dv) / safe, 0.0f);
    s.dzdv = pn_select(solvable, (a.du * b.dz - b.du * a.dz) / safe, 0.0f);
    s.holds = solvable;
    return s;
}

PN_KERNEL void cascade_mask(PN_GLOBAL const float* maps, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                            PN_GLOBAL int* bad_rows, const CascadeParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const pn_dims rd = p.receivers;
    const CascadeReceiver r = load_cascade_receiver(receivers, rd, pn_x, pn_y, bad_rows);
    const pn_float c = select_cascade(&p, r);
    const pn_mask inside = c >= 0.0f;
    const pn_float cc = pn_max(c, 0.0f);
    const CascadePoint q = cascade_point(&p, r, cc);
    const CascadeStep sx = pick_step(cascade_step(&p, r, q, cc, load_cascade_neighbour(receivers, rd, pn_x + 1, pn_y)),
                                     cascade_step(&p, r, q, cc, load_cascade_neighbour(receivers, rd, pn_x - 1, pn_y)));
    const CascadeStep sy = pick_step(cascade_step(&p, r, q, cc, load_cascade_neighbour(receivers, rd, pn_x, pn_y + 1)),
                                     cascade_step(&p, r, q, cc, load_cascade_neighbour(receivers, rd, pn_x, pn_y - 1)));
    const ReceiverSlope plane = cascade_slope(sx, sy);
    const pn_float low = cascade_value(p.bias_min, cc), high = cascade_value(p.bias_max, cc);
    const pn_float fallback = pn_clamp(cascade_value(p.static_bias, cc), low, high);

    /* 4x4 Gaussian PCF (kernels/pcf_gauss.h's footprint and weights) in cascade cc. */
    const int n = p.grid;
    pn_float g[PN_PCF_MAX_GRID], wx[PN_PCF_MAX_GRID + 1], wy[PN_PCF_MAX_GRID + 1];
    pcf_gauss_taps(n, p.sigma, g);
    const float first = -0.5f - 0.5f * (float)(n - 1);
    const float W = (float)p.maps.width, H = (float)p.map_height;
    const pn_float u = pn_clamp(q.u, 0.0f, 1.0f), v = pn_clamp(q.v, 0.0f, 1.0f);
    const pn_float fx = u * W + first, fy = v * H + first;
    const pn_float x0 = pn_floor(fx), y0 = pn_floor(fy);
    pcf_gauss_axis_weights(g, n, fx - x0, wx);
    pcf_gauss_axis_weights(g, n, fy - y0, wy);
    const pn_float row0 = cc * H;
    pn_float visibility = 0.0f;
    for (int l = 0; l <= n; ++l) {
        const pn_float ty = pn_clamp(y0 + (float)l, 0.0f, H - 1.0f);
        const pn_float dv = (ty + 0.5f) / H - v;
        pn_float row = 0.0f;
        for (int k = 0; k <= n; ++k) {
            const pn_float tx = pn_clamp(x0 + (float)k, 0.0f, W - 1.0f);
            const pn_float du = (tx + 0.5f) / W - u;
            /* The tap's depth on the receiver's plane, less the minimum (a tap on
             * the plane itself would otherwise be decided by rounding). */
            const pn_float dynamic = pn_clamp(low - (plane.dzdu * du + plane.dzdv * dv), low, high);
            const pn_float reference = q.z - pn_select(plane.holds, dynamic, fallback);
            const pn_float d = pn_fetch(maps, p.maps, pn_to_int(tx), pn_to_int(row0 + ty));
            row = row + wx[k] * pcf_lit(d, reference);
        }
        visibility = visibility + wy[l] * row;
    }
    visibility = pn_select(inside, pn_clamp(visibility, 0.0f, 1.0f), 1.0f);
    pn_store(out, p.out, pn_x, pn_y, visibility);
    pn_store(PN_PLANE(out, p.out, 1), p.out, pn_x, pn_y, c);
}

#endif
