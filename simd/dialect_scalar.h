// Scalar binding of the kernel dialect (kernels/dialect.h): one lane, plain C++.
//
// The readable oracle of the dialect and the debug path: every operation is the
// obvious one. Included inside the namespace penumbra::cpu::scalar by
// simd/cpu_kernels.cpp, after <cmath>, <cstdint> and <cstring>.
// Keep the semantics identical to simd/dialect_simd.h and cl/dialect_cl.h.

using pn_float = float;
using pn_int = std::int32_t;
using pn_uint = std::uint32_t;
using pn_mask = bool;
using uint = std::uint32_t;

// Every description function is inlined, as on SIMD: the builds' literal value
// and limb counts (sat_block_exact) specialise only a loop that is inlined, and
// GCC stopped inlining the exact build's once it read one strip ahead (1.55x
// slower; docs/integration.md, "Reading one strip ahead").
#define PN_FN static inline __attribute__((always_inline))
#define PN_KERNEL static inline
#define PN_GLOBAL
#define PN_LANES 1
/* The readable oracle takes the row-order path (kernels/dialect.h), so that
 * the backends' agreement tests compare it bit for bit with the corner path. */
#define PN_FRACTIONAL_ROWS_IN_ORDER 1

inline constexpr int kLanes = 1;

PN_FN float pn_min(float a, float b) { return a < b ? a : b; }
PN_FN float pn_max(float a, float b) { return a > b ? a : b; }
PN_FN float pn_clamp(float v, float lo, float hi) { return pn_min(pn_max(v, lo), hi); }
PN_FN float pn_abs(float v) { return std::fabs(v); }
PN_FN float pn_sqrt(float v) { return std::sqrt(v); }
PN_FN float pn_floor(float v) { return std::floor(v); }
PN_FN float pn_ceil(float v) { return std::ceil(v); }
PN_FN float pn_fma(float a, float b, float c) { return std::fma(a, b, c); }
PN_FN float pn_exp(float v) { return std::exp(v); }
PN_FN float pn_log(float v) { return std::log(v); }
PN_FN float pn_select(bool m, float a, float b) { return m ? a : b; }
PN_FN bool pn_and(bool a, bool b) { return a && b; }
PN_FN bool pn_or(bool a, bool b) { return a || b; }
PN_FN bool pn_not(bool a) { return !a; }
PN_FN bool pn_any(bool m) { return m; }
PN_FN bool pn_all(bool m) { return m; }

PN_FN std::int32_t pn_imin(std::int32_t a, std::int32_t b) { return a < b ? a : b; }
PN_FN std::int32_t pn_imax(std::int32_t a, std::int32_t b) { return a > b ? a : b; }
PN_FN std::int32_t pn_iclamp(std::int32_t v, std::int32_t lo, std::int32_t hi) { return pn_imin(pn_imax(v, lo), hi); }
// Out of range (and NaN) gives INT32_MIN, as the SIMD conversion instructions
// do, instead of C++'s undefined behaviour: kernels may meet such values in
// inputs they flag as bad.
PN_FN std::int32_t pn_to_int(float v)
{
    return v >= -2147483648.0f && v < 2147483648.0f ? static_cast<std::int32_t>(v) : INT32_MIN;
}
PN_FN float pn_int_to_float(std::int32_t v) { return static_cast<float>(v); }
PN_FN float pn_uint_to_float(std::uint32_t v) { return static_cast<float>(v); }
PN_FN std::uint32_t pn_float_to_uint(float v) { return static_cast<std::uint32_t>(pn_to_int(v)); }
PN_FN bool pn_iless(std::int32_t a, std::int32_t b) { return a < b; }
PN_FN std::int32_t pn_iselect(bool m, std::int32_t a, std::int32_t b) { return m ? a : b; }
PN_FN std::int32_t pn_uint_to_index(std::uint32_t u) { return static_cast<std::int32_t>(u); }
PN_FN std::uint32_t pn_ushr(std::uint32_t v, int n) { return v >> n; }
PN_FN std::uint32_t pn_ushl(std::uint32_t v, int n) { return v << n; }
PN_FN std::uint32_t pn_as_uint(float v)
{
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return bits;
}
PN_FN float pn_as_float(std::uint32_t v)
{
    float value;
    std::memcpy(&value, &v, sizeof value);
    return value;
}

