/* Pismo's shadow-ray test (Neulander, "Pismo: Parallax-Interpolated Shadow
 * Map Occlusion", Rhythm & Hues; notes in ../shared/seeds/002;
 * docs/pismo.md, "The kernel"). The light is a triangle mesh with one
 * perspective layered depth map per vertex.
 *
 * Two entries, run one after the other over a chunk of receivers:
 *
 *   pismo_estimates  per receiver P and map j: the first estimate D_j, the
 *                    radial depth of the farthest layer of the BLED map j, at
 *                    P's pixel, nearer than P's own depth minus the bias;
 *                    -1 where there is none (no such layer, or P outside the
 *                    map). Out: pixel (x, j rows + y) for receiver (x, y),
 *                    so every estimate is computed once per P per map and
 *                    read back by the second entry with a row load.
 *   pismo_visibility per receiver P, for each ray i of each light triangle
 *                    (a, b, c), barycentric weights w = (w_a, w_b, w_c):
 *                      L_i = sum w_k V_k                (a point on the light)
 *                      D   = sum w_k D_k / sum w_k over the corners with an
 *                            estimate (none: O_i = P)
 *                      O_i = L_i + D (P - L_i) / |P - L_i|
 *                      lit_i = sum w_k (1 - o_k), o_k = 1 when the TEST map
 *                            k holds, at O_i's pixel, a layer nearer than
 *                            |P - V_k| minus the bias (P behind the occluder)
 *                    Out: sum_i weight_i lit_i / sum_i weight_i sum_k w_k,
 *                    in [0, 1] (the denominator is 1 up to float rounding).
 *
 * Sources (host/src/pismo_pack.cpp packs them; keep the layouts in sync):
 *   offsets   uint: every map's offsets into `depths`, maps one after
 *             another (map j's pixel q at j W H + q), then one end entry
 *   depths    float: every layer, nearest first within a pixel
 *   ids       float (visibility): the surface id of each test-map layer,
 *             parallel to depths (one stand-in element without ids)
 *   cameras   PN_PISMO_CAMERA_FLOATS floats per map: position, right, down,
 *             forward (3 each), 2 tan(fov/2), 2 tan(fov/2) / W, 2 unused
 *   triangles PN_PISMO_TRIANGLE_UINTS uints per triangle: corners a, b, c,
 *             its first ray and the end of its rays
 *   rays      PN_PISMO_RAY_FLOATS floats per ray: w_a, w_b, w_c, its weight
 *             (the triangle's share of the light's area over its strata)
 * The ray pattern is the same for every receiver (host/src/pismo_rays.cpp
 * states the formula). Receivers: planes x, y, z, world position; a
 * non-finite one flags its row and reads as 0.
 *
 * Landing: p - position = (x, y, d) along (right, down, forward); inside
 * when d > 0 and the pixel (floor(u W), floor(v H)) of u = 1/2 + x / (2 tan
 * d), v likewise, lies in the map (MapCamera, penumbra/layered_depth_map.h).
 * A point outside a map sees no caster there: no estimate, no occlusion.
 * The bias is bias_texels texel footprints at the point's depth d,
 * bias_texels 2 tan(fov/2) d / W.
 *
 * The receiver's own surface (p.normals; docs/pismo.md, "The receiver's own
 * surface"), with P's normal n, as the truth counts it (its rays start at P
 * lifted along n, so a ray below P's tangent plane enters P's solid):
 *   a ray to L_i with n . (L_i - P) <= 0 is blocked;
 *   a corner map k with n . (V_k - P) <= 0 sees P's solid from behind: its
 *     hard test is "occluded" (so a ray ending at V_k is still that test),
 *     and a ray above the plane leaves it out, the other corners' weights
 *     renormalised (none left: lit);
 *   elsewhere map k's bias grows by min(tan theta_k, max_slope) texels,
 *     theta_k the angle between n and V_k - P: the depth P's own surface
 *     spans across one texel seen from V_k (no acne at a lit terminator).
 *
 * Surface ids (p.surface_ids; docs/pismo.md, "A surface id per layer"): the
 * receiver's 7th plane is the id of the surface it lies on (< 0: unknown, the
 * rules above), each test-map layer carries the id of the surface it crosses.
 * Map k then occludes when a layer of ANOTHER surface lies nearer than |P -
 * V_k| minus other_bias_texels texels; a layer of P's own surface never
 * occludes P (every caster is a convex solid, which cannot block a ray above
 * its tangent plane at a point of its surface; the rays below it are blocked
 * by the rules above, which stay).
 */
