/* The Hammersley point set in polar form, as a disc of filter taps.
 *
 * Point k of n (Weisstein, "Hammersley Point Set", MathWorld):
 *   x_k = k / n,  y_k = phi_2(k), the base-2 radical inverse (the bits of k
 *   mirrored about the binary point: phi_2(6 = 110b) = 0.011b = 3/8).
 * Burley ("Shadow Map Bias Cone and Improved Soft Shadows", section 3.2, notes
 * 2-4) takes x as the angle, theta = 2 pi x, and y as the radius:
 *   radius = y        concentrates taps near the centre (the blocker search:
 *                     close contacts can only be near the centre, note 4);
 *   radius = sqrt(y)  restores uniform density over the disc (the area within
 *                     radius rho is rho^2, so sqrt maps uniform y to uniform
 *                     area: the percentage-closer blur, note 3).
 * Point 0 is the centre (y_0 = 0), so every pattern tests the receiver's own
 * texel, which is what makes a zero radius a hard shadow equal to pcf r=0.
 *
 * The disc helpers at the end read the map under the family's depth bias
 * (kernels/depth_bias.h), so this file follows it in the kernel list.
 *
 * The pattern is uniform (the same for every pixel). Its rotation step is
 * computed in double by the series below, not by a library cos or sin (which
 * may differ between OpenCL and C++ by an ulp), and the taps are walked by
 * that rotation in double, so every backend places the taps on the same
 * float values.
 */
#ifndef PENUMBRA_HAMMERSLEY_H
#define PENUMBRA_HAMMERSLEY_H

/* phi_2(k) for k < 2^24 (exact in float: the mirrored bits fit a mantissa). */
PN_FN float hammersley_radical_inverse(uint k)
{
    uint b = k;
    b = (b << 16) | (b >> 16);
    b = ((b & 0x00ff00ffu) << 8) | ((b & 0xff00ff00u) >> 8);
    b = ((b & 0x0f0f0f0fu) << 4) | ((b & 0xf0f0f0f0u) >> 4);
    b = ((b & 0x33333333u) << 2) | ((b & 0xccccccccu) >> 2);
    b = ((b & 0x55555555u) << 1) | ((b & 0xaaaaaaaau) >> 1);
    return (float)(b >> 8) * (1.0f / 16777216.0f);
}

/* sin a for |a| <= pi/4 by its Taylor series to a^17 (the next term is below
 * 1e-19), in Horner form. */
PN_FN double hammersley_sin_series(double a)
{
    const double a2 = a * a;
    double s = 1.0 / 355687428096000.0;          /* 1/17! */
    s = 1.0 / 1307674368000.0 - a2 * s;          /* 1/15! */
    s = 1.0 / 6227020800.0 - a2 * s;             /* 1/13! */
    s = 1.0 / 39916800.0 - a2 * s;               /* 1/11! */
    s = 1.0 / 362880.0 - a2 * s;                 /* 1/9! */
    s = 1.0 / 5040.0 - a2 * s;                   /* 1/7! */
    s = 1.0 / 120.0 - a2 * s;                    /* 1/5! */
    s = 1.0 / 6.0 - a2 * s;                      /* 1/3! */
    return a * (1.0 - a2 * s);
}

/* cos a for |a| <= pi/4, to a^18. */
PN_FN double hammersley_cos_series(double a)
{
    const double a2 = a * a;
    double c = 1.0 / 6402373705728000.0;         /* 1/18! */
    c = 1.0 / 20922789888000.0 - a2 * c;         /* 1/16! */
    c = 1.0 / 87178291200.0 - a2 * c;            /* 1/14! */
    c = 1.0 / 479001600.0 - a2 * c;              /* 1/12! */
    c = 1.0 / 3628800.0 - a2 * c;                /* 1/10! */
    c = 1.0 / 40320.0 - a2 * c;                  /* 1/8! */
    c = 1.0 / 720.0 - a2 * c;                    /* 1/6! */
    c = 1.0 / 24.0 - a2 * c;                     /* 1/4! */
    c = 0.5 - a2 * c;                            /* 1/2! */
    return 1.0 - a2 * c;
}

