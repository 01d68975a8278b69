/* The exponential warps of exponential variance shadow maps (EVSM: Lauritzen
 * & McCool, "Layered variance shadow maps", GI 2008, section 4; Lauritzen's
 * thesis, 2007): depth z in [0, 1] is stored as
 *     w+(z) = e^{c+ (z - 1)}   and   w-(z) = -e^{-c- z}
 * with their squares, and the Chebyshev bound is applied to each warped
 * variable. Both warps are increasing in z, so P(w(Z) >= w(z)) = P(Z >= z);
 * the steep exponential squeezes the depths in front of the receiver
 * together, which is what reduces light leaking.
 *
 * Normalisation: the usual warp is e^{c+ z}; dividing it by e^{c+} keeps
 * every stored value in (0, 1] (the squares down to e^{-2 c+}), so float
 * sums over a whole map cannot overflow and exact tables can quantize the
 * values to 16-bit steps. The Chebyshev bound is invariant under scaling of
 * the variable (the variance and the squared distance scale alike), so this
 * changes no result. The negative warp is stored as e^{-c- z} (positive) and
 * negated when read.
 *
 * Storage limits on the exponents (the host enforces them; docs/moments.md):
 *  - 16-bit values (exact tables, steps of 1/65535): the smallest square,
 *    e^{-2c} at the far end of the warp, must still be one step:
 *    c <= ln(65535) / 2 = 5.545 (the same bound as fp16's largest value,
 *    65504, gives the literature's 5.54);
 *  - 32-bit floats: e^{-2c} must stay a normal float (2^-126), c <= 43.67;
 *    the literature uses 42, which also leaves summation headroom.
 * Slope: dw+/dz = c+ w+, d(w-)/dz = c- e^{-c- z}; the variance floor is
 * scaled by the slope's square at the receiver (a depth spread s is a warped
 * spread s |w'|).
 */
#ifndef PENUMBRA_EXPONENTIAL_WARP_H
#define PENUMBRA_EXPONENTIAL_WARP_H

PN_FN pn_float evsm_positive_warp(pn_float z, float c)
{
    return pn_exp(c * (z - 1.0f));
}

/* e^{-c z}: the negative warp's magnitude (the warp is its negation). */
PN_FN pn_float evsm_negative_magnitude(pn_float z, float c)
{
    return pn_exp(-c * z);
}

/* The stored channels of one texel: w+, w+^2, then (4 channels) |w-|, w-^2. */
PN_FN void evsm_encode(pn_float z, float c_positive, float c_negative, int channels, pn_float* v)
{
    v[0] = evsm_positive_warp(z, c_positive);
    v[1] = v[0] * v[0];
    if (channels == 4) {
        v[2] = evsm_negative_magnitude(z, c_negative);
        v[3] = v[2] * v[2];
    }
}

#endif