#ifndef PENUMBRA_PISMO_H
#define PENUMBRA_PISMO_H

typedef struct {
    pn_float x, y, z;
} PismoPoint;

/* A shading point: its position, its normal (zero without p.normals) and its
 * surface id (-1 without p.surface_ids). */
typedef struct {
    PismoPoint p, n;
    pn_float surface;
} PismoReceiver;

/* Where a point lands in one map. */
typedef struct {
    pn_int pixel;   /* index into the offsets (clamped into the map: valid to gather) */
    pn_float limit; /* the point's depth minus the bias there */
    pn_float depth; /* the point's depth */
    pn_float texel; /* one texel's footprint at that depth */
    pn_mask inside;
} PismoLanding;

PN_FN PismoLanding pismo_land(PN_GLOBAL const float* cameras, PismoParams p, int map, PismoPoint q, pn_float bias_texels)
{
    PN_GLOBAL const float* c = cameras + PN_PISMO_CAMERA_FLOATS * map;
    const pn_float lx = q.x - c[0], ly = q.y - c[1], lz = q.z - c[2];
    const pn_float x = lx * c[3] + ly * c[4] + lz * c[5];
    const pn_float y = lx * c[6] + ly * c[7] + lz * c[8];
    const pn_float d = lx * c[9] + ly * c[10] + lz * c[11];
    const pn_float col = pn_floor((0.5f + x / (d * c[12])) * (float)p.map_width);
    const pn_float row = pn_floor((0.5f + y / (d * c[12])) * (float)p.map_height);
    PismoLanding at;
    /* Every comparison with a NaN (d = 0) is false: such a point is outside. */
    at.inside = pn_and(pn_and(d > 0.0f, pn_and(col >= 0.0f, col < (float)p.map_width)),
                       pn_and(row >= 0.0f, row < (float)p.map_height));
    const pn_int ix = pn_to_int(pn_select(at.inside, col, 0.0f));
    const pn_int iy = pn_to_int(pn_select(at.inside, row, 0.0f));
    at.pixel = ix + iy * p.map_width + map * (p.map_width * p.map_height);
    at.depth = pn_sqrt(lx * lx + ly * ly + lz * lz);
    at.texel = c[13] * at.depth;
    at.limit = at.depth - bias_texels * at.texel;
    return at;
}

/* n . (t - P): <= 0 where the receiver's own surface faces away from t
 * (0 without normals, so no own-surface rule: the masks below need n != 0). */
PN_FN pn_float pismo_facing(PismoReceiver r, float tx, float ty, float tz)
{
    return r.n.x * (tx - r.p.x) + r.n.y * (ty - r.p.y) + r.n.z * (tz - r.p.z);
}

PN_FN pn_mask pismo_has_normal(PismoReceiver r)
{
    return r.n.x * r.n.x + r.n.y * r.n.y + r.n.z * r.n.z > 0.0f;
}

/* Map `map`'s bias in texels at r: bias_texels, plus min(tan theta, max_slope)
 * where r's surface faces the map's vertex. */