/* One tap of the unit disc: (dx, dy) = radius (cos theta, sin theta). */
typedef struct {
    float dx;
    float dy;
    float radius;
} DiscTap;

/* (cos, sin) of the angle 2 pi k / n of tap k: the angle is reduced to the
 * nearest quarter turn q and a remainder a in [-pi/4, pi/4]; then (cos, sin)
 * of q quarter turns rotate (cos a, sin a). */
PN_FN void hammersley_angle(int k, int n, double* cos_t, double* sin_t)
{
    const double turns = (double)k / (double)n;
    const int q = (int)(4.0 * turns + 0.5);
    const double a = 6.283185307179586 * (turns - 0.25 * (double)q);
    const double c = hammersley_cos_series(a), s = hammersley_sin_series(a);
    const int quadrant = q & 3;
    *cos_t = quadrant == 0 ? c : quadrant == 1 ? -s : quadrant == 2 ? -c : s;
    *sin_t = quadrant == 0 ? s : quadrant == 1 ? c : quadrant == 2 ? -s : -c;
}

/* The taps of an n-point pattern in order, k = 0 .. n - 1. Tap k's angle is
 * k times 2 pi / n, so each step rotates the last (cos, sin) by the step's
 * (cos, sin), taken once from the series: four multiplies a tap instead of a
 * series, which a work-item per receiver (OpenCL) would pay per receiver.
 * The rotation runs in double: after PN_SOFT_MAX_SAMPLES steps its error is
 * below 1e-12, far under a float offset's ulp. */
typedef struct {
    double cos_t, sin_t;   /* tap k's direction */
    double step_c, step_s; /* the rotation by 2 pi / n */
    int k;
    int uniform_density;   /* nonzero: radius sqrt(y) (the blur pass); zero: y (the depth pass) */
} DiscWalk;

PN_FN DiscWalk hammersley_walk(int n, int uniform_density)
{
    DiscWalk w;
    w.cos_t = 1.0;
    w.sin_t = 0.0;
    hammersley_angle(1, n, &w.step_c, &w.step_s);
    w.k = 0;
    w.uniform_density = uniform_density;
    return w;
}

/* The current tap, then a step to the next one. */
PN_FN DiscTap hammersley_walk_next(DiscWalk* w)
{
    const float y = hammersley_radical_inverse((uint)w->k);
    DiscTap tap;
    tap.radius = w->uniform_density ? (float)sqrt((double)y) : y;
    tap.dx = (float)((double)tap.radius * w->cos_t);
    tap.dy = (float)((double)tap.radius * w->sin_t);
    const double next_c = w->cos_t * w->step_c - w->sin_t * w->step_s;
    w->sin_t = w->sin_t * w->step_c + w->cos_t * w->step_s;
    w->cos_t = next_c;
    w->k = w->k + 1;
    return tap;
}

/* ---- The disc around a receiver (pcss, burley). Uses kernels/depth_bias.h. ---- */

/* The texel a tap at continuous texel coordinate t reads: floor(t) clamped
 * into [0, size - 1] (clamp to edge), as a float holding an integer. */
PN_FN pn_float hammersley_texel(pn_float t, int size)
{
    return pn_clamp(pn_floor(t), 0.0f, (float)size - 1.0f);
}

/* What one tap of a disc reads: its depth (normalised), and the depth it must
 * reach to be lit under the family's bias at the texel it reads
 * (pcf_tap_reference), before any cone. */
typedef struct {
    pn_float depth;
    pn_float reference;
} DiscSample;

/* Tap t of the disc of `radius` (texture units) around receiver r on the
 * map of dims `map`, read from the rows `held` holds (the whole map, or a
 * band the CPU schedule converted; hammersley_disc_leaves_band): the tap
 * sits at (u W + dx radius W, v H + dy radius H) texels. */
PN_FN DiscSample hammersley_sample(PN_GLOBAL const float* depth, pn_dims map, DirectMap held, PcfBias b,
                                   PcfReceiver r, pn_float radius, DiscTap t)
{
    const float w = (float)map.width, h = (float)map.height;
    const pn_float tx = hammersley_texel(r.u * w + t.dx * radius * w, map.width);
    const pn_float ty = hammersley_texel(r.v * h + t.dy * radius * h, map.height);
    DiscSample s;
    s.depth = depth_fetch(depth, held, pn_to_int(tx), pn_to_int(ty));
    s.reference = pcf_tap_reference(r, b, map, tx, ty);
    return s;
}

