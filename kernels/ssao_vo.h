/* Volumetric obscurance with line integrals, paired samples (Loos & Sloan,
 * "Volumetric Obscurance", I3D 2010, as Hall's Toy Story 3 notes describe
 * it: Siggraph 2010 course, "SSAO"; docs/ssao.md).
 *
 * Per pixel of view depth z (distance along the view axis, world units), the
 * obscurance o is the fraction of a sphere of radius R around the pixel's
 * point that lies behind the depth buffer (inside solid geometry, read as a
 * height field). The sphere is cut into lines parallel to the view axis
 * through the points (x, y) of its unit disc; a line of unit half length
 * h = sqrt(1 - x^2 - y^2) spans the depths z -+ R h, and the depth z_s seen
 * through it hides the part behind z_s:
 *     occluded fraction f = saturate((z - z_s) / (2 R h) + 1/2),
 * which is 1/2 on a plane facing the camera (the method's definition of
 * "unoccluded" is o = 1/2). The estimate is the sum of the samples' f
 * weighted by the sphere volume each one's line stands for (host: the
 * Voronoi cells of the pattern, penumbra/ssao.h), starting from the centre
 * pixel's half-occluded line, so o = 1/2 + sum_j w_j (e_j1 + e_j2), with
 * e = f - 1/2 the deviation each sample brings (a sum of zeros on a flat
 * plane: exactly 1/2).
 *
 * The screen radius is R f_px / z pixels (f_px the focal length in pixels:
 * the radius shrinks with 1/depth), capped at max_pixels (the notes' 0.07 of
 * the screen); a capped radius means a smaller sphere, R' = r_px z / f_px,
 * which also scales the line lengths. Offsets are in pixels of one size on
 * both axes: the notes' division of x by the aspect ratio, which works in
 * texture coordinates, is this. Fetches: the nearest pixel, rounded
 * symmetrically (half away from zero), so a pair's two taps mirror exactly
 * through the centre pixel.
 *
 * Paired samples: each pattern point (x, y) has its mirror (-x, -y). A
 * sample is usable by u in [0, 1]: 0 off screen; for an occluder nearer than
 * the centre by d = z - z_s, u = 1 up to d = R' (inside the sphere) falling
 * linearly to 0 at d = falloff R', so far occluders do not occlude (the
 * notes' distance modifier, started at the sphere's front instead of at the
 * centre so that occluders inside the sphere count whole). An unusable
 * share 1 - u takes, by `unusable`:
 *   PN_SSAO_PAIRED       its partner's inverse 1 - f (a flat surface through
 *                        the centre gives f1 + f2 = 1), weighted by the
 *                        partner's own u, else 1/2: the notes' shader;
 *   PN_SSAO_ZERO         0 (unoccluded: the halo at silhouettes);
 *   PN_SSAO_HALF         1/2;
 *   PN_SSAO_RENORMALISE  nothing: the weights of the usable shares are
 *                        renormalised (the centre's included).
 * Rotation: with `rotate`, the pattern turns per pixel by the angle of the
 * 4x4 tile at (x mod 4, y mod 4): cosine and sine pairs after the pattern.
 *
 * Source (one float array, host/src/ssao.cpp packs it): per pair j, x, y, h,
 * w (4 floats); then 16 (cos, sin) pairs, row-major over the tile.
 * Input: one plane of view depths; 0 means no surface (o = 0 there, and a
 * sample seeing it reads an infinitely far depth: open). Rows holding a
 * negative or non-finite depth are flagged in bad_rows. Output: o in [0, 1],
 * or, with `accessibility`, the notes' remap to an AO term
 * 1 - saturate(2 o - 1) (1 unoccluded, as the AO truth).
 */
#ifndef PENUMBRA_SSAO_VO_H
#define PENUMBRA_SSAO_VO_H

/* A sample reading no surface (depth 0) sees this far. */
#define PN_SSAO_FAR 1e30f

/* Half away from zero, so that v and -v round to opposite integers. */
PN_FN pn_float ssao_round_symmetric(pn_float v)
{
    const pn_float r = pn_floor(pn_abs(v) + 0.5f);
    return pn_select(v < 0.0f, -r, r);
}

/* One tap at the centre plus (ox, oy) pixels: its depth difference d = z - z_s
 * and usability u (before the distance falloff: on screen or not). */
typedef struct {
    pn_float difference;
    pn_float usable;
} SsaoTap;

