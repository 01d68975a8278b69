/* OpenCL C binding of the kernel dialect (kernels/dialect.h): one work-item
 * per pixel, so a "lane" is a scalar and a strip is one pixel.
 *
 * Prepended to the kernel descriptions when the program is embedded (see
 * cmake/embed_kernels.cmake). Keep the semantics identical to
 * simd/dialect_scalar.h (the oracle) and simd/dialect_simd.h. Contraction is
 * off, as -ffp-contract=off is on the CPU side: a * b + c never fuses unless a
 * description says pn_fma.
 */
#pragma OPENCL FP_CONTRACT OFF
/* Double lanes need fp64; the host refuses a device without it before it
 * builds the program (cl/opencl_runtime.cpp). */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable

typedef float pn_float;
typedef int pn_int;
typedef uint pn_uint;
typedef int pn_mask;

#define PN_FN static inline
#define PN_KERNEL kernel

/* One program per kernel entry (cl/opencl_programs.h): the embed step writes
 * every entry of the family as PN_ENTRY(name), and the program's source
 * starts with `#define PN_ENTRY_IS_<its entry> ~, kernel`. PN_ENTRY(name) is
 * `kernel` for that name and nothing for the family's other entries, so PoCL
 * compiles one kernel per program, not the family's all. The others stay
 * plain (emitted) functions, not static ones, because LLVM inlines a static
 * helper by how many callers it has: as the vertical pass's only caller,
 * bilateral_taps inlined differently and bilateral_vertical ran 1.4 to 1.7
 * times slower (docs/opencl_startup.md). The test is the preprocessor's
 * argument-count probe: a defined PN_ENTRY_IS_name shifts `kernel` into the
 * second place, an undefined one leaves the empty argument there. */
#define PN_ENTRY_SECOND(first, second, ...) second
#define PN_ENTRY_PROBE(...) PN_ENTRY_SECOND(__VA_ARGS__, , ~)
#define PN_ENTRY(name) PN_ENTRY_PROBE(PN_ENTRY_IS_##name)
#define PN_GLOBAL global
#define PN_LANES 1
#define PN_FRACTIONAL_ROWS_IN_ORDER 0 /* kernels/dialect.h; not measured on OpenCL */

PN_FN float pn_min(float a, float b) { return a < b ? a : b; }
PN_FN float pn_max(float a, float b) { return a > b ? a : b; }
PN_FN float pn_clamp(float v, float lo, float hi) { return pn_min(pn_max(v, lo), hi); }
PN_FN float pn_abs(float v) { return fabs(v); }
PN_FN float pn_sqrt(float v) { return sqrt(v); }
PN_FN float pn_floor(float v) { return floor(v); }
PN_FN float pn_ceil(float v) { return ceil(v); }
PN_FN float pn_fma(float a, float b, float c) { return fma(a, b, c); }
PN_FN float pn_exp(float v) { return exp(v); }
PN_FN float pn_log(float v) { return log(v); }
PN_FN float pn_select(int m, float a, float b) { return m ? a : b; }
PN_FN int pn_and(int a, int b) { return a && b; }
PN_FN int pn_or(int a, int b) { return a || b; }
PN_FN int pn_not(int a) { return !a; }
PN_FN int pn_any(int m) { return m; }
PN_FN int pn_all(int m) { return m; }

PN_FN int pn_imin(int a, int b) { return a < b ? a : b; }
PN_FN int pn_imax(int a, int b) { return a > b ? a : b; }
PN_FN int pn_iclamp(int v, int lo, int hi) { return pn_imin(pn_imax(v, lo), hi); }
PN_FN int pn_to_int(float v) { return (int)v; }
PN_FN float pn_int_to_float(int v) { return (float)v; }
PN_FN float pn_uint_to_float(uint v) { return (float)v; }
PN_FN uint pn_float_to_uint(float v) { return (uint)(int)v; }
PN_FN int pn_iless(int a, int b) { return a < b; }
PN_FN int pn_iselect(int m, int a, int b) { return m ? a : b; }
PN_FN int pn_uint_to_index(uint u) { return (int)u; }
PN_FN uint pn_ushr(uint v, int n) { return v >> n; }
PN_FN uint pn_ushl(uint v, int n) { return v << n; }
PN_FN uint pn_as_uint(float v) { return as_uint(v); }
PN_FN float pn_as_float(uint v) { return as_float(v); }

