/* Depth conventions: how a shadow map's texels and the receivers' z are
 * stored, and their conversion to the normalised linear depth every method
 * computes with, l = (d - near) / (far - near) in [0, 1] for a distance d from
 * the light along its axis (docs/integration.md, "Depth conventions").
 *
 *   PN_DEPTH_NORMALIZED  l itself (the library's contract before conventions):
 *                        returned as stored, bit for bit, no clamp.
 *   PN_DEPTH_LINEAR      the distance d in [near, far]:  l = (d - near) / (far - near).
 *   PN_DEPTH_PERSPECTIVE the hyperbolic depth a D3D / Vulkan projection matrix
 *                        writes into a [0, 1] depth buffer,
 *                            z = far (d - near) / (d (far - near)),
 *                        so that, with k = (far - near) / near,
 *                            l = z / (1 + k (1 - z)).
 *                        (Solve z for d: d = near far / (far - z (far - near));
 *                        then d - near = near z (far - near) / (far - z (far - near))
 *                        and far - z (far - near) = near (1 + k (1 - z)).)
 *   PN_DEPTH_REVERSED    reversed Z as D3D / Vulkan write it, z_r = 1 - z:
 *                            l = (1 - z_r) / (1 + k z_r).
 *
 * Both rational forms add positive terms only (no cancellation): l has a few
 * float roundings of relative error; what the convention itself loses is its
 * float32 storage (perspective depth crowds the far range into the last ulps
 * below 1), measured in tests/kernels/depth_convention_test.cpp.
 *
 * A stored value is first clamped into the convention's stored range [low,
 * high] ([0, 1], or [near, far] for linear; values outside it are refused by
 * the host or flagged by the kernels, depth_outside), so that no denominator
 * vanishes, and l into [0, 1] (a rounding above 1 is not a depth). Receivers'
 * z is converted by the same function: a receiver beyond the far plane
 * compares as at the far plane.
 *
 * dl/dz, for a receiver plane's slopes dz/du given in the stored convention
 * (chain rule), written in l so that the caller needs no stored value:
 *   linear 1 / (far - near); perspective (1 + k l)^2 / (1 + k); reversed -(1 + k l)^2 / (1 + k).
 * (From l = z / (1 + k (1 - z)): z = l (1 + k) / (1 + k l), and dl/dz =
 * (1 + k) / (1 + k (1 - z))^2 with 1 + k (1 - z) = (1 + k) / (1 + k l).)
 */
#ifndef PENUMBRA_DEPTH_CONVENTION_H
#define PENUMBRA_DEPTH_CONVENTION_H

/* Stored depths the conventions refuse: outside [low, high] (normalised:
 * [0, 1], so that a zeroed DepthConversion is today's contract), NaN and
 * infinities included. */
PN_FN pn_mask depth_outside(pn_float z, DepthConversion c)
{
    const float low = c.kind == PN_DEPTH_NORMALIZED ? 0.0f : c.low;
    const float high = c.kind == PN_DEPTH_NORMALIZED ? 1.0f : c.high;
    return pn_not(pn_and(z >= low, z <= high));
}

/* The conversion alone (top of this file), without the clamps: for a
 * stored value inside the range, l up to a rounding above 1; outside it, a
 * value outside [0, 1] or an infinity (a vanishing denominator), never NaN
 * unless the stored value is. For the per-texel loops that clamp l into [0, 1]
 * anyway and flag or refuse what lies outside the range (the table builds,
 * the direct window sums), where every operation on the way from the load
 * to the stores is paid. */
PN_FN pn_float depth_to_unclamped(pn_float z, DepthConversion c)
{
    if (c.kind == PN_DEPTH_NORMALIZED) return z;
    if (c.kind == PN_DEPTH_LINEAR) return (z - c.low) * c.scale;
    const pn_float far_side = c.kind == PN_DEPTH_PERSPECTIVE ? z : 1.0f - z;  /* grows with d */
    const pn_float near_side = c.kind == PN_DEPTH_PERSPECTIVE ? 1.0f - z : z; /* shrinks with d */
    return far_side / (1.0f + c.scale * near_side);
}

/* A strip of a stored map and its conversion (depth_to_unclamped), for the
 * exact and the 16-bit encoded table builds, which walk each row strip by
 * strip and read one strip ahead (depth_strip at PN_STRIP_AFTER(x)): the next
 * strip's conversion then runs beside the current strip's long chain (limbs,
 * scans, column sums) instead of heading it, where a rational convention's
 * division lengthened it. The float build's chain is short: there reading
 * ahead slowed the normalised path and gained nothing (docs/integration.md,
 * "Reading one strip ahead"). The strip read after a block's last is not
 * used; past the row's end it reads 0, as pn_load does. */
typedef struct {
    pn_float stored;
    pn_float unclamped;
} DepthStrip;

PN_FN DepthStrip depth_strip(PN_GLOBAL const float* depth, pn_dims d, int x, int y, DepthConversion c)
{
    DepthStrip s;
    s.stored = pn_load(depth, d, x, y);
    s.unclamped = depth_to_unclamped(s.stored, c);
    return s;
}

