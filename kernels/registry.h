/* The registry of kernel entry points: one X-macro list that drives the
 * OpenCL kernel objects (cl/opencl_backend.cpp), the CPU function tables
 * (simd/cpu_kernels.cpp) and a test that every entry exists on every backend.
 * Add an entry here when a description gains a PN_KERNEL.
 */
#ifndef PENUMBRA_REGISTRY_H
#define PENUMBRA_REGISTRY_H

#define PN_KERNEL_REGISTRY(X) \
    X(sat_bands_float)        \
    X(sat_bands_exact)        \
    X(sat_join_bands_float)   \
    X(sat_join_bands_exact)   \
    X(vsm_float)              \
    X(vsm_exact)              \
    X(vssm_float)             \
    X(vssm_exact)             \
    X(bilateral_full)         \
    X(bilateral_horizontal)   \
    X(bilateral_vertical)     \
    X(sdf_grid)               \
    X(sdf_analytic)           \
    X(encoded_bands_float)    \
    X(encoded_bands_exact)    \
    X(msm_float)              \
    X(msm_exact)              \
    X(msm_soft_float)         \
    X(msm_soft_exact)         \
    X(evsm_float)             \
    X(evsm_exact)

#endif
