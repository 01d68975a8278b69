/* Ambient volumes: the per-pixel blend factor between a light and a dark
 * ambient rig (Hall, "Toy Story 3: The Video Game Rendering Techniques",
 * Siggraph 2010 course, section "Ambient Lighting": the ambient buffer).
 *
 * Each volume is a sphere or a box, rotated and scaled, given by its centre c
 * and the matrix M that takes a world offset to the volume's unit shape
 * (rows: the volume's local axes divided by its half size times the scale
 * bias; host/src/ambient_volumes.cpp packs them). Per pixel, for the world
 * position P:
 *
 *   q = M (P - c)                       the offset in the unit shape
 *   sphere:  d = |q|
 *   box:     d = |s(q)| inside the cube (max |q_i| <= 1), else outside,
 *            s the cube-to-sphere map (Nowell 2006, quoted in the notes):
 *            s_x = q_x sqrt(1 - q_y^2/2 - q_z^2/2 + q_y^2 q_z^2/3), and so on,
 *            which takes the cube's surface onto the unit sphere, so that a
 *            box falls off smoothly towards its faces and corners
 *   factor:  f = clamp((1 - d) / (1 - delay), 0, 1)
 *
 * The scale bias (the notes' "sphere scale bias", about 1.05) enlarges the
 * shape before the falloff; `delay` in [0, 1) is the notes' "modified falloff
 * curve": f stays 1 out to d = delay, then falls linearly to 0 at d = 1.
 * Overlapping volumes combine by their maximum (the notes' BlendOp = MAX,
 * SrcBlend = DestBlend = ONE), so a pixel is as dark as its darkest volume
 * and the order of the volumes does not matter. No volume: 0 (the light rig).
 *
 * Records (PN_AMBIENT_VOLUME_FLOATS floats each): kind (PN_AMBIENT_SPHERE or
 * PN_AMBIENT_BOX), c (3), M row-major (9), delay, 1 / (1 - delay), unused.
 * Positions in world units; the factor is unitless in [0, 1]. Rows holding a
 * non-finite position are flagged in bad_rows (the factor there is 0).
 */
#ifndef PENUMBRA_AMBIENT_VOLUMES_H
#define PENUMBRA_AMBIENT_VOLUMES_H

typedef struct {
    pn_float x, y, z;
} AmbientLanes3;

/* One row of M times the offset. */
PN_FN pn_float ambient_row(PN_GLOBAL const float* m, AmbientLanes3 o)
{
    return m[0] * o.x + m[1] * o.y + m[2] * o.z;
}

/* The cube-to-sphere map's stretch of one axis, from the other two squared. */
PN_FN pn_float ambient_cube_stretch(pn_float a2, pn_float b2)
{
    return pn_sqrt(pn_max(1.0f - 0.5f * a2 - 0.5f * b2 + (1.0f / 3.0f) * a2 * b2, 0.0f));
}

/* The factor of the volume whose record starts at r, at world position p. */
PN_FN pn_float ambient_volume_factor(PN_GLOBAL const float* r, AmbientLanes3 p)
{
    AmbientLanes3 o;
    o.x = p.x - r[1];
    o.y = p.y - r[2];
    o.z = p.z - r[3];
    const pn_float qx = ambient_row(r + 4, o), qy = ambient_row(r + 7, o), qz = ambient_row(r + 10, o);
    const pn_float x2 = qx * qx, y2 = qy * qy, z2 = qz * qz;
    pn_float d2 = x2 + y2 + z2;
    pn_mask outside = d2 > 1.0f;
    if (r[0] == (float)PN_AMBIENT_BOX) {
        const pn_float sx = qx * ambient_cube_stretch(y2, z2);
        const pn_float sy = qy * ambient_cube_stretch(z2, x2);
        const pn_float sz = qz * ambient_cube_stretch(x2, y2);
        d2 = sx * sx + sy * sy + sz * sz;
        outside = pn_or(pn_or(x2 > 1.0f, y2 > 1.0f), z2 > 1.0f);
    }
    const pn_float f = pn_saturate((1.0f - pn_sqrt(pn_min(d2, 1.0f))) * r[14]);
    return pn_select(outside, 0.0f, f);
}

/* The maximum over the volumes: the notes' MAX blend of the ambient buffer. */
PN_FN pn_float ambient_volumes_factor(PN_GLOBAL const float* volumes, int count, AmbientLanes3 p)
{
    pn_float f = 0.0f;
    for (int i = 0; i < count; ++i) f = pn_max(f, ambient_volume_factor(volumes + i * PN_AMBIENT_VOLUME_FLOATS, p));
    return f;
}

/* A receiver plane read as 0 where it is not finite (and the row flagged);
 * lanes past the row's end are not checked. */
PN_FN pn_float ambient_checked_plane(PN_GLOBAL const float* receivers, pn_dims d, int c, int x, int y,
                                     pn_mask active, PN_GLOBAL int* bad_rows)
{
    const pn_float value = pn_load(PN_PLANE(receivers, d, c), d, x, y);
    const pn_mask finite = pn_finite(value);
    pn_flag_any(bad_rows, y, pn_and(active, pn_not(finite)));
    return pn_select(finite, value, 0.0f);
}

/* The world position at receiver planes c .. c + 2. */
PN_FN AmbientLanes3 ambient_load_position(PN_GLOBAL const float* receivers, pn_dims d, int c, int x, int y,
                                        pn_mask active, PN_GLOBAL int* bad_rows)
{
    AmbientLanes3 p;
    p.x = ambient_checked_plane(receivers, d, c, x, y, active, bad_rows);
    p.y = ambient_checked_plane(receivers, d, c + 1, x, y, active, bad_rows);
    p.z = ambient_checked_plane(receivers, d, c + 2, x, y, active, bad_rows);
    return p;
}

/* The ambient buffer alone: out plane 0 gets the factor at the positions of
 * receiver planes position_plane .. + 2. */
PN_KERNEL void ambient_volumes(PN_GLOBAL const float* volumes, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                               PN_GLOBAL int* bad_rows, const AmbientParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const AmbientLanes3 pos = ambient_load_position(receivers, p.receivers, p.position_plane, pn_x, pn_y, pn_active,
                                                  bad_rows);
    pn_store(out, p.out, pn_x, pn_y, ambient_volumes_factor(volumes, p.volume_count, pos));
}

#endif