/* Double lanes (kernels/dialect.h): a scalar double per work-item. */
typedef double pn_double;
typedef int pn_dmask;
PN_FN double pn_to_double(float v) { return (double)v; }
PN_FN float pn_double_to_float(double v) { return (float)v; }
PN_FN double pn_int_to_double(int v) { return (double)v; }
PN_FN double pn_uint_to_double(uint v) { return (double)v; }
PN_FN uint pn_double_to_uint(double v) { return (uint)(int)v; }
PN_FN double pn_dmin(double a, double b) { return a < b ? a : b; }
PN_FN double pn_dmax(double a, double b) { return a > b ? a : b; }
PN_FN double pn_dclamp(double v, double lo, double hi) { return pn_dmin(pn_dmax(v, lo), hi); }
PN_FN double pn_dabs(double v) { return fabs(v); }
PN_FN double pn_dsqrt(double v) { return sqrt(v); }
PN_FN double pn_dfloor(double v) { return floor(v); }
PN_FN double pn_dexp(double v) { return exp(v); }
PN_FN double pn_dselect(int m, double a, double b) { return m ? a : b; }
PN_FN int pn_dand(int a, int b) { return a && b; }
PN_FN int pn_dor(int a, int b) { return a || b; }
PN_FN int pn_dnot(int a) { return !a; }
PN_FN int pn_dany(int m) { return m; }
PN_FN int pn_dfinite(double v) { return v - v == 0.0; }
PN_FN int pn_dmask_to_mask(int m) { return m; }
PN_FN int pn_mask_to_dmask(int m) { return m; }

#define PN_PLANE(ptr, dims, c) ((ptr) + (size_t)(c) * (size_t)(dims).plane_pitch)

PN_FN size_t pn_index(pn_dims d, int x, int y) { return (size_t)y * (size_t)d.pitch + (size_t)x; }

PN_FN float pn_load(global const float* plane, pn_dims d, int x, int y) { return x < d.width ? plane[pn_index(d, x, y)] : 0.0f; }
PN_FN void pn_store(global float* plane, pn_dims d, int x, int y, float v) { if (x < d.width) plane[pn_index(d, x, y)] = v; }
PN_FN void pn_store_stream(global float* plane, pn_dims d, int x, int y, float v) { pn_store(plane, d, x, y, v); }
PN_FN float pn_gather(global const float* ptr, int index) { return ptr[index]; }
PN_FN float pn_fetch(global const float* plane, pn_dims d, int x, int y)
{
    return plane[pn_index(d, pn_iclamp(x, 0, d.width - 1), pn_iclamp(y, 0, d.height - 1))];
}
PN_FN float pn_fetch_rows(global const float* plane, pn_dims d, int first_row, int x, int y)
{
    return pn_fetch(plane, d, x, pn_iclamp(y, first_row, first_row + d.height - 1) - first_row);
}
PN_FN float pn_load_clamped(global const float* plane, pn_dims d, int x, int y) { return pn_fetch(plane, d, x, y); }
PN_FN int pn_strips_inside(pn_dims d, int x0, int x1) { return x0 >= 0 && x1 < d.width; }
PN_FN float pn_load_inside(global const float* plane, pn_dims d, int x, int y) { return plane[pn_index(d, x, y)]; }
PN_FN uint pn_uload(global const uint* plane, pn_dims d, int x, int y) { return x < d.width ? plane[pn_index(d, x, y)] : 0u; }
PN_FN void pn_ustore(global uint* plane, pn_dims d, int x, int y, uint v) { if (x < d.width) plane[pn_index(d, x, y)] = v; }
PN_FN void pn_ustore_stream(global uint* plane, pn_dims d, int x, int y, uint v) { pn_ustore(plane, d, x, y, v); }
PN_FN uint pn_ugather(global const uint* ptr, int index) { return ptr[index]; }
/* One 8-byte load (vload2 needs only the element's alignment). */
PN_FN void pn_ugather_pair(global const uint* ptr, int index, uint* first, uint* second)
{
    const uint2 pair = vload2(0, ptr + index);
    *first = pair.x;
    *second = pair.y;
}
/* A pair kept whole (kernels/dialect.h): OpenCL's uint2, whose - wraps per
 * component. The join is exact (both products and the sum below 2^49). */