PN_FN pn_float pismo_bias(PN_GLOBAL const float* cameras, PismoParams p, int map, PismoReceiver r)
{
    PN_GLOBAL const float* c = cameras + PN_PISMO_CAMERA_FLOATS * map;
    const pn_float facing = pismo_facing(r, c[0], c[1], c[2]);
    const pn_float tx = c[0] - r.p.x, ty = c[1] - r.p.y, tz = c[2] - r.p.z;
    const pn_float scale = pn_sqrt((tx * tx + ty * ty + tz * tz) * (r.n.x * r.n.x + r.n.y * r.n.y + r.n.z * r.n.z));
    const pn_float cosine = pn_select(facing > 0.0f, facing / pn_max(scale, 1e-30f), 1.0f);
    const pn_float tangent = pn_sqrt(pn_max(1.0f - cosine * cosine, 0.0f)) / pn_max(cosine, 1e-6f);
    return p.bias_texels + pn_select(pn_and(pismo_has_normal(r), facing > 0.0f), pn_min(tangent, p.max_slope), 0.0f);
}

PN_FN PismoReceiver pismo_receiver(PN_GLOBAL const float* receivers, PismoParams p, int y, PN_GLOBAL int* bad_rows,
                                   int x)
{
    PismoReceiver r;
    r.p.x = load_checked_plane(receivers, p.receivers, 0, x, y, bad_rows);
    r.p.y = load_checked_plane(receivers, p.receivers, 1, x, y, bad_rows);
    r.p.z = load_checked_plane(receivers, p.receivers, 2, x, y, bad_rows);
    r.n.x = 0.0f;
    r.n.y = 0.0f;
    r.n.z = 0.0f;
    if (p.normals) {
        r.n.x = load_checked_plane(receivers, p.receivers, 3, x, y, bad_rows);
        r.n.y = load_checked_plane(receivers, p.receivers, 4, x, y, bad_rows);
        r.n.z = load_checked_plane(receivers, p.receivers, 5, x, y, bad_rows);
    }
    r.surface = -1.0f;
    if (p.surface_ids) r.surface = load_checked_plane(receivers, p.receivers, 6, x, y, bad_rows);
    return r;
}

/* The farthest layer of a pixel nearer than `limit`, or -1: the layers are
 * increasing, so the walk stops at the first one at or past it. */
PN_FN pn_float pismo_nearest_occluder(PN_GLOBAL const uint* offsets, PN_GLOBAL const float* depths, PismoParams p,
                                      PismoLanding at)
{
    pn_uint first, second;
    pn_ugather_pair(offsets, at.pixel, &first, &second);
    pn_int i = pn_uint_to_index(first);
    const pn_int end = pn_uint_to_index(second);
    pn_float nearest = -1.0f;
    pn_mask active = pn_and(at.inside, pn_iless(i, end));
    while (pn_any(active)) {
        const pn_float d = pn_gather(depths, pn_imin(i, p.last_depth));
        active = pn_and(active, d < at.limit);
        nearest = pn_select(active, d, nearest);
        i = pn_iselect(active, i + 1, i);
        active = pn_and(active, pn_iless(i, end));
    }
    return nearest;
}

PN_KERNEL void pismo_estimates(PN_GLOBAL const uint* offsets, PN_GLOBAL const float* depths,
                               PN_GLOBAL const float* cameras, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                               PN_GLOBAL int* bad_rows, const PismoParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const int rows = p.receivers.height;
    const PismoReceiver r = pismo_receiver(receivers, p, pn_y % rows, bad_rows, pn_x);
    const int map = pn_y / rows;
    const PismoLanding at = pismo_land(cameras, p, map, r.p, pismo_bias(cameras, p, map, r));
    pn_store(out, p.out, pn_x, pn_y, pismo_nearest_occluder(offsets, depths, p, at));
}

/* What a ray needs of one corner of its triangle, per receiver. */
typedef struct {
    int map;
    float vx, vy, vz;  /* the vertex */
    pn_float estimate; /* D_k, or -1 */
    pn_float limit;    /* |P - V_k| minus the bias */
    pn_float other_limit; /* |P - V_k| minus other_bias_texels: for another surface's layers (surface ids) */
    pn_float bias;     /* the bias there, texels */
    pn_mask p_inside;  /* P lands in map k */
    pn_mask own;       /* P's own solid occludes V_k (its surface faces away from it) */
} PismoCorner;

