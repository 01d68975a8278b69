/* Percentage-closer filtering over N taps of a disc, rotated per receiver.
 *
 * The pattern is Vogel's spiral (Vogel 1979, the sunflower): tap i of N at
 *     radius R sqrt((i + 1/2) / N),  angle i * gamma + phi,
 * gamma = pi (3 - sqrt 5), the golden angle, R the disc radius in texels.
 * Chosen over a Poisson disc (a stored table per N, no closed form) and
 * Hammersley (rows of taps that line up along the radius for small N): any N
 * is a closed form, the density is uniform over the disc (tap i owns the
 * annulus of area pi R^2 / N), and a rotation is an offset of the angle.
 *
 * Rotation (Toy Story 3, Siggraph 2010 course notes, "Randomized
 * Rotations"): the receiver at pixel (x, y) of the receivers' grid takes
 * phi = 2 pi k / 16 with k from the notes' randomized 4 x 4 tile
 *      4  1  3  7
 *      8 11 15  6
 *     10  2 14  5
 *      0 13 12  9
 * at (x mod 4, y mod 4): 16 patterns that a blur of 4 pixels (penumbra blur)
 * averages into one of 16 N taps. rotate = 0 keeps phi = 0 everywhere (the
 * banding case of the failure figure).
 *
 * A tap reads the texel containing it (clamp-to-edge) and weighs 1 / N; the
 * receiver sits at (u W, v H) in texel space (texel k spans [k, k + 1)). The
 * golden-angle rotation advances in double by one rotation per tap: the
 * float32 offsets stay within 1e-6 texels of the exact pattern.
 */
#ifndef PENUMBRA_PCF_DISC_H
#define PENUMBRA_PCF_DISC_H

typedef struct {
    pn_float c, s; /* cos phi, sin phi */
} DiscRotation;

/* The receiver strip's rotations from Toy Story 3's 4 x 4 tile. */
PN_FN DiscRotation pcf_disc_rotation(pn_float lane_x, int y, int rotate)
{
    const int tile[16] = {4, 1, 3, 7, 8, 11, 15, 6, 10, 2, 14, 5, 0, 13, 12, 9};
    /* cos(2 pi k / 16), k = 0 .. 15; sin(2 pi k / 16) = cos(2 pi (k - 4) / 16). */
    const float cos16[16] = {1.0f, 0.92387953f, 0.70710678f, 0.38268343f, 0.0f, -0.38268343f, -0.70710678f,
                             -0.92387953f, -1.0f, -0.92387953f, -0.70710678f, -0.38268343f, 0.0f, 0.38268343f,
                             0.70710678f, 0.92387953f};
    DiscRotation r;
    r.c = 1.0f;
    r.s = 0.0f;
    if (!rotate) return r;
    const pn_float column = lane_x - 4.0f * pn_floor(lane_x * 0.25f);
    for (int i = 0; i < 4; ++i) {
        const int k = tile[4 * (y & 3) + i];
        const pn_mask here = column == (float)i;
        r.c = pn_select(here, cos16[k], r.c);
        r.s = pn_select(here, cos16[(k + 12) & 15], r.s);
    }
    return r;
}

PN_KERNEL void pcf_disc(PN_GLOBAL const float* depth, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                        PN_GLOBAL int* bad_rows, const PcfParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const PcfReceiver r =
        pcf_load_receiver(receivers, p.receivers, p.depth, p.bias, p.convention, pn_x, pn_y, bad_rows);
    const DiscRotation rot = pcf_disc_rotation(pn_lane_x, pn_y, p.rotate);
    const pn_float px = r.u * (float)p.depth.width, py = r.v * (float)p.depth.height;
    const float w = (float)p.depth.width - 1.0f, h = (float)p.depth.height - 1.0f;
    /* cos, sin of the golden angle pi (3 - sqrt 5). */
    const double golden_c = -0.7373688780783197, golden_s = 0.6754902942615238;
    double tap_c = 1.0, tap_s = 0.0;
    pn_float lit = 0.0f;
    for (int i = 0; i < p.taps; ++i) {
        const pn_float radius = p.disc_radius * pn_sqrt((pn_float)(((float)i + 0.5f) / (float)p.taps));
        const float c = (float)tap_c, s = (float)tap_s;
        const pn_float ox = radius * (rot.c * c - rot.s * s), oy = radius * (rot.s * c + rot.c * s);
        const pn_float tx = pn_clamp(pn_floor(px + ox), 0.0f, w), ty = pn_clamp(pn_floor(py + oy), 0.0f, h);
        const pn_float d = pn_fetch(depth, p.depth, pn_to_int(tx), pn_to_int(ty));
        lit = lit + pcf_tap_lit(d, r, p.bias, p.convention, p.depth, tx, ty);
        const double next_c = tap_c * golden_c - tap_s * golden_s;
        tap_s = tap_s * golden_c + tap_c * golden_s;
        tap_c = next_c;
    }
    pn_store(out, p.out, pn_x, pn_y, lit / (float)p.taps);
}

#endif