/* Percentage-closer filtering over the uniform-density disc (radius sqrt(y))
 * of `radius` (texture units): the fraction of n taps lit, a tap at distance
 * rho (texture units) from the centre lowered by the cone slope * rho
 * (slope 0: the family's bias alone; Burley's bias cone otherwise). */
PN_FN pn_float hammersley_disc_visibility(PN_GLOBAL const float* depth, pn_dims map, DirectMap held, PcfBias b,
                                          PcfReceiver r, pn_float radius, int n, pn_float slope)
{
    pn_float lit = 0.0f;
    DiscWalk walk = hammersley_walk(n, 1);
    for (int k = 0; k < n; ++k) {
        const DiscTap t = hammersley_walk_next(&walk);
        const DiscSample s = hammersley_sample(depth, map, held, b, r, radius, t);
        lit = lit + pcf_lit(s.depth, s.reference - slope * t.radius * radius);
    }
    return lit / (float)n;
}

/* The blocker search of both soft members: n taps of the disc of `radius`
 * (texture units); a tap at distance rho = t.radius * radius blocks when its
 * depth is below its reference minus cone_slope * rho (pcss: slope 0), and
 * weighs 1 - weight_falloff * t.radius (pcss: 0, every tap 1; burley: 0.9,
 * Burley's 1 - 0.9 r / R). Returns the weighted mean depth of the blocking
 * taps; `found` marks the lanes with one (weights stay >= 0.1 > 0). */
PN_FN pn_float hammersley_blocker_depth(PN_GLOBAL const float* depth, pn_dims map, DirectMap held, PcfBias b,
                                        PcfReceiver r,
                                        pn_float radius, int n, int uniform_density, pn_float cone_slope,
                                        float weight_falloff, pn_mask* found)
{
    pn_float weighted = 0.0f, total = 0.0f;
    DiscWalk walk = hammersley_walk(n, uniform_density);
    for (int k = 0; k < n; ++k) {
        const DiscTap t = hammersley_walk_next(&walk);
        const DiscSample s = hammersley_sample(depth, map, held, b, r, radius, t);
        const pn_mask blocks = s.depth < s.reference - cone_slope * t.radius * radius;
        const float weight = 1.0f - weight_falloff * t.radius;
        weighted = weighted + pn_select(blocks, weight * s.depth, 0.0f);
        total = total + pn_select(blocks, weight, 0.0f);
    }
    *found = total > 0.0f;
    return weighted / pn_select(*found, total, 1.0f);
}

/* Whether any lane of `lanes` has a disc of `radius` (texture units) with a
 * tap in a row that `held` does not hold (uniform). A tap's row lies between
 * those of v H - |radius| H and v H + |radius| H: |dy| <= 1, and each float
 * step of hammersley_sample is monotonic, so testing the two extremes is
 * exact. The whole map holds every row: no test. The CPU schedule sizes a
 * band for the blocker search's fixed radius; a filter disc that grew
 * beyond it sends its strip back to the whole map (PN_BAND_RERUN). */
PN_FN int hammersley_disc_leaves_band(DirectMap held, pn_dims map, PcfReceiver r, pn_float radius, pn_mask lanes)
{
    if (held.rows.height >= map.height) return 0;
    const float h = (float)map.height;
    const pn_float reach = pn_abs(radius) * h;
    const pn_float top = hammersley_texel(r.v * h - reach, map.height);
    const pn_float bottom = hammersley_texel(r.v * h + reach, map.height);
    const pn_mask inside =
        pn_and(top >= (float)held.first_row, bottom < (float)(held.first_row + held.rows.height));
    return pn_any(pn_and(lanes, pn_not(inside)));
}

/* The strip's result left to the schedule (see hammersley_disc_leaves_band). */
PN_FN void hammersley_store_rerun(PN_GLOBAL float* out, pn_dims d, int x, int y)
{
    const pn_float rerun = PN_BAND_RERUN;
    pn_store(out, d, x, y, rerun);
}

#endif