PN_FN PismoCorner pismo_corner(PN_GLOBAL const float* cameras, PN_GLOBAL const float* estimates, PismoParams p,
                               int map, PismoReceiver r, int x, int y)
{
    PismoCorner k;
    PN_GLOBAL const float* c = cameras + PN_PISMO_CAMERA_FLOATS * map;
    k.map = map;
    k.vx = c[0];
    k.vy = c[1];
    k.vz = c[2];
    k.estimate = pn_load(estimates, p.estimates, x, map * p.receivers.height + y);
    k.bias = pismo_bias(cameras, p, map, r);
    const PismoLanding at = pismo_land(cameras, p, map, r.p, k.bias);
    k.limit = at.limit;
    k.other_limit = at.depth - p.other_bias_texels * at.texel;
    k.p_inside = at.inside;
    k.own = pn_and(pismo_has_normal(r), pismo_facing(r, k.vx, k.vy, k.vz) <= 0.0f);
    return k;
}

/* With surface ids, whether a layer of another surface than the receiver's
 * lies nearer than other_limit among the layers [i, end): the layers are
 * increasing, so the walk stops at the first one at or past it. */
PN_FN pn_mask pismo_other_surface_nearer(PN_GLOBAL const float* depths, PN_GLOBAL const float* ids, PismoParams p,
                                         pn_int i, pn_int end, pn_mask active, pn_float other_limit, pn_float own)
{
    pn_mask found = pn_and(active, pn_not(active));
    active = pn_and(active, pn_iless(i, end));
    while (pn_any(active)) {
        const pn_int at = pn_imin(i, p.last_depth);
        active = pn_and(active, pn_gather(depths, at) < other_limit);
        const pn_float id = pn_gather(ids, at);
        found = pn_or(found, pn_and(active, pn_or(id < own, id > own)));
        active = pn_and(active, pn_not(found));
        i = pn_iselect(active, i + 1, i);
        active = pn_and(active, pn_iless(i, end));
    }
    return found;
}

/* o_k: whether test map k holds, at o's pixel, a layer nearer than P's limit
 * there (its nearest layer is enough: any nearer layer implies it), or P's
 * own solid occludes V_k. With P's surface id, a layer of another surface
 * nearer than the other limit instead. */
PN_FN pn_mask pismo_occludes(PN_GLOBAL const uint* offsets, PN_GLOBAL const float* depths, PN_GLOBAL const float* ids,
                             PN_GLOBAL const float* cameras, PismoParams p, PismoCorner k, PismoPoint o,
                             pn_float surface)
{
    const PismoLanding at = pismo_land(cameras, p, k.map, o, k.bias);
    pn_uint first, second;
    pn_ugather_pair(offsets, at.pixel, &first, &second);
    const pn_int begin = pn_uint_to_index(first);
    const pn_int end = pn_uint_to_index(second);
    const pn_float front = pn_gather(depths, pn_imin(begin, p.last_depth));
    const pn_mask valid = pn_and(at.inside, k.p_inside);
    const pn_mask by_depth = pn_and(pn_and(valid, pn_iless(begin, end)), front < k.limit);
    if (!p.surface_ids) return pn_or(k.own, by_depth);
    const pn_mask known = surface >= 0.0f;
    const pn_mask by_id = pismo_other_surface_nearer(depths, ids, p, begin, end, pn_and(valid, known), k.other_limit,
                                                     surface);
    return pn_or(k.own, pn_or(pn_and(known, by_id), pn_and(pn_not(known), by_depth)));
}

/* The lit share of one ray, sum of w_k (1 - o_k), weights w (uniform: the
 * pattern is the same for every receiver, so L_i is too). */