// Double lanes (kernels/dialect.h, "Double lanes"): plain double and bool.
using pn_double = double;
using pn_dmask = bool;
PN_FN double pn_to_double(float v) { return double(v); }
PN_FN float pn_double_to_float(double v) { return float(v); }
PN_FN double pn_int_to_double(std::int32_t v) { return double(v); }
PN_FN double pn_uint_to_double(std::uint32_t v) { return double(v); }
// Truncation of a value in [0, 2^31), as the SIMD conversions do.
PN_FN std::uint32_t pn_double_to_uint(double v) { return std::uint32_t(std::int32_t(v)); }
PN_FN double pn_dmin(double a, double b) { return a < b ? a : b; }
PN_FN double pn_dmax(double a, double b) { return a > b ? a : b; }
PN_FN double pn_dclamp(double v, double lo, double hi) { return pn_dmin(pn_dmax(v, lo), hi); }
PN_FN double pn_dabs(double v) { return std::fabs(v); }
PN_FN double pn_dsqrt(double v) { return std::sqrt(v); }
PN_FN double pn_dfloor(double v) { return std::floor(v); }
PN_FN double pn_dexp(double v) { return std::exp(v); }
PN_FN double pn_dselect(bool m, double a, double b) { return m ? a : b; }
PN_FN bool pn_dand(bool a, bool b) { return a && b; }
PN_FN bool pn_dor(bool a, bool b) { return a || b; }
PN_FN bool pn_dnot(bool a) { return !a; }
PN_FN bool pn_dany(bool m) { return m; }
PN_FN bool pn_dfinite(double v) { return v - v == 0.0; }
PN_FN bool pn_dmask_to_mask(bool m) { return m; }
PN_FN bool pn_mask_to_dmask(bool m) { return m; }

#define PN_PLANE(ptr, dims, c) ((ptr) + (std::size_t)(c) * (std::size_t)(dims).plane_pitch)

PN_FN std::size_t pn_index(pn_dims d, int x, int y) { return std::size_t(y) * std::size_t(d.pitch) + std::size_t(x); }

PN_FN float pn_load(const float* plane, pn_dims d, int x, int y) { return x < d.width ? plane[pn_index(d, x, y)] : 0.0f; }
PN_FN void pn_store(float* plane, pn_dims d, int x, int y, float v) { if (x < d.width) plane[pn_index(d, x, y)] = v; }
PN_FN void pn_store_stream(float* plane, pn_dims d, int x, int y, float v) { pn_store(plane, d, x, y, v); }
PN_FN float pn_gather(const float* ptr, std::int32_t index) { return ptr[index]; }
PN_FN float pn_fetch(const float* plane, pn_dims d, std::int32_t x, std::int32_t y)
{
    return plane[pn_index(d, pn_iclamp(x, 0, d.width - 1), pn_iclamp(y, 0, d.height - 1))];
}
PN_FN float pn_fetch_rows(const float* plane, pn_dims d, int first_row, std::int32_t x, std::int32_t y)
{
    return pn_fetch(plane, d, x, pn_iclamp(y, first_row, first_row + d.height - 1) - first_row);
}
PN_FN float pn_load_clamped(const float* plane, pn_dims d, int x, int y) { return pn_fetch(plane, d, x, y); }
PN_FN bool pn_strips_inside(pn_dims d, int x0, int x1) { return x0 >= 0 && x1 < d.width; }
PN_FN float pn_load_inside(const float* plane, pn_dims d, int x, int y) { return plane[pn_index(d, x, y)]; }

