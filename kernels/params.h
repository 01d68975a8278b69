/* Host/device shared parameter layouts of every kernel.
 *
 * This is the one file that both the host (C++) and the device (OpenCL C, and
 * the per-ISA CPU translation units) read, so the layouts cannot drift apart.
 * Members are only int and float (4 bytes each, no padding), so the host's
 * struct and the OpenCL kernel argument have the same bytes.
 */
#ifndef PENUMBRA_KERNEL_PARAMS_H
#define PENUMBRA_KERNEL_PARAMS_H

#ifdef __cplusplus
namespace penumbra {
#endif

/* An image's geometry in elements: planes of `height` rows of `pitch`
 * elements, of which the first `width` are pixels. */
typedef struct {
    int width;
    int height;
    int pitch;
    int plane_pitch;
} pn_dims;

/* Summed-area table of depth moments (kernels/moment_table.h).
 * The table stores inclusive sums S(x, y) = sum of m(i, j) for i <= x, j <= y;
 * row y lives at table + (y + 1) * pitch, so that row -1 (table + 0) is a zero
 * row and column -1 is the last padding element of the row before, also zero.
 * `table.width` and `table.height` are the map's size (not W + 1). */
typedef struct {
    pn_dims depth;     /* the depth map: one plane, values in [0, 1] */
    pn_dims table;     /* `moments` planes of inclusive sums */
    pn_dims columns;   /* column accumulators: `moments` planes, one row per band */
    int moments;       /* 2 (z, z^2) or 4 (z .. z^4) */
    int band_height;   /* rows per band in the banded (OpenCL) schedule */
} SatParams;

/* Chebyshev lookups (kernels/chebyshev.h, vsm.h, vssm.h). */
typedef struct {
    pn_dims table;          /* the moment table (see SatParams) */
    pn_dims receivers;      /* planes u, v, z */
    pn_dims out;            /* one plane: visibility */
    int radius;             /* vsm: box radius in texels */
    int max_radius;         /* vssm: largest filter radius the table allows (texels) */
    float min_variance;     /* variance floor, in depth^2 */
    float bleed;            /* light-bleeding reduction in [0, 1) */
    float light_size;       /* vssm: light width in texture units at the near plane */
    float exact_scale;      /* exact tables: 1 / 65535 (depth per quantization step) */
} ChebyshevParams;

#ifdef __cplusplus
}  /* namespace penumbra */
#endif

#endif
