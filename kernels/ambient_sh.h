/* Irradiance from an ambient light rig in spherical harmonics (Ramamoorthi &
 * Hanrahan, "An Efficient Representation for Irradiance Environment Maps",
 * Siggraph 2001; used for Toy Story 3's ambient rigs, Hall, Siggraph 2010).
 *
 * The host projects a rig of directional lights onto the real SH basis to
 * order 2 and convolves it with the clamped cosine (host/src/ambient_rig.cpp);
 * what reaches the kernel is, per colour channel, the nine weights w_i of the
 * polynomial basis b(n) = (1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2), the
 * SH normalisation constants folded in, so that the irradiance is
 *
 *   E(n) = sum_i w_i b_i(n),     n the unit normal
 *
 * (order 1: the first four terms; the rest of the weights are 0 and skipped).
 * With a dark rig, E = (1 - f) E_light(n) + f E_dark(n), so f = 0 gives the
 * light rig and f = 1 the dark one exactly; the factor f comes from a
 * receiver plane (an ambient buffer made elsewhere) or from the ambient
 * volumes at the pixel's world position (kernels/ambient_volumes.h). The
 * notes' cheaper variant evaluates only the first 4 dark weights
 * (dark_terms = 4).
 *
 * Inputs: receiver planes 0..2 the normal (any length > 0; normalised here),
 * the factor at factor_plane or the position at position_plane .. + 2.
 * Output: planes R, G, B of irradiance (the rig's units). Boundary policy: a
 * normal that is zero or not finite, a position or factor that is not finite,
 * or a factor outside [0, 1] flags its row in bad_rows and writes 0; the host
 * reports it (or, asked to, leaves zero normals black).
 */
#ifndef PENUMBRA_AMBIENT_SH_H
#define PENUMBRA_AMBIENT_SH_H

typedef struct {
    pn_float b[PN_SH_TERMS];
} AmbientBasis;

/* The polynomial basis at the unit normal n (see the header). */
PN_FN AmbientBasis ambient_basis(AmbientLanes3 n)
{
    AmbientBasis s;
    s.b[0] = 1.0f;
    s.b[1] = n.y;
    s.b[2] = n.z;
    s.b[3] = n.x;
    s.b[4] = n.x * n.y;
    s.b[5] = n.y * n.z;
    s.b[6] = 3.0f * n.z * n.z - 1.0f;
    s.b[7] = n.x * n.z;
    s.b[8] = n.x * n.x - n.y * n.y;
    return s;
}

/* sum of the first `terms` weights of channel c times the basis. */
PN_FN pn_float ambient_eval(const float* weights, int c, int terms, AmbientBasis s)
{
    pn_float e = 0.0f;
    for (int i = 0; i < terms; ++i) e = e + weights[c * PN_SH_TERMS + i] * s.b[i];
    return e;
}

/* The blend factor per AmbientParams.blend (0 for PN_AMBIENT_LIGHT_ONLY). */
PN_FN pn_float ambient_factor(PN_GLOBAL const float* volumes, PN_GLOBAL const float* receivers, const AmbientParams p,
                              int x, int y, pn_mask active, PN_GLOBAL int* bad_rows)
{
    if (p.blend == PN_AMBIENT_BLEND_VOLUMES) {
        const AmbientLanes3 pos = ambient_load_position(receivers, p.receivers, p.position_plane, x, y, active, bad_rows);
        return ambient_volumes_factor(volumes, p.volume_count, pos);
    }
    if (p.blend != PN_AMBIENT_BLEND_PLANE) return 0.0f;
    const pn_float f = ambient_checked_plane(receivers, p.receivers, p.factor_plane, x, y, active, bad_rows);
    const pn_mask in_range = pn_and(f >= 0.0f, f <= 1.0f);
    pn_flag_any(bad_rows, y, pn_and(active, pn_not(in_range)));
    return pn_select(in_range, f, 0.0f);
}

PN_KERNEL void ambient_sh(PN_GLOBAL const float* volumes, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                          PN_GLOBAL int* bad_rows, const AmbientParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const AmbientLanes3 raw = ambient_load_position(receivers, p.receivers, 0, pn_x, pn_y, pn_active, bad_rows);
    const pn_float length2 = raw.x * raw.x + raw.y * raw.y + raw.z * raw.z;
    const pn_mask usable = length2 > 0.0f;
    pn_flag_any(bad_rows, pn_y, pn_and(pn_active, pn_not(usable)));
    const pn_float inv = 1.0f / pn_sqrt(pn_select(usable, length2, 1.0f));
    AmbientLanes3 n;
    n.x = raw.x * inv;
    n.y = raw.y * inv;
    n.z = raw.z * inv;
    const AmbientBasis s = ambient_basis(n);
    const pn_float f = ambient_factor(volumes, receivers, p, pn_x, pn_y, pn_active, bad_rows);
    for (int c = 0; c < 3; ++c) {
        pn_float e = ambient_eval(p.light, c, p.light_terms, s);
        if (p.blend != PN_AMBIENT_LIGHT_ONLY) e = (1.0f - f) * e + f * ambient_eval(p.dark, c, p.dark_terms, s);
        pn_store(PN_PLANE(out, p.out, c), p.out, pn_x, pn_y, pn_select(usable, e, 0.0f));
    }
}

#endif