PN_FN std::uint32_t pn_uload(const std::uint32_t* plane, pn_dims d, int x, int y) { return x < d.width ? plane[pn_index(d, x, y)] : 0u; }
PN_FN void pn_ustore(std::uint32_t* plane, pn_dims d, int x, int y, std::uint32_t v) { if (x < d.width) plane[pn_index(d, x, y)] = v; }
PN_FN void pn_ustore_stream(std::uint32_t* plane, pn_dims d, int x, int y, std::uint32_t v) { pn_ustore(plane, d, x, y, v); }
PN_FN std::uint32_t pn_ugather(const std::uint32_t* ptr, std::int32_t index) { return ptr[index]; }
PN_FN void pn_ugather_pair(const std::uint32_t* ptr, std::int32_t index, std::uint32_t* first, std::uint32_t* second)
{
    *first = ptr[index];
    *second = ptr[index + 1];
}
// A pair kept whole (kernels/dialect.h): both parts wrap on their own.
struct pn_upair {
    std::uint32_t first, second;
};
PN_FN pn_upair operator-(pn_upair a, pn_upair b) { return {a.first - b.first, a.second - b.second}; }
PN_FN pn_upair pn_ugather_upair(const std::uint32_t* ptr, std::int32_t index) { return {ptr[index], ptr[index + 1]}; }
PN_FN void pn_ugather_upair_both(const std::uint32_t* a, const std::uint32_t* b, std::int32_t index, pn_upair* from_a,
                                 pn_upair* from_b)
{
    *from_a = pn_ugather_upair(a, index);
    *from_b = pn_ugather_upair(b, index);
}
PN_FN void pn_ugather_upair2(const std::uint32_t* ptr, std::int32_t index, pn_upair* first, pn_upair* second)
{
    *first = pn_ugather_upair(ptr, index);
    *second = pn_ugather_upair(ptr, index + 2);
}
PN_FN void pn_ugather_upair2_both(const std::uint32_t* a, const std::uint32_t* b, std::int32_t index,
                                  pn_upair* from_a, pn_upair* from_b)
{
    pn_ugather_upair2(a, index, &from_a[0], &from_a[1]);
    pn_ugather_upair2(b, index, &from_b[0], &from_b[1]);
}
PN_FN double pn_upair_join(pn_upair v) { return double(v.first) * 65536.0 + double(v.second); }

PN_FN void pn_ustore_pair_stream(std::uint32_t* plane, pn_dims d, int x, int y, std::uint32_t first, std::uint32_t second)
{
    if (x >= d.width) return;
    plane[2 * pn_index(d, x, y)] = first;
    plane[2 * pn_index(d, x, y) + 1] = second;
}
PN_FN void pn_uload_pair(const std::uint32_t* plane, pn_dims d, int x, int y, std::uint32_t* first, std::uint32_t* second)
{
    *first = x < d.width ? plane[2 * pn_index(d, x, y)] : 0u;
    *second = x < d.width ? plane[2 * pn_index(d, x, y) + 1] : 0u;
}

// Many lanes (threads) may raise the same flag; only ones are written, but the
// store is atomic so that the race is defined.
PN_FN void pn_flag_any(int* flags, int i, bool m)
{
    if (m) std::atomic_ref<int>(flags[i]).store(1, std::memory_order_relaxed);
}
PN_FN bool pn_finite(float v) { return v - v == 0.0f; }

#define PN_FOR_STRIPS(x, begin, end) for (int x = (begin); x < (end); ++x)
#define PN_STRIP_AFTER(x) ((x) + 1)
PN_FN float pn_scan_add(float v) { return v; }
PN_FN float pn_last(float v) { return v; }
PN_FN std::uint32_t pn_uscan_add(std::uint32_t v) { return v; }
PN_FN std::uint32_t pn_ulast(std::uint32_t v) { return v; }
PN_FN float pn_last_value(float v) { return v; }
PN_FN std::uint32_t pn_ulast_value(std::uint32_t v) { return v; }

#define PN_PIXEL_ARGS int pn_strip_x, int pn_row_y
#define PN_PIXEL_BEGIN(width, height)        \
    const int pn_x = pn_strip_x;              \
    const int pn_y = pn_row_y;                \
    const float pn_lane_x = float(pn_x);      \
    const bool pn_active = pn_x < (width);    \
    (void)pn_lane_x;                          \
    (void)pn_active
#define PN_TASK_ARGS int pn_task_index
#define PN_TASK_BEGIN(count) \
    const int pn_task = pn_task_index; \
    (void)(count)
