/* Sphere-traced soft shadows through a signed distance field.
 *
 * Per receiver (a world-space point P, optionally lifted along its normal N by
 * `normal_offset`: o = P + N normal_offset), a ray o + t w is marched towards
 * the light: w = normalize(L - o) with t_end = min(t_max, |L - o|) for a light
 * centred at L, or w = the given unit direction with t_end = t_max for a
 * directional light. Starting at t = t_min, each step evaluates the distance
 * h = f(o + t w) and advances t by h (sphere tracing, Hart 1996); the lane
 * keeps the narrowest "safe angle" seen, as a visibility estimate
 * (Quilez, "penumbra shadows in raymarched SDFs", iquilezles.org, 2010/2018):
 *
 *   classic:  res = min(res, k h / t)
 *   improved: the spheres of radii h_prev and h about two consecutive points
 *             (distance h_prev apart) bound the occluder; their intersection
 *             circle is the estimated closest approach, at y = h^2 / (2 h_prev)
 *             back along the ray and at distance d = sqrt(h^2 - y^2) from it:
 *             res = min(res, k d / (t - y)).
 *             (The circle's plane lies x from the current point with
 *             h_prev^2 - (h_prev - x)^2 = h^2 - x^2, i.e. x = h^2 / (2 h_prev).)
 *             The first step uses h_prev = 1e20, so y = 0 and d = h: the
 *             classic term. The circle must lie between the two samples
 *             (y < h_prev, which also gives y < h): when the field grows
 *             faster than sqrt(2) per step, as straight away from a surface,
 *             it lies behind the previous sample (at h = 2 h_prev it is the
 *             spheres' tangent point, d = 0, a false 0), and the classic term
 *             stands in; so it does for a circle behind the origin (t <= y).
 *             The triangulation assumes a point-like occluder: against a
 *             smooth one it reads narrower (sqrt(3)/2 of the clearance of a
 *             plane grazed at a small angle), which darkens penumbrae a little.
 *   inner:    res = min(res, k h / t) with h signed: the ray goes on through
 *             solids (no hit), so inside an occluder k h / t goes negative,
 *             and the visibility is smoothstep(-1, 1, res) =
 *             (1 + r)^2 (2 - r) / 4 with r = clamp(res, -1, 1): 1/2 where
 *             the ray to the light's centre grazes an edge, 0 only once the
 *             ray has been 1/k deep inside (the umbra), so the estimate
 *             covers both halves of a penumbra (the "inner penumbra" variant
 *             of Quilez's article, 2020 revision; docs/sdf.md). Each step is
 *             at least max(hit_epsilon, PN_SDF_INNER_STEP t / k): since d is
 *             1-Lipschitz, k h / t moves by at most about PN_SDF_INNER_STEP
 *             between samples, and a ray crosses an occluder's interior in
 *             about 1 / PN_SDF_INNER_STEP steps before res <= -1 ends it.
 *
 * k (> 0, "hardness") sets how wide a safe angle counts as fully lit:
 * 1 / k radians. For a light of width W at distance D, k = c 2 D / W
 * relates it to the light's half-angle (host: sdf_hardness, docs/sdf.md).
 * With k_per_distance > 0 (a light at a point), each receiver computes its
 * own k = k_per_distance D from its distance D to the light's centre.
 *
 * A lane stops when h < hit_epsilon (a hit: visibility 0; inner: when
 * res <= -1, visibility 0), when t >= t_end (escaped: the estimate so far),
 * or after max_steps distance evaluations (exhausted: the estimate so far;
 * the rest of the ray counts as clear). Output: visibility clamp(res, 0, 1)
 * (inner: its smoothstep) in [0, 1], never NaN; optionally the number of
 * distance evaluations per receiver (the lane's active steps).
 *
 * Boundary policy.
 *  - A receiver inside a solid (f(o + t_min w) < hit_epsilon, negative
 *    included) is in shadow, as the ground truth's rays from inside are
 *    (inner: k f / t_min <= -1 at the first step, for any solid deeper than
 *    t_min / k).
 *  - Distance grid (sdf_grid): nodes (i, j, k) at grid_origin + voxel (i, j, k),
 *    x fastest; trilinear inside the box of nodes. Outside it the world is
 *    empty but for what the grid holds: for the nearest box point q at
 *    distance e from p, every point g inside the box is at least
 *    sqrt(|q - g|^2 + e^2) from p (projection onto a convex set), so
 *    f = sqrt(max(f(q), 0)^2 + e^2),
 *    a lower bound that is exact for a nearest surface point seen from q
 *    straight across the box face. Receivers outside the box march in, and
 *    rays leave it and escape.
 *  - Analytic scene (sdf_analytic): the minimum of the primitives' exact
 *    distances (layout: SdfParams in kernels/params.h); no primitives means
 *    f = 1e30 (all lit).
 *
 * Units: positions, distances, t, epsilons and offsets in world units (any,
 * consistently); k in 1 / radians; visibility and steps unitless.
 * Inputs: receivers planes x, y, z (world positions); normals planes x, y, z
 * (read only when normal_offset != 0); rows holding a NaN or infinite position
 * (or normal) are flagged in bad_rows. Outputs: out plane 0 visibility, plane 1
 * steps when write_steps.
 */
