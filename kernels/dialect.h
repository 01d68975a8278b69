/* The penumbra kernel dialect: the contract every binding fulfils.
 *
 * A kernel description (a .h file in kernels/) is written in the common subset
 * of OpenCL C 1.2 and C++20, using only the vocabulary below. Three bindings
 * define it: cl/dialect_cl.h (OpenCL C, one work-item per pixel),
 * simd/dialect_simd.h (xsimd, one pixel per lane, compiled once per ISA) and
 * simd/dialect_scalar.h (plain C++, one lane: the readable oracle). A
 * description never names a lane count, an ISA, xsimd or OpenCL; tests grep
 * for it (DialectPurity in tests/kernels/kernel_table_test.cpp).
 *
 * Types
 *   pn_float, pn_int, pn_uint   per-pixel (per-lane) float, int32, uint32
 *   pn_mask                     per-pixel condition, from comparing pn_float
 *   float, int                  uniform values: parameters, loop counters, offsets
 *   uint                        32-bit unsigned scalar (storage element of exact tables)
 *   A uniform converts to a lane value implicitly (pn_float x = 0.0f).
 *   Unsigned arithmetic wraps modulo 2^32 in every binding.
 *
 * Functions and qualifiers
 *   PN_FN          before every function of a description
 *   PN_KERNEL      before an entry point (an OpenCL `kernel`)
 *   PN_GLOBAL      before a pointer into an image or buffer
 *
 * Arithmetic and math (float lanes; `pn_i...` for pn_int, `pn_u...` for pn_uint)
 *   + - * / and comparisons as usual; pn_min pn_max pn_clamp pn_abs pn_sqrt
 *   pn_floor pn_ceil pn_fma (the only fused operation, on every ISA with FMA;
 *   SSE4.2 has none and rounds twice; contraction is off
 *   everywhere else) pn_exp pn_log
 *   pn_select(mask, if_true, if_false) instead of a branch on a lane value
 *   pn_and pn_or pn_not on masks; pn_any(mask), pn_all(mask) give a uniform
 *   answer, for loops whose trip count differs per lane.
 *   pn_to_int(f) truncates; pn_int_to_float; pn_uint_to_float (exact rounding
 *   over the whole uint32 range); pn_float_to_uint(f) for f in [0, 2^31);
 *   pn_ushr(u, n) logical shift right by a uniform count.
 *   pn_ushl(u, n) shift left by a uniform count (wrapping, as all unsigned
 *   arithmetic); pn_as_uint(f) and pn_as_float(u) reinterpret the 32 bits of
 *   a lane (OpenCL's as_uint / as_float), for exponent-field arithmetic.
 *   Integer lanes as indices (a search through per-pixel arrays):
 *   pn_iless(a, b) the lanes where a < b (a pn_mask, so it combines with float
 *   conditions); pn_iselect(mask, a, b) per lane; pn_uint_to_index(u) a uint
 *   lane as an int index (u < 2^31: the same value).
 *
 * Double lanes (per-window moments formed before any float32 step; docs/dialect.md)
 *   pn_double, pn_dmask         per-pixel double and its condition; a pn_double
 *                               covers the same pixels as a pn_float (on SIMD two
 *                               halves of double batches: half the throughput)
 *   + - * / and comparisons on pn_double (with pn_double or double operands);
 *   pn_dmin pn_dmax pn_dclamp pn_dabs pn_dsqrt pn_dfloor pn_dexp pn_dselect;
 *   pn_dand pn_dor pn_dnot pn_dany pn_dfinite on pn_dmask.
 *   Conversions are explicit: pn_to_double(pn_float), pn_double_to_float (round
 *   to nearest), pn_int_to_double and pn_uint_to_double (exact over the whole
 *   range), pn_double_to_uint(d) (truncation, d in [0, 2^31)),
 *   pn_dmask_to_mask and pn_mask_to_dmask. Double literals (1.0, not 1.0f) keep
 *   arithmetic in double on every binding. OpenCL needs cl_khr_fp64: a device
 *   without it is refused with an Error before any program is built.
 *
 * Memory (images are planes described by a pn_dims, see kernels/params.h)
 *   PN_PLANE(ptr, dims, c)          pointer to plane c
 *   pn_load(plane, dims, x, y)      the strip of lanes starting at uniform (x, y);
 *                                   lanes at or past dims.width read 0
 *   pn_store(plane, dims, x, y, v)  the same strip; lanes past the width are not
 *                                   written (nothing is written past a row's end)
 *   pn_store_stream(...)            pn_store with a hint that the data will not be
 *                                   read again soon (non-temporal on SIMD)
 *   pn_fetch(plane, dims, x, y)     per-lane coordinates, clamp-to-edge: the one
 *                                   boundary helper
 *   pn_fetch_rows(plane, dims, first_row, x, y)  pn_fetch of a plane holding
 *                                   rows [first_row, first_row + height) of a
 *                                   taller image, y one of that image's rows
 *                                   (clamped into those held): on SIMD the same
 *                                   vector work per tap as pn_fetch, the row
 *                                   offset folded into the gather's base once
 *   pn_load_clamped(plane, dims, x, y)  the strip at uniform (x, y), clamp-to-edge:
 *                                   lane i reads column clamp(x + i, 0, width - 1)
 *                                   of row clamp(y, 0, height - 1); x and y may lie
 *                                   outside the image. A uniform-offset tap (a
 *                                   filter's neighbour at pn_x + dx): one
 *                                   contiguous load unless the strip crosses an edge
 *   pn_strips_inside(dims, x0, x1)  uniform: every lane of the strips starting at
 *                                   x0 .. x1 lies in [0, width) (x0 >= 0 and the
 *                                   strip at x1 ends within the row)
 *   pn_load_inside(plane, dims, x, y)  the strip at (x, y) with no check at all:
 *                                   for strips pn_strips_inside vouched for, with
 *                                   0 <= y < height (a filter's interior fast path)
 *   pn_gather(ptr, index)           per-lane element index; the caller guarantees
 *                                   it is in bounds (every lane, active or not)
 *   pn_uload pn_ustore pn_ustore_stream pn_ugather  the same for uint data
 *   pn_ugather_pair(ptr, index, &first, &second)  ptr[index] and ptr[index + 1]
 *                                   per lane (both in bounds): one 64-bit gather
 *                                   element per lane on SIMD instead of two
 *   pn_upair                        per-pixel pair of uint32 kept whole, as gathered
 *   pn_ugather_upair(ptr, index)    ptr[index] and ptr[index + 1] as one pn_upair
 *                                   (both in bounds); a - b wraps each part on its
 *                                   own; pn_upair_join(v) = first 2^16 + second as
 *                                   pn_double (exact: a limb pair's window sum)
 *   pn_ugather_upair_both(a, b, index, &from_a, &from_b)  pn_ugather_upair of two
 *                                   planes at the same indices (SIMD: per-lane loads,
 *                                   each lane's index extracted once for both)
 *   pn_ugather_upair2(ptr, index, &first, &second)  the pairs at index and
 *                                   index + 2 (16 contiguous bytes, all in bounds)
 *   pn_ugather_upair2_both(a, b, index, from_a, from_b)  pn_ugather_upair2 of two
 *                                   planes at the same indices into from_a[0..1] and
 *                                   from_b[0..1] (SIMD: each lane's index extracted once)
 *   PN_FRACTIONAL_ROWS_IN_ORDER     a schedule choice, 0 or 1: VSSM's filter reads
 *                                   its fractional window row by row, both values at
 *                                   once (1), or 16 corners per value (0); the same
 *                                   doubles either way (kernels/chebyshev.h)
 *   pn_ustore_pair_stream(plane, dims, x, y, first, second)  two strips
 *                                   interleaved: element 2 (y pitch + x + i) + 0 / + 1
 *                                   get lane i of first / second (lanes past the
 *                                   width not written); the limb tables' pair planes
 *   pn_uload_pair(plane, dims, x, y, &first, &second)  its inverse (lanes past the
 *                                   width read 0; not on a hot path)
 *
 * Input checks (a kernel validates the values it reads, so that checking
 * costs no extra pass over memory; the host reports the first bad value)
 *   pn_flag_any(flags, i, mask)     sets flags[i] to 1 if any lane of mask is set
 *   pn_finite(v)                    the lanes whose value is neither NaN nor infinite
 *
 * Row scans (for kernels that walk a row strip by strip)
 *   PN_FOR_STRIPS(x, begin, end)    for (x = begin; x < end; x += lane count)
 *   PN_STRIP_AFTER(x)               the first column of the strip after the one at x
 *                                   (x + lane count): to read a row one strip ahead
 *   pn_scan_add(v)                  inclusive prefix sum across the lanes of a strip
 *   pn_last(v)                      every lane gets the value of the last lane
 *   pn_last_value(v)                the last lane's value as a uniform float
 *   pn_uscan_add, pn_ulast, pn_ulast_value   the same, wrapping, for pn_uint
 *
 * Entry shapes (the bindings expand them)
 *   Per pixel: PN_KERNEL void name(<buffers>, const Params p, PN_PIXEL_ARGS)
 *              { PN_PIXEL_BEGIN(width, height); ... }
 *     defines int pn_x (first pixel of the strip), int pn_y (its row),
 *     pn_float pn_lane_x (each lane's x) and pn_mask pn_active (lanes inside
 *     the image). Loads and stores at (pn_x, pn_y) are the lanes' own pixels.
 *   Per task:  PN_KERNEL void name(<buffers>, const Params p, PN_TASK_ARGS)
 *              { PN_TASK_BEGIN(count); ... }   defines int pn_task in [0, count).
 *   The begin macro is an entry's first statement, and `count` is written
 *   inside it, not computed before it: the OpenCL backend launches every
 *   entry once with zeroed parameters and no tasks before it stores the
 *   program's binary (cl/opencl_prime.h), and then nothing but the bounds
 *   test may run (a zero divisor in `count` must not be reached).
 *
 * Helpers below are written in the dialect itself and so exist in every binding.
 */
