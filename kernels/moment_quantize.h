/* The optimized 16-bit quantization of four depth moments (Peters & Klein,
 * "Moment Shadow Mapping", I3D 2015, section "Quantization"; the transform
 * and offset for depth in [0, 1] from the paper's supplementary shader code).
 *
 * The power moments (z, z^2, z^3, z^4) of depths in [0, 1] are strongly
 * correlated: they fill a thin curved region of R^4, so rounding each to 16
 * bits moves them out of the set of valid moment vectors and the
 * reconstruction fails. The paper's affine map o = T m + (c, 0, 0, 0) was
 * optimized so that this region fills [0, 1]^4 evenly; each o_k is then
 * rounded to a 16-bit step (1/65535) and the rounding error, mapped back by
 * T^-1, stays small in the directions the reconstruction is sensitive to.
 *
 * Inputs: z in [0, 1] (a depth of the map). Outputs: encode gives four
 * values in [0, 1] (clamped: the exact map reaches -6.5e-8 for o_3); decode
 * takes four window means of encoded values and returns the means of z^k.
 * Measured (tests/kernels/moment_quantize_test.cpp): the decoded moments of one texel
 * are within 1.1e-5 of z^k for every 16-bit depth; T^-1 T = I to 4e-9. Both
 * matrices are the paper's; decode is linear, so it commutes with the box
 * filter: decoding a window mean is the mean of decoded texels.
 */
#ifndef PENUMBRA_MOMENT_QUANTIZE_H
#define PENUMBRA_MOMENT_QUANTIZE_H

#define PN_QUANTIZE_STEPS 65535.0f        /* 16-bit steps of an encoded value in [0, 1] */
#define PN_MSM_OFFSET 0.035955884801f     /* the paper's offset of o_1 */

/* The means of z, z^2, z^3, z^4 over a window (or one texel). */
typedef struct {
    pn_double b1, b2, b3, b4;
} FourMoments;

/* o = T m + (offset, 0, 0, 0), m = (z, z^2, z^3, z^4). Evaluated as it is
 * printed, each o_k sums terms up to 190 times larger than itself (the
 * coefficients reach 82), and float rounding moves a third of a 16-bit step.
 * The same polynomials rewritten about z = 1/2 (Taylor coefficients of the
 * paper's rows, offset included, to 10 digits) sum terms at most 8 times
 * larger: Horner's rule in t = z - 1/2. */
PN_FN pn_float msm_encode_row(pn_float t, float c0, float c1, float c2, float c3, float c4)
{
    return c0 + t * (c1 + t * (c2 + t * (c3 + t * c4)));
}

PN_FN void msm_encode_optimized(pn_float z, pn_float* o)
{
    const pn_float t = z - 0.5f;
    o[0] = msm_encode_row(t, 0.9483532233f, -1.5783509526f, -11.5640829984f, 10.1695802278f, 39.3703274134f);
    o[1] = msm_encode_row(t, 0.0745338949f, -1.8289821998f, 10.5382100949f, 11.3061685198f, -35.3649032570f);
    o[2] = msm_encode_row(t, 0.3288123159f, 1.8831981688f, 2.1352130235f, -3.9590426379f, -6.6543490743f);
    o[3] = msm_encode_row(t, 0.9498012486f, -0.0000000066f, 2.1939962105f, 0.0000000275f, -23.9728048165f);
    for (int k = 0; k < 4; ++k) o[k] = pn_clamp(o[k], 0.0f, 1.0f);
}

/* Rounds an encoded value in [0, 1] to its 16-bit step, as a float value. */
PN_FN pn_float msm_quantize_step(pn_float v)
{
    return pn_floor(v * PN_QUANTIZE_STEPS + 0.5f) * (1.0f / PN_QUANTIZE_STEPS);
}

/* m = T^-1 (o - (offset, 0, 0, 0)), rows of T^-1 as in the paper, in
 * double (the means come in double; the matrix is taken as printed). */
PN_FN FourMoments msm_decode_optimized(pn_double o1, pn_double o2, pn_double o3, pn_double o4)
{
    const pn_double u = o1 - 0.035955884801;
    FourMoments m;
    m.b1 = 0.2227744146 * u + 0.0771972861 * o2 + 0.7926986636 * o3 + 0.0319417555 * o4;
    m.b2 = 0.1549679261 * u + 0.1394629426 * o2 + 0.7963415838 * o3 - 0.1722823173 * o4;
    m.b3 = 0.1451988946 * u + 0.2120202157 * o2 + 0.7258694464 * o3 - 0.2758014811 * o4;
    m.b4 = 0.163127443 * u + 0.2591432266 * o2 + 0.6539092497 * o3 - 0.3376131734 * o4;
    return m;
}

#endif