PN_FN pn_float pismo_ray_light(PN_GLOBAL const uint* offsets, PN_GLOBAL const float* depths,
                                   PN_GLOBAL const float* ids, PN_GLOBAL const float* cameras, PismoParams p,
                                   const PismoCorner* k, PN_GLOBAL const float* w, PismoReceiver r)
{
    const PismoPoint q = r.p;
    const float lx = w[0] * k[0].vx + w[1] * k[1].vx + w[2] * k[2].vx;
    const float ly = w[0] * k[0].vy + w[1] * k[1].vy + w[2] * k[2].vy;
    const float lz = w[0] * k[0].vz + w[1] * k[1].vz + w[2] * k[2].vz;
    pn_float distance = 0.0f, weight = 0.0f;
    for (int j = 0; j < 3; ++j) {
        const pn_mask has = k[j].estimate > 0.0f;
        distance = distance + pn_select(has, w[j] * k[j].estimate, 0.0f);
        weight = weight + pn_select(has, w[j], 0.0f);
    }
    const pn_float tx = q.x - lx, ty = q.y - ly, tz = q.z - lz;
    const pn_float along = distance / weight / pn_sqrt(tx * tx + ty * ty + tz * tz);
    const pn_mask estimated = weight > 0.0f;
    PismoPoint o;
    o.x = pn_select(estimated, lx + tx * along, q.x);
    o.y = pn_select(estimated, ly + ty * along, q.y);
    o.z = pn_select(estimated, lz + tz * along, q.z);
    /* A corner that sees P's own solid (k.own) does not see what this ray
     * passes when the ray is above P's tangent plane: the other corners
     * answer, renormalised; with none left the ray is lit. */
    pn_float lit = 0.0f, answering = 0.0f;
    for (int j = 0; j < 3; ++j) {
        lit = lit + pn_select(pn_or(k[j].own, pismo_occludes(offsets, depths, ids, cameras, p, k[j], o, r.surface)),
                              0.0f, w[j]);
        answering = answering + pn_select(k[j].own, 0.0f, w[j]);
    }
    const float all = (0.0f + w[0]) + w[1] + w[2];
    const pn_float share = pn_select(answering > 0.0f, lit / pn_max(answering, 1e-30f), 1.0f) * all;
    const pn_mask has_normal = pismo_has_normal(r);
    /* Without normals no corner is own: lit as summed. A ray below P's tangent plane enters P's own solid. */
    return pn_select(has_normal, pn_select(pismo_facing(r, lx, ly, lz) <= 0.0f, 0.0f, share), lit);
}

PN_KERNEL void pismo_visibility(PN_GLOBAL const uint* offsets, PN_GLOBAL const float* depths,
                                PN_GLOBAL const float* ids, PN_GLOBAL const float* cameras, PN_GLOBAL const uint* triangles,
                                PN_GLOBAL const float* rays, PN_GLOBAL const float* estimates,
                                PN_GLOBAL const float* receivers, PN_GLOBAL float* out, PN_GLOBAL int* bad_rows,
                                const PismoParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const PismoReceiver q = pismo_receiver(receivers, p, pn_y, bad_rows, pn_x);
    /* Lit rays over all rays, both summed in the same order, so that a point
     * that every ray reaches is exactly 1 and one that none reaches exactly 0
     * (the float32 weights sum to 1 only within a rounding). */
    pn_float lit = 0.0f;
    float total = 0.0f;
    for (int t = 0; t < p.triangles; ++t) {
        PN_GLOBAL const uint* tri = triangles + PN_PISMO_TRIANGLE_UINTS * t;
        PismoCorner k[3];
        for (int j = 0; j < 3; ++j) k[j] = pismo_corner(cameras, estimates, p, (int)tri[j], q, pn_x, pn_y);
        for (int r = (int)tri[3]; r < (int)tri[4]; ++r) {
            PN_GLOBAL const float* w = rays + PN_PISMO_RAY_FLOATS * r;
            lit = lit + w[3] * pismo_ray_light(offsets, depths, ids, cameras, p, k, w, q);
            total = total + w[3] * (((0.0f + w[0]) + w[1]) + w[2]);
        }
    }
    pn_store(out, p.out, pn_x, pn_y, pn_saturate(lit / total));
}

#endif