typedef uint2 pn_upair;
PN_FN pn_upair pn_ugather_upair(global const uint* ptr, int index) { return vload2(0, ptr + index); }
PN_FN void pn_ugather_upair_both(global const uint* a, global const uint* b, int index, pn_upair* from_a,
                                 pn_upair* from_b)
{
    *from_a = vload2(0, a + index);
    *from_b = vload2(0, b + index);
}
/* One 16-byte load (vload4 needs only the element's alignment). */
PN_FN void pn_ugather_upair2(global const uint* ptr, int index, pn_upair* first, pn_upair* second)
{
    const uint4 v = vload4(0, ptr + index);
    *first = v.xy;
    *second = v.zw;
}
PN_FN void pn_ugather_upair2_both(global const uint* a, global const uint* b, int index,
                                  pn_upair* from_a, pn_upair* from_b)
{
    pn_ugather_upair2(a, index, &from_a[0], &from_a[1]);
    pn_ugather_upair2(b, index, &from_b[0], &from_b[1]);
}
PN_FN double pn_upair_join(pn_upair v) { return (double)v.x * 65536.0 + (double)v.y; }

PN_FN void pn_ustore_pair_stream(global uint* plane, pn_dims d, int x, int y, uint first, uint second)
{
    if (x >= d.width) return;
    plane[2 * pn_index(d, x, y)] = first;
    plane[2 * pn_index(d, x, y) + 1] = second;
}
PN_FN void pn_uload_pair(global const uint* plane, pn_dims d, int x, int y, uint* first, uint* second)
{
    *first = x < d.width ? plane[2 * pn_index(d, x, y)] : 0u;
    *second = x < d.width ? plane[2 * pn_index(d, x, y) + 1] : 0u;
}

/* Many work-items may raise the same flag; all write the same value, 1. */
PN_FN void pn_flag_any(global int* flags, int i, int m) { if (m) flags[i] = 1; }
PN_FN int pn_finite(float v) { return v - v == 0.0f; }

#define PN_FOR_STRIPS(x, begin, end) for (int x = (begin); x < (end); ++x)
#define PN_STRIP_AFTER(x) ((x) + 1)
PN_FN float pn_scan_add(float v) { return v; }
PN_FN float pn_last(float v) { return v; }
PN_FN uint pn_uscan_add(uint v) { return v; }
PN_FN uint pn_ulast(uint v) { return v; }
PN_FN float pn_last_value(float v) { return v; }
PN_FN uint pn_ulast_value(uint v) { return v; }

/* Per pixel: the global id is the pixel; rows may be launched in chunks, so
 * the host passes the first row of the launch. */
#define PN_PIXEL_ARGS int pn_row_offset
#define PN_PIXEL_BEGIN(width, height)                         \
    const int pn_x = (int)get_global_id(0);                   \
    const int pn_y = (int)get_global_id(1) + pn_row_offset;   \
    if (pn_x >= (width) || pn_y >= (height)) return;          \
    const float pn_lane_x = (float)pn_x;                      \
    const int pn_active = 1;                                  \
    (void)pn_lane_x;                                          \
    (void)pn_active
/* The launch's count is tested first: a work-item past it (the launch
 * rounds up to whole work-groups, cl/opencl_work_groups.h; a launch of no
 * tasks, cl/opencl_prime.h, has only such work-items) returns before the
 * kernel's own count, whose parameters may then be zeros, is evaluated. */
#define PN_TASK_ARGS int pn_task_count
#define PN_TASK_BEGIN(count)                                  \
    const int pn_task = (int)get_global_id(0);                \
    if (pn_task >= pn_task_count || pn_task >= (count)) return
