/* The kernel table: every entry point of the kernel descriptions, once.
 *
 * X(family, name, shape, Params, (buffers...)) per entry, where
 *  - family: the OpenCL source the entry's program is built from (the files
 *    the family needs; one program per entry, built on first use) and the
 *    CPU backend's file for it;
 *  - name:   the PN_KERNEL function of the descriptions that implements it;
 *  - shape:  pixel (its last arguments are Params p, then the pixel x, y)
 *            or task (Params p, then the task index);
 *  - buffers, in argument order: PN_IN(T) (read), PN_OUT(T) (written),
 *    PN_INOUT(T) (read and written), PN_SOURCE(T) (read: the source of a
 *    lookup-shaped entry, one buffer or several arrays, before its
 *    receivers; host/backend/kernel_id.h), T one of float, uint, int; a
 *    consumer defines PN_IN, PN_OUT, PN_INOUT and PN_SOURCE before it
 *    expands the table.
 *
 * From this list and from nothing else come the CPU function tables of every
 * ISA (simd/), the OpenCL kernel objects and their argument binding (cl/) and
 * the typed identifier the host names a kernel by (host/backend/kernel_id.h).
 * A table entry that a backend does not define fails that backend's build.
 *
 * This header holds macros only, so it may be included by C++ and by the
 * build's embed step; it is not part of the OpenCL program.
 */
#ifndef PENUMBRA_KERNEL_TABLE_H
#define PENUMBRA_KERNEL_TABLE_H

/* The families, each an OpenCL program of its own. */
#define PN_KERNEL_FAMILIES(F) F(moment_table) F(chebyshev) F(bilateral) F(sdf) F(moments) F(pcf) F(ambient) F(dsm) F(ssao) F(pismo)

#define PN_KERNEL_TABLE(X)                                                                                  \
    X(moment_table, sat_bands_float, task, SatParams,                                                    \
      (PN_IN(float), PN_OUT(float), PN_OUT(float), PN_OUT(float), PN_OUT(int)))                             \
    X(moment_table, sat_bands_exact, task, SatParams,                                                    \
      (PN_IN(float), PN_OUT(uint), PN_OUT(uint), PN_OUT(uint), PN_OUT(int)))                                \
    X(moment_table, sat_join_bands_float, pixel, SatParams, (PN_INOUT(float), PN_IN(float)))             \
    X(moment_table, sat_join_bands_exact, pixel, SatParams, (PN_INOUT(uint), PN_IN(uint)))               \
    X(chebyshev, vsm_float, pixel, ChebyshevParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int))) \
    X(chebyshev, vsm_exact, pixel, ChebyshevParams, (PN_SOURCE(uint), PN_IN(float), PN_OUT(float), PN_OUT(int)))  \
    X(chebyshev, vsm_direct, pixel, ChebyshevParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int))) \
    X(chebyshev, vssm_float, pixel, ChebyshevParams,                                                     \
      (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))                                             \
    X(chebyshev, vssm_exact, pixel, ChebyshevParams, (PN_SOURCE(uint), PN_IN(float), PN_OUT(float), PN_OUT(int))) \
    X(bilateral, bilateral_full, pixel, BilateralParams,                                                 \
      (PN_IN(float), PN_IN(float), PN_IN(float), PN_IN(int), PN_IN(float), PN_OUT(float), PN_OUT(int)))     \
    X(bilateral, bilateral_horizontal, pixel, BilateralParams,                                           \
      (PN_IN(float), PN_IN(float), PN_IN(float), PN_IN(int), PN_IN(float), PN_OUT(float), PN_OUT(int)))     \
    X(bilateral, bilateral_vertical, pixel, BilateralParams,                                             \
      (PN_IN(float), PN_IN(float), PN_IN(float), PN_IN(int), PN_IN(float), PN_OUT(float)))                  \
    X(sdf, sdf_grid, pixel, SdfParams, (PN_IN(float), PN_IN(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))     \
    X(sdf, sdf_analytic, pixel, SdfParams, (PN_IN(float), PN_IN(float), PN_IN(float), PN_OUT(float), PN_OUT(int))) \
    X(moments, encoded_bands_float, task, EncodedSatParams, (PN_IN(float), PN_OUT(float), PN_OUT(float), PN_OUT(int))) \
    X(moments, encoded_bands_exact, task, EncodedSatParams, (PN_IN(float), PN_OUT(uint), PN_OUT(uint), PN_OUT(int)))   \
    X(moments, msm_float, pixel, MomentParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))       \
    X(moments, msm_exact, pixel, MomentParams, (PN_SOURCE(uint), PN_IN(float), PN_OUT(float), PN_OUT(int)))        \
    X(moments, msm_direct, pixel, MomentParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))      \
    X(moments, msm_soft_float, pixel, MomentParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))  \
    X(moments, msm_soft_exact, pixel, MomentParams, (PN_SOURCE(uint), PN_IN(float), PN_OUT(float), PN_OUT(int)))   \
    X(moments, evsm_float, pixel, MomentParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))      \
    X(moments, evsm_exact, pixel, MomentParams, (PN_SOURCE(uint), PN_IN(float), PN_OUT(float), PN_OUT(int)))      \
    X(moments, evsm_direct, pixel, MomentParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))     \
    X(pcf, pcf, pixel, PcfParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))                   \
    X(pcf, pcf_gather, pixel, PcfParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))            \
    X(pcf, pcf_gauss, pixel, PcfParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))             \
    X(pcf, pcf_disc, pixel, PcfParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))             \
    X(pcf, pcss, pixel, SoftPcfParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))              \
    X(pcf, burley, pixel, SoftPcfParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))            \
    X(pcf, cascade_mask, pixel, CascadeParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))      \
    X(ambient, ambient_sh, pixel, AmbientParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))    \
    X(ambient, ambient_volumes, pixel, AmbientParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int))) \
    X(dsm, dsm_lookup, pixel, DsmParams,                                                                   \
      (PN_SOURCE(uint), PN_SOURCE(float), PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))     \
    X(ssao, ssao_vo, pixel, SsaoParams, (PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))      \
    X(pismo, pismo_estimates, pixel, PismoParams,                                                          \
      (PN_SOURCE(uint), PN_SOURCE(float), PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))     \
    X(pismo, pismo_visibility, pixel, PismoParams,                                                         \
      (PN_SOURCE(uint), PN_SOURCE(float), PN_SOURCE(float), PN_SOURCE(float), PN_SOURCE(uint), PN_SOURCE(float), \
       PN_SOURCE(float), PN_IN(float), PN_OUT(float), PN_OUT(int)))

#endif
