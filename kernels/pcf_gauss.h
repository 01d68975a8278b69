/* Percentage-closer filtering on an n x n grid of Gaussian-weighted bilinear
 * taps: Toy Story 3's "4x4 Gaussian PCF" (Siggraph 2010 course notes, after
 * Andersson et al. 2009) for n = 4, and the same filter sized for other n.
 *
 * In texel space (texel k's centre at k), the receiver sits at
 * (u W - 1/2, v H - 1/2); tap (i, j), 0 <= i, j < n, sits at the receiver plus
 * (i - (n-1)/2, j - (n-1)/2), one texel apart. A tap is a bilinear PCF: the
 * four texels around it are compared (kernels/depth_bias.h) and their results
 * weighed bilinearly, as hardware shadow samplers do. Tap (i, j) weighs
 * g_i g_j, with g_i = exp(-(i - (n-1)/2)^2 / (2 sigma^2)) / sum_k exp(...):
 * the grid's separable, normalised Gaussian; sigma is in texels.
 *
 * All taps share the fractional position f of the first one, so the taps'
 * bilinear footprints tile an (n+1) x (n+1) block of texels (5 x 5 for n = 4:
 * the notes' "two pass 5x5 gaussian filter, but with a depth test on each
 * pixel fetched"). Each texel of the block is compared once and weighs
 *     w_x(k) w_y(l),  w_x(k) = g_k (1 - f_x) + g_{k-1} f_x,  k = 0 .. n
 * (g_{-1} = g_n = 0), exactly what the n^2 bilinear taps give; the weights sum
 * to 1. Texels outside the map are read clamp-to-edge (a sampler's
 * CLAMP_TO_EDGE); the receiver-plane bias uses the texel actually read.
 * Output in [0, 1].
 */
#ifndef PENUMBRA_PCF_GAUSS_H
#define PENUMBRA_PCF_GAUSS_H

/* The footprint's weights along one axis: w[k], k = 0 .. n, for the first
 * tap's fractional position f; g (n entries) is the normalised Gaussian. */
PN_FN void pcf_gauss_axis_weights(const pn_float* g, int n, pn_float f, pn_float* w)
{
    for (int k = 0; k <= n; ++k) {
        pn_float weight = 0.0f;
        if (k < n) weight = weight + g[k] * (1.0f - f);
        if (k > 0) weight = weight + g[k - 1] * f;
        w[k] = weight;
    }
}

/* g_i for the grid side n and sigma, normalised to sum 1 (lanes all equal). */
PN_FN void pcf_gauss_taps(int n, float sigma, pn_float* g)
{
    const float centre = 0.5f * (float)(n - 1), scale = -0.5f / (sigma * sigma);
    pn_float sum = 0.0f;
    for (int i = 0; i < n; ++i) {
        const float t = (float)i - centre;
        const pn_float e = t * t * scale;
        g[i] = pn_exp(e);
        sum = sum + g[i];
    }
    for (int i = 0; i < n; ++i) g[i] = g[i] / sum;
}

PN_KERNEL void pcf_gauss(PN_GLOBAL const float* depth, PN_GLOBAL const float* receivers, PN_GLOBAL float* out,
                         PN_GLOBAL int* bad_rows, const PcfParams p, PN_PIXEL_ARGS)
{
    PN_PIXEL_BEGIN(p.out.width, p.out.height);
    const PcfReceiver r =
        pcf_load_receiver(receivers, p.receivers, p.depth, p.bias, p.convention, pn_x, pn_y, bad_rows);
    const int n = p.grid;
    pn_float g[PN_PCF_MAX_GRID], wx[PN_PCF_MAX_GRID + 1], wy[PN_PCF_MAX_GRID + 1];
    pcf_gauss_taps(n, p.sigma, g);
    /* The first tap's texel-space position, its texel and its fraction. */
    const float first = -0.5f - 0.5f * (float)(n - 1);
    const pn_float fx = r.u * (float)p.depth.width + first, fy = r.v * (float)p.depth.height + first;
    const pn_float x0 = pn_floor(fx), y0 = pn_floor(fy);
    pcf_gauss_axis_weights(g, n, fx - x0, wx);
    pcf_gauss_axis_weights(g, n, fy - y0, wy);
    const float w = (float)p.depth.width - 1.0f, h = (float)p.depth.height - 1.0f;
    pn_float visibility = 0.0f;
    for (int l = 0; l <= n; ++l) {
        const pn_float ty = pn_clamp(y0 + (float)l, 0.0f, h);
        pn_float row = 0.0f;
        for (int k = 0; k <= n; ++k) {
            const pn_float tx = pn_clamp(x0 + (float)k, 0.0f, w);
            const pn_float d = pn_fetch(depth, p.depth, pn_to_int(tx), pn_to_int(ty));
            row = row + wx[k] * pcf_tap_lit(d, r, p.bias, p.convention, p.depth, tx, ty);
        }
        visibility = visibility + wy[l] * row;
    }
    pn_store(out, p.out, pn_x, pn_y, pn_clamp(visibility, 0.0f, 1.0f));
}

#endif