#ifndef PENUMBRA_DIALECT_H
#define PENUMBRA_DIALECT_H

/* The element types of a moment table: float sums, or exact uint limbs
 * (kernels/moment_table.h). An entry that differs only in the table's type is
 * written once, as a macro M(variant, T) defining PN_KERNEL void
 * NAME_##variant(... PN_GLOBAL const T* table ...), calling helpers named
 * HELPER_##variant that take one argument list in both variants; then
 * PN_TABLE_VARIANTS(M) instantiates NAME_float and NAME_exact, the two entries
 * of kernels/kernel_table.h. */
#define PN_TABLE_VARIANTS(M) M(float, float) M(exact, uint)

/* The lane vocabulary of each variant's sums, so that a body over a table's
 * sums (a scan, a box query) is written once in such a macro: its lane type
 * pn_sum_##variant and pn_sum_load_, _store_, _gather_, _scan_, _last_##variant
 * (pn_load / pn_uload and so on; the uint ones wrap). */
typedef pn_float pn_sum_float;
typedef pn_uint pn_sum_exact;
#define pn_sum_load_float pn_load
#define pn_sum_load_exact pn_uload
#define pn_sum_store_float pn_store
#define pn_sum_store_exact pn_ustore
#define pn_sum_gather_float pn_gather
#define pn_sum_gather_exact pn_ugather
#define pn_sum_scan_float pn_scan_add
#define pn_sum_scan_exact pn_uscan_add
#define pn_sum_last_float pn_last
#define pn_sum_last_exact pn_ulast

/* Linear step: 0 at or below lo, 1 at or above hi, linear between. Used for
 * light-bleeding reduction (Lauritzen, GPU Gems 3 ch. 8). Requires lo < hi. */
PN_FN pn_float pn_linstep(float lo, float hi, pn_float v)
{
    return pn_clamp((v - lo) / (hi - lo), 0.0f, 1.0f);
}

PN_FN pn_float pn_saturate(pn_float v)
{
    return pn_clamp(v, 0.0f, 1.0f);
}

#endif