#ifndef PENUMBRA_SDF_H
#define PENUMBRA_SDF_H

#define PN_SDF_FAR 1e30f        /* "no surface": the distance of an empty scene */
#define PN_SDF_NO_PREVIOUS 1e20f /* h_prev before the first step (Quilez) */
#define PN_SDF_TINY 1e-30f      /* keeps divisions by lengths and t finite */
#define PN_SDF_INNER_STEP 0.25f /* inner estimate: the least step, in units of t / k */

typedef struct {
    pn_float x, y, z;
} SdfVec3;

PN_FN SdfVec3 sdf_vec3(pn_float x, pn_float y, pn_float z)
{
    SdfVec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

PN_FN pn_float sdf_dot(SdfVec3 a, SdfVec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

PN_FN pn_float sdf_length(SdfVec3 a) { return pn_sqrt(sdf_dot(a, a)); }

/* a + b s */
PN_FN SdfVec3 sdf_along(SdfVec3 a, SdfVec3 b, pn_float s) { return sdf_vec3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }

/* p minus the uniform point stored at r[0..2] */
PN_FN SdfVec3 sdf_minus_stored(SdfVec3 p, PN_GLOBAL const float* r)
{
    return sdf_vec3(p.x - r[0], p.y - r[1], p.z - r[2]);
}

/* dot(v, the uniform vector stored at r[0..2]) */
PN_FN pn_float sdf_dot_stored(SdfVec3 v, PN_GLOBAL const float* r) { return v.x * r[0] + v.y * r[1] + v.z * r[2]; }

/* ---- analytic primitives (records: kernels/params.h, SdfParams) ---------- */

/* Plane {n, offset}: the half-space dot(p, n) <= offset. */
PN_FN pn_float sdf_plane(SdfVec3 p, PN_GLOBAL const float* r) { return sdf_dot_stored(p, r) - r[3]; }

/* Sphere {centre, radius}. */
PN_FN pn_float sdf_sphere(SdfVec3 p, PN_GLOBAL const float* r) { return sdf_length(sdf_minus_stored(p, r)) - r[3]; }

/* Box {centre, half size, local axes x, y, z in world}: with q = |local p| -
 * half size, |max(q, 0)| outside plus max(q) (negative) inside. */
PN_FN pn_float sdf_box(SdfVec3 p, PN_GLOBAL const float* r)
{
    const SdfVec3 c = sdf_minus_stored(p, r);
    const pn_float qx = pn_abs(sdf_dot_stored(c, r + 6)) - r[3];
    const pn_float qy = pn_abs(sdf_dot_stored(c, r + 9)) - r[4];
    const pn_float qz = pn_abs(sdf_dot_stored(c, r + 12)) - r[5];
    const SdfVec3 outside = sdf_vec3(pn_max(qx, 0.0f), pn_max(qy, 0.0f), pn_max(qz, 0.0f));
    return sdf_length(outside) + pn_min(pn_max(qx, pn_max(qy, qz)), 0.0f);
}

/* Capsule {a, b - a, 1 / |b - a|^2 (0 if a = b), radius}: the distance to the
 * segment at parameter s = clamp((p - a).(b - a) / |b - a|^2, 0, 1), minus r. */
PN_FN pn_float sdf_capsule(SdfVec3 p, PN_GLOBAL const float* r)
{
    const SdfVec3 pa = sdf_minus_stored(p, r);
    const pn_float s = pn_clamp(sdf_dot_stored(pa, r + 3) * r[6], 0.0f, 1.0f);
    const SdfVec3 off = sdf_vec3(pa.x - r[3] * s, pa.y - r[4] * s, pa.z - r[5] * s);
    return sdf_length(off) - r[7];
}

PN_FN pn_float sdf_analytic_distance(PN_GLOBAL const float* prims, const SdfParams p, SdfVec3 pos)
{
    pn_float d = PN_SDF_FAR;
    PN_GLOBAL const float* r = prims;
    for (int i = 0; i < p.planes; ++i, r += PN_SDF_PLANE_FLOATS) d = pn_min(d, sdf_plane(pos, r));
    for (int i = 0; i < p.spheres; ++i, r += PN_SDF_SPHERE_FLOATS) d = pn_min(d, sdf_sphere(pos, r));
    for (int i = 0; i < p.boxes; ++i, r += PN_SDF_BOX_FLOATS) d = pn_min(d, sdf_box(pos, r));
    for (int i = 0; i < p.capsules; ++i, r += PN_SDF_CAPSULE_FLOATS) d = pn_min(d, sdf_capsule(pos, r));
    return d;
}

/* ---- the distance grid --------------------------------------------------- */

/* One axis: the node coordinate clamped into the box (c), the cell's lower
 * node (i, so that i + 1 is a node too) and the fraction within it. */
typedef struct {
    pn_float c, i, f;
} SdfAxis;

PN_FN SdfAxis sdf_grid_axis(pn_float world, float origin, float inv_voxel, int nodes)
{
    SdfAxis a;
    /* Any value (NaN included: pn_max returns its second operand) lands in
     * [0, nodes - 1], so every gather below stays inside the grid. */
    a.c = pn_clamp((world - origin) * inv_voxel, 0.0f, (float)(nodes - 1));
    a.i = pn_min(pn_floor(a.c), (float)(nodes - 2));
    a.f = a.c - a.i;
    return a;
}

PN_FN pn_float sdf_lerp(pn_float a, pn_float b, pn_float f) { return a + (b - a) * f; }

/* Trilinear interpolation of the 2 x 2 x 2 nodes from `base`, then the
 * outside bound of the header comment. */
PN_FN pn_float sdf_grid_distance(PN_GLOBAL const float* grid, const SdfParams p, SdfVec3 pos)
{
    const SdfAxis ax = sdf_grid_axis(pos.x, p.grid_x, p.inv_voxel, p.grid_nx);
    const SdfAxis ay = sdf_grid_axis(pos.y, p.grid_y, p.inv_voxel, p.grid_ny);
    const SdfAxis az = sdf_grid_axis(pos.z, p.grid_z, p.inv_voxel, p.grid_nz);
    const int row = p.grid_nx, slice = p.grid_nx * p.grid_ny;
    const pn_int base = pn_to_int(ax.i) + pn_to_int(ay.i) * row + pn_to_int(az.i) * slice;
    const pn_float d00 = sdf_lerp(pn_gather(grid, base), pn_gather(grid, base + 1), ax.f);
    const pn_float d10 = sdf_lerp(pn_gather(grid, base + row), pn_gather(grid, base + (row + 1)), ax.f);
    const pn_float d01 = sdf_lerp(pn_gather(grid, base + slice), pn_gather(grid, base + (slice + 1)), ax.f);
    const pn_float d11 =
        sdf_lerp(pn_gather(grid, base + (slice + row)), pn_gather(grid, base + (slice + row + 1)), ax.f);
    const pn_float inside = sdf_lerp(sdf_lerp(d00, d10, ay.f), sdf_lerp(d01, d11, ay.f), az.f);

    const SdfVec3 beyond = sdf_vec3((pos.x - p.grid_x) * p.inv_voxel - ax.c, (pos.y - p.grid_y) * p.inv_voxel - ay.c,
                                    (pos.z - p.grid_z) * p.inv_voxel - az.c);
    const pn_float e2 = sdf_dot(beyond, beyond) * (p.voxel * p.voxel);
    const pn_float kept = pn_max(inside, 0.0f);
    return pn_select(e2 > 0.0f, pn_sqrt(kept * kept + e2), inside);
}

/* ---- the march ----------------------------------------------------------- */

typedef struct {
    SdfVec3 origin, dir;
    pn_float t, t_end;
    pn_float k;      /* hardness (per receiver with k_per_distance) */
    pn_float res;    /* the narrowest estimate so far */
    pn_float h_prev; /* the previous step's distance (improved estimate) */
    pn_float steps;  /* distance evaluations while active */
    pn_mask active;
} SdfMarch;

PN_FN SdfVec3 sdf_load_vec3(PN_GLOBAL const float* planes, pn_dims d, int x, int y, PN_GLOBAL int* bad_rows)
{
    const SdfVec3 v = sdf_vec3(pn_load(PN_PLANE(planes, d, 0), d, x, y), pn_load(PN_PLANE(planes, d, 1), d, x, y),
                               pn_load(PN_PLANE(planes, d, 2), d, x, y));
    pn_flag_any(bad_rows, y, pn_not(pn_and(pn_and(pn_finite(v.x), pn_finite(v.y)), pn_finite(v.z))));
    return v;
}

PN_FN SdfMarch sdf_march_begin(PN_GLOBAL const float* receivers, PN_GLOBAL const float* normals,
                               PN_GLOBAL int* bad_rows, const SdfParams p, int x, int y, pn_mask in_image)
{
    SdfMarch m;
    m.origin = sdf_load_vec3(receivers, p.receivers, x, y, bad_rows);
    if (p.normal_offset != 0.0f)
        m.origin = sdf_along(m.origin, sdf_load_vec3(normals, p.normals, x, y, bad_rows), p.normal_offset);
    const SdfVec3 light = sdf_vec3(p.light_x, p.light_y, p.light_z);
    m.k = p.k;
    if (p.light_is_direction) {
        m.dir = light;
        m.t_end = p.t_max;
    } else {
        const SdfVec3 to_light = sdf_vec3(light.x - m.origin.x, light.y - m.origin.y, light.z - m.origin.z);
        const pn_float distance = sdf_length(to_light);
        const pn_float inv = 1.0f / pn_max(distance, PN_SDF_TINY);
        m.dir = sdf_vec3(to_light.x * inv, to_light.y * inv, to_light.z * inv);
        m.t_end = pn_min(distance, p.t_max);
        if (p.k_per_distance > 0.0f) m.k = p.k_per_distance * distance;
    }
    m.t = p.t_min;
    m.res = 1.0f;
    m.h_prev = PN_SDF_NO_PREVIOUS;
    m.steps = 0.0f;
    /* t < t_end is false for NaN: a bad receiver never marches. */
    m.active = pn_and(in_image, m.t < m.t_end);
    return m;
}

PN_FN SdfVec3 sdf_march_point(const SdfMarch* m) { return sdf_along(m->origin, m->dir, m->t); }

PN_FN pn_float sdf_classic_estimate(pn_float k, pn_float h, pn_float t) { return k * h / pn_max(t, PN_SDF_TINY); }

PN_FN pn_float sdf_improved_estimate(pn_float k, pn_float h, pn_float h_prev, pn_float t)
{
    const pn_float y = h * h / (2.0f * h_prev);
    const pn_float d = pn_sqrt(pn_max(h * h - y * y, 0.0f));
    const pn_float along = t - y;
    const pn_mask circle = pn_and(along > 0.0f, y < h_prev);
    return pn_select(circle, k * d / pn_max(along, PN_SDF_TINY), sdf_classic_estimate(k, h, t));
}

/* One step for the active lanes; the others keep their state. */
PN_FN void sdf_march_step(SdfMarch* m, pn_float h, const SdfParams p)
{
    const pn_float estimate = p.estimate == PN_SDF_IMPROVED ? sdf_improved_estimate(m->k, h, m->h_prev, m->t)
                                                            : sdf_classic_estimate(m->k, h, m->t);
    m->res = pn_select(m->active, pn_min(m->res, estimate), m->res);
    m->steps = pn_select(m->active, m->steps + 1.0f, m->steps);
    m->h_prev = pn_select(m->active, h, m->h_prev);
    pn_mask done;
    if (p.estimate == PN_SDF_INNER) {
        /* Through solids: at least PN_SDF_INNER_STEP / k of the way per step
         * (relative to t), so that k h / t moves by at most about that much
         * between samples; done once the umbra is certain (res <= -1). */
        const pn_float floor = pn_max(p.hit_epsilon, m->t * (PN_SDF_INNER_STEP / m->k));
        m->t = pn_select(m->active, m->t + pn_max(h, floor), m->t);
        done = m->res <= -1.0f;
    } else {
        done = h < p.hit_epsilon;
        m->res = pn_select(pn_and(m->active, done), 0.0f, m->res);
        m->t = pn_select(m->active, m->t + h, m->t);
    }
    m->active = pn_and(pn_and(m->active, pn_not(done)), m->t < m->t_end);
}

/* The inner-penumbra estimate's visibility: smoothstep from -1 to 1. */
PN_FN pn_float sdf_inner_visibility(pn_float res)
{
    const pn_float r = pn_clamp(res, -1.0f, 1.0f);
    return 0.25f * (1.0f + r) * (1.0f + r) * (2.0f - r);
}

PN_FN void sdf_march_end(PN_GLOBAL float* out, const SdfParams p, int x, int y, const SdfMarch* m)
{
    const pn_float visibility =
        p.estimate == PN_SDF_INNER ? sdf_inner_visibility(m->res) : pn_clamp(m->res, 0.0f, 1.0f);
    pn_store(out, p.out, x, y, visibility);
    if (p.write_steps) pn_store(PN_PLANE(out, p.out, 1), p.out, x, y, m->steps);
}

/* The two entries differ only in the distance they march through: the
 * march of both, `distance(source, p, point)` per step. */
#define PN_SDF_MARCH(distance, source)                                                          \
    PN_PIXEL_BEGIN(p.out.width, p.out.height);                                                  \
    SdfMarch m = sdf_march_begin(receivers, normals, bad_rows, p, pn_x, pn_y, pn_active);       \
    for (int i = 0; i < p.max_steps && pn_any(m.active); ++i)                                   \
        sdf_march_step(&m, distance(source, p, sdf_march_point(&m)), p);                        \
    sdf_march_end(out, p, pn_x, pn_y, &m)

PN_KERNEL void sdf_grid(PN_GLOBAL const float* grid, PN_GLOBAL const float* receivers,
                        PN_GLOBAL const float* normals, PN_GLOBAL float* out, PN_GLOBAL int* bad_rows,
                        const SdfParams p, PN_PIXEL_ARGS)
{
    PN_SDF_MARCH(sdf_grid_distance, grid);
}

PN_KERNEL void sdf_analytic(PN_GLOBAL const float* prims, PN_GLOBAL const float* receivers,
                            PN_GLOBAL const float* normals, PN_GLOBAL float* out, PN_GLOBAL int* bad_rows,
                            const SdfParams p, PN_PIXEL_ARGS)
{
    PN_SDF_MARCH(sdf_analytic_distance, prims);
}

#endif