/* The conversion clamped into [0, 1], for stored values the caller checks or
 * flags (a map checked up front, a table build's flag): equal to
 * depth_to_normalized on every value in the range, one clamp fewer. */
PN_FN pn_float depth_checked_to_normalized(pn_float stored, DepthConversion c)
{
    if (c.kind == PN_DEPTH_NORMALIZED) return stored;
    return pn_clamp(depth_to_unclamped(stored, c), 0.0f, 1.0f);
}

/* Rows [y0, y1) of a stored, checked map (dims d) converted by
 * depth_checked_to_normalized into rows 0 .. y1 - y0 of `out` (dims o): the
 * CPU's direct window sums and soft discs convert the band of rows their
 * taps read once, not each texel once per tap (simd/cpu_direct_sums.cpp).
 * The per-tap arithmetic, so the same values: the discs' taps convert so;
 * the window sums' taps skip the clamp, which texel_values applies anyway
 * (kernels/moment_table.h), and a clamp applied twice is applied once. */
PN_FN void depth_convert_rows(PN_GLOBAL const float* depth, pn_dims d, PN_GLOBAL float* out, pn_dims o,
                              DepthConversion c, int y0, int y1)
{
    for (int y = y0; y < y1; ++y)
        PN_FOR_STRIPS(x, 0, d.width)
        {
            pn_store(out, o, x, y - y0, depth_checked_to_normalized(pn_load(depth, d, x, y), c));
        }
}

/* The map an entry reading a DirectMap (kernels/params.h) reads: `direct` as
 * the host or the CPU's band schedule set it, or, left zeroed (Params filled
 * by hand), the whole map of dims `map` in the receivers' convention `c`. */
PN_FN DirectMap direct_map(DirectMap direct, pn_dims map, DepthConversion c)
{
    if (direct.rows.height > 0) return direct;
    DirectMap whole;
    whole.rows = map;
    whole.first_row = 0;
    whole.convention = c;
    return whole;
}

/* The normalised linear depth of a stored value, clamped (top of this file):
 * pn_clamp(depth_to_unclamped(...), 0, 1) of every value in the range. */
PN_FN pn_float depth_to_normalized(pn_float stored, DepthConversion c)
{
    if (c.kind == PN_DEPTH_NORMALIZED) return stored;
    return depth_checked_to_normalized(pn_clamp(stored, c.low, c.high), c);
}

/* dl/dz at normalised depth l (top of this file): scales a receiver plane's
 * slopes from the stored convention's units into l's. */
PN_FN pn_float depth_slope_factor(pn_float l, DepthConversion c)
{
    if (c.kind == PN_DEPTH_NORMALIZED) return 1.0f;
    if (c.kind == PN_DEPTH_LINEAR) return c.scale;
    const pn_float grow = 1.0f + c.scale * l;
    const pn_float factor = grow * grow / (1.0f + c.scale);
    return c.kind == PN_DEPTH_PERSPECTIVE ? factor : -factor;
}

/* The stored value of normalised depth l, clamped into [0, 1] (the inverse
 * of depth_to_normalized): linear near + l (far - near); perspective
 * l (1 + k) / (1 + k l); reversed (1 - l) / (1 + k l). */
PN_FN pn_float depth_from_normalized(pn_float l, DepthConversion c)
{
    if (c.kind == PN_DEPTH_NORMALIZED) return l;
    const pn_float t = pn_clamp(l, 0.0f, 1.0f);
    if (c.kind == PN_DEPTH_LINEAR) return c.low + t * (c.high - c.low);
    const pn_float grow = 1.0f + c.scale * t;
    return c.kind == PN_DEPTH_PERSPECTIVE ? t * (1.0f + c.scale) / grow : (1.0f - t) / grow;
}

/* A comparison "normalised depth >= reference" moved into the stored
 * convention once per receiver, so that the taps are compared as stored
 * (every conversion is monotonic: increasing, or decreasing for reversed
 * Z, where the comparison turns): depth_lit(stored, depth_threshold(ref)).
 * A reference below 0 is met by every stored depth, one beyond 1 by none. */
PN_FN pn_float depth_threshold(pn_float reference, DepthConversion c)
{
    if (c.kind == PN_DEPTH_NORMALIZED) return reference;
    const float beyond = c.kind == PN_DEPTH_REVERSED ? -3.0e38f : 3.0e38f;
    return pn_select(reference <= 1.0f, depth_from_normalized(reference, c), beyond);
}

/* 1 where a stored depth meets a threshold of depth_threshold, else 0. */
PN_FN pn_float depth_lit(pn_float stored, pn_float threshold, DepthConversion c)
{
    const pn_mask lit = c.kind == PN_DEPTH_REVERSED ? stored <= threshold : stored >= threshold;
    return pn_select(lit, 1.0f, 0.0f);
}

/* A shadow map's texel (x, y) (y a row of the whole map), as normalised
 * depth, read from the rows `m` holds (clamped into them: a row they lack
 * reads their nearest); the map's range was checked up front (the
 * percentage-closer family's host). */
PN_FN pn_float depth_fetch(PN_GLOBAL const float* depth, DirectMap m, pn_int x, pn_int y)
{
    return depth_checked_to_normalized(pn_fetch_rows(depth, m.rows, m.first_row, x, y), m.convention);
}

#endif