PN_FN SsaoTap ssao_tap(PN_GLOBAL const float* depth, pn_dims d, pn_float cx, float cy, pn_float z, pn_float ox,
                       pn_float oy)
{
    const pn_float tx = cx + ox, ty = cy + oy;
    const pn_mask on_screen = pn_and(pn_and(tx >= 0.0f, tx < (float)d.width), pn_and(ty >= 0.0f, ty < (float)d.height));
    const pn_float zs = pn_fetch(depth, d, pn_to_int(pn_max(tx, 0.0f)), pn_to_int(pn_max(ty, 0.0f)));
    SsaoTap t;
    t.difference = z - pn_select(zs > 0.0f, zs, PN_SSAO_FAR);
    t.usable = pn_select(on_screen, 1.0f, 0.0f);
    return t;
}

/* u times the distance falloff: 1 up to d = R', 0 from d = falloff R'. */
PN_FN pn_float ssao_usable(SsaoTap t, pn_float sphere, float falloff)
{
    return t.usable * pn_saturate((falloff * sphere - t.difference) / ((falloff - 1.0f) * sphere));
}

/* The deviation e = f - 1/2 of a line of half length `half_length` (world units). */
PN_FN pn_float ssao_deviation(SsaoTap t, pn_float half_length)
{
    return pn_clamp(t.difference / (2.0f * half_length), -0.5f, 0.5f);
}

/* The deviation of a sample whose usable share is u, its partner's being
 * (e2, u2), by the unusable-sample rule. */
PN_FN pn_float ssao_estimate(int rule, pn_float e, pn_float u, pn_float e2, pn_float u2)
{
    if (rule == PN_SSAO_PAIRED) return u * e - (1.0f - u) * u2 * e2;
    if (rule == PN_SSAO_ZERO) return u * (e + 0.5f) - 0.5f;
    return u * e; /* PN_SSAO_HALF, and RENORMALISE's usable share */
}

/* The obscurance o at the strip whose depth is z (> 0). */
PN_FN pn_float ssao_obscurance(PN_GLOBAL const float* pattern, PN_GLOBAL const float* depth, const SsaoParams p,
                               pn_float cx, int y, pn_float z)
{
    const pn_float pixels = pn_min(p.radius * p.focal / z, p.max_pixels);
    /* Floored so that a subnormal depth cannot make a line of length 0 (0 / 0). */
    const pn_float sphere = pn_max(pixels * z / p.focal, 1e-30f);
    pn_float c = 1.0f, s = 0.0f;
    if (p.rotate) {
        const pn_float column = cx - 4.0f * pn_floor(cx * 0.25f);
        const pn_int entry = pn_to_int(2.0f * (column + (float)(4 * (y & 3))) + (float)(4 * p.pairs));
        c = pn_gather(pattern, entry);
        s = pn_gather(pattern, entry + 1);
    }
    pn_float sum = 0.0f, weight = p.centre_weight;
    for (int j = 0; j < p.pairs; ++j) {
        PN_GLOBAL const float* q = pattern + 4 * j;
        const pn_float ox = ssao_round_symmetric((c * q[0] - s * q[1]) * pixels);
        const pn_float oy = ssao_round_symmetric((s * q[0] + c * q[1]) * pixels);
        const SsaoTap t1 = ssao_tap(depth, p.depth, cx, (float)y, z, ox, oy);
        const SsaoTap t2 = ssao_tap(depth, p.depth, cx, (float)y, z, -ox, -oy);
        const pn_float half_length = sphere * q[2];
        const pn_float u1 = ssao_usable(t1, sphere, p.falloff), u2 = ssao_usable(t2, sphere, p.falloff);
        const pn_float e1 = ssao_deviation(t1, half_length), e2 = ssao_deviation(t2, half_length);
        sum = sum + q[3] * (ssao_estimate(p.unusable, e1, u1, e2, u2) + ssao_estimate(p.unusable, e2, u2, e1, u1));
        weight = weight + q[3] * (u1 + u2);
    }
    if (p.unusable == PN_SSAO_RENORMALISE) return 0.5f + sum / weight;
    return 0.5f + sum;
}

PN_KERNEL void ssao_vo(PN_GLOBAL const float* pattern, PN_GLOBAL const float* depth, PN_GLOBAL float* out,
                       PN_GLOBAL int* bad_rows, const SsaoParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const pn_float z = pn_load(depth, p.depth, pn_x, pn_y);
    pn_flag_any(bad_rows, pn_y, pn_and(pn_active, pn_not(pn_and(pn_finite(z), z >= 0.0f))));
    const pn_mask surface = pn_and(pn_finite(z), z > 0.0f);
    const pn_float o = ssao_obscurance(pattern, depth, p, pn_lane_x, pn_y, pn_select(surface, z, 1.0f));
    const pn_float value = pn_select(surface, pn_saturate(o), 0.0f);
    pn_store(out, p.out, pn_x, pn_y, p.accessibility ? 1.0f - pn_saturate(2.0f * value - 1.0f) : value);
}

#endif
