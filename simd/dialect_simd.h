// xsimd binding of the kernel dialect (kernels/dialect.h): one pixel per lane.
//
// Included inside namespace penumbra::cpu::<isa> by simd/cpu_kernels.cpp with
// PN_ARCH naming the xsimd architecture (xsimd::sse4_2, xsimd::fma3<xsimd::avx2>,
// xsimd::avx512bw). Keep the semantics identical to simd/dialect_scalar.h (the
// oracle) and cl/dialect_cl.h. Tails: a strip that reaches past an image's
// width is loaded through a zeroed stack buffer and stored through one, so
// nothing is read or written past a row's end.

using pn_float = xsimd::batch<float, PN_ARCH>;
using pn_int = xsimd::batch<std::int32_t, PN_ARCH>;
using pn_uint = xsimd::batch<std::uint32_t, PN_ARCH>;
using pn_mask = xsimd::batch_bool<float, PN_ARCH>;
using uint = std::uint32_t;

// Every description function is inlined into its kernel: the kernels pass
// SIMD vectors between many small functions, and a call passes them through
// memory. GCC's own heuristics stopped inlining the table queries once the
// limb tables made them larger (measured: docs/moments.md, "Speed after issue 9").
#define PN_FN static inline __attribute__((always_inline))
#define PN_KERNEL static inline
#define PN_GLOBAL

inline constexpr int kLanes = int(pn_float::size);
#define PN_LANES kLanes
// A schedule choice (kernels/dialect.h): AVX2's 16 vector registers hold a
// fractional window's rows read in interval order, both values at once, but
// not its 16 corners per value; AVX-512's 32 do better with the corners
// (docs/moment_table.md, "Session 17"). SSE4.2's pair reads are scalar loops.
#if defined(PN_ISA_avx2)
#define PN_FRACTIONAL_ROWS_IN_ORDER 1
#else
#define PN_FRACTIONAL_ROWS_IN_ORDER 0
#endif

PN_FN pn_float pn_min(pn_float a, pn_float b) { return xsimd::min(a, b); }
PN_FN pn_float pn_max(pn_float a, pn_float b) { return xsimd::max(a, b); }
PN_FN pn_float pn_clamp(pn_float v, pn_float lo, pn_float hi) { return pn_min(pn_max(v, lo), hi); }
PN_FN pn_float pn_abs(pn_float v) { return xsimd::abs(v); }
PN_FN pn_float pn_sqrt(pn_float v) { return xsimd::sqrt(v); }
PN_FN pn_float pn_floor(pn_float v) { return xsimd::floor(v); }
PN_FN pn_float pn_ceil(pn_float v) { return xsimd::ceil(v); }
// Fused where the ISA has FMA, as std::fma (scalar) and OpenCL's fma are.
// xsimd 8.1 has no AVX-512 fma: its generic fallback would round twice. SSE4.2
// has no FMA instruction: there it is a multiply and an add (the one ISA on
// which pn_fma rounds twice; tests state their tolerance for it).
PN_FN pn_float pn_fma(pn_float a, pn_float b, pn_float c)
{
#if defined(PN_ISA_avx512)
    return _mm512_fmadd_ps(a, b, c);
#else
    return xsimd::fma(a, b, c);
#endif
}
PN_FN pn_float pn_exp(pn_float v) { return xsimd::exp(v); }
PN_FN pn_float pn_log(pn_float v) { return xsimd::log(v); }
PN_FN pn_float pn_select(pn_mask m, pn_float a, pn_float b) { return xsimd::select(m, a, b); }
PN_FN pn_mask pn_and(pn_mask a, pn_mask b) { return a & b; }
PN_FN pn_mask pn_or(pn_mask a, pn_mask b) { return a | b; }
PN_FN pn_mask pn_not(pn_mask a) { return !a; }
PN_FN bool pn_any(pn_mask m) { return xsimd::any(m); }
PN_FN bool pn_all(pn_mask m) { return xsimd::all(m); }

PN_FN pn_int pn_imin(pn_int a, pn_int b) { return xsimd::min(a, b); }
PN_FN pn_int pn_imax(pn_int a, pn_int b) { return xsimd::max(a, b); }
PN_FN pn_int pn_iclamp(pn_int v, pn_int lo, pn_int hi) { return pn_imin(pn_imax(v, lo), hi); }
PN_FN pn_int pn_to_int(pn_float v) { return xsimd::batch_cast<std::int32_t>(v); }
PN_FN pn_float pn_int_to_float(pn_int v) { return xsimd::batch_cast<float>(v); }
PN_FN pn_uint pn_ushr(pn_uint v, int n) { return v >> n; }
PN_FN pn_uint pn_ushl(pn_uint v, int n) { return v << n; }
PN_FN pn_uint pn_as_uint(pn_float v) { return xsimd::bitwise_cast<pn_uint>(v); }
PN_FN pn_float pn_as_float(pn_uint v) { return xsimd::bitwise_cast<pn_float>(v); }
// uint32 -> float with one rounding, like a scalar conversion: both halves are
// exact in float, so only the final addition rounds.
PN_FN pn_float pn_uint_to_float(pn_uint v)
{
    const pn_int high = xsimd::bitwise_cast<pn_int>(v >> 16);
    const pn_int low = xsimd::bitwise_cast<pn_int>(v & pn_uint(0xFFFFu));
    return pn_int_to_float(high) * 65536.0f + pn_int_to_float(low);
}
PN_FN pn_uint pn_float_to_uint(pn_float v) { return xsimd::bitwise_cast<pn_uint>(pn_to_int(v)); }
// Integer lanes as indices (kernels/dialect.h). The compare yields the float
// lanes' mask: on AVX-512 both are the same 16-bit mask register, before it
// the same all-ones lanes in a vector register.
PN_FN pn_mask pn_iless(pn_int a, pn_int b)
{
#if defined(PN_ISA_avx512)
    return pn_mask(_mm512_cmplt_epi32_mask(a, b));
#elif defined(PN_ISA_avx2)
    return pn_mask(_mm256_castsi256_ps(_mm256_cmpgt_epi32(b, a)));
#else
    return pn_mask(_mm_castsi128_ps(_mm_cmplt_epi32(a, b)));
#endif
}
// A blend moves bits unchanged, so the float select serves int lanes.
PN_FN pn_int pn_iselect(pn_mask m, pn_int a, pn_int b)
{
    return xsimd::bitwise_cast<pn_int>(
        xsimd::select(m, xsimd::bitwise_cast<pn_float>(a), xsimd::bitwise_cast<pn_float>(b)));
}
PN_FN pn_int pn_uint_to_index(pn_uint u) { return xsimd::bitwise_cast<pn_int>(u); }

// Double lanes (kernels/dialect.h): pn_double covers the lanes of pn_float,
// as two xsimd double batches (lanes [0, N/2) in lo, [N/2, N) in hi), with
// the arithmetic of xsimd on each half. Only the conversions between lane
// widths need the ISA's own instructions.
using pn_double_half = xsimd::batch<double, PN_ARCH>;
using pn_dmask_half = xsimd::batch_bool<double, PN_ARCH>;
struct pn_double {
    pn_double_half lo, hi;
    pn_double() = default;
    pn_double(double v) : lo(v), hi(v) {}
    pn_double(pn_double_half l, pn_double_half h) : lo(l), hi(h) {}
};
struct pn_dmask {
    pn_dmask_half lo, hi;
};
#define PN_DOUBLE_BINARY(op)                                                                           \
    PN_FN pn_double operator op(pn_double a, pn_double b) { return {a.lo op b.lo, a.hi op b.hi}; } \
    PN_FN pn_double operator op(pn_double a, double b) { return a op pn_double(b); }               \
    PN_FN pn_double operator op(double a, pn_double b) { return pn_double(a) op b; }
PN_DOUBLE_BINARY(+)
PN_DOUBLE_BINARY(-)
PN_DOUBLE_BINARY(*)
PN_DOUBLE_BINARY(/)
#undef PN_DOUBLE_BINARY
PN_FN pn_double operator-(pn_double a) { return {-a.lo, -a.hi}; }
#define PN_DOUBLE_COMPARE(op)                                                                         \
    PN_FN pn_dmask operator op(pn_double a, pn_double b) { return {a.lo op b.lo, a.hi op b.hi}; } \
    PN_FN pn_dmask operator op(pn_double a, double b) { return a op pn_double(b); }               \
    PN_FN pn_dmask operator op(double a, pn_double b) { return pn_double(a) op b; }
PN_DOUBLE_COMPARE(<)
PN_DOUBLE_COMPARE(<=)
PN_DOUBLE_COMPARE(>)
PN_DOUBLE_COMPARE(>=)
PN_DOUBLE_COMPARE(==)
#undef PN_DOUBLE_COMPARE
PN_FN pn_double pn_dmin(pn_double a, pn_double b) { return {xsimd::min(a.lo, b.lo), xsimd::min(a.hi, b.hi)}; }
PN_FN pn_double pn_dmax(pn_double a, pn_double b) { return {xsimd::max(a.lo, b.lo), xsimd::max(a.hi, b.hi)}; }
PN_FN pn_double pn_dclamp(pn_double v, pn_double lo, pn_double hi) { return pn_dmin(pn_dmax(v, lo), hi); }
PN_FN pn_double pn_dabs(pn_double v) { return {xsimd::abs(v.lo), xsimd::abs(v.hi)}; }
PN_FN pn_double pn_dsqrt(pn_double v) { return {xsimd::sqrt(v.lo), xsimd::sqrt(v.hi)}; }
PN_FN pn_double pn_dfloor(pn_double v) { return {xsimd::floor(v.lo), xsimd::floor(v.hi)}; }
PN_FN pn_double pn_dexp(pn_double v) { return {xsimd::exp(v.lo), xsimd::exp(v.hi)}; }
PN_FN pn_double pn_dselect(pn_dmask m, pn_double a, pn_double b)
{
    return {xsimd::select(m.lo, a.lo, b.lo), xsimd::select(m.hi, a.hi, b.hi)};
}
PN_FN pn_dmask pn_dand(pn_dmask a, pn_dmask b) { return {a.lo & b.lo, a.hi & b.hi}; }
PN_FN pn_dmask pn_dor(pn_dmask a, pn_dmask b) { return {a.lo | b.lo, a.hi | b.hi}; }
PN_FN pn_dmask pn_dnot(pn_dmask a) { return {!a.lo, !a.hi}; }
PN_FN bool pn_dany(pn_dmask m) { return xsimd::any(m.lo) || xsimd::any(m.hi); }
PN_FN pn_dmask pn_dfinite(pn_double v) { return (v - v) == 0.0; }

#if defined(PN_ISA_avx512)
PN_FN pn_double pn_to_double(pn_float v)
{
    const __m512d bits = _mm512_castps_pd(v);
    return {_mm512_cvtps_pd(_mm512_castps512_ps256(v)), _mm512_cvtps_pd(_mm256_castpd_ps(_mm512_extractf64x4_pd(bits, 1)))};
}
PN_FN pn_float pn_double_to_float(pn_double d)
{
    const __m512d low = _mm512_castps_pd(_mm512_castps256_ps512(_mm512_cvtpd_ps(d.lo)));
    return _mm512_castpd_ps(_mm512_insertf64x4(low, _mm256_castps_pd(_mm512_cvtpd_ps(d.hi)), 1));
}
PN_FN pn_double pn_int_to_double(pn_int v)
{
    return {_mm512_cvtepi32_pd(_mm512_castsi512_si256(v)), _mm512_cvtepi32_pd(_mm512_extracti64x4_epi64(v, 1))};
}
PN_FN pn_double pn_uint_to_double(pn_uint v)
{
    return {_mm512_cvtepu32_pd(_mm512_castsi512_si256(v)), _mm512_cvtepu32_pd(_mm512_extracti64x4_epi64(v, 1))};
}
PN_FN pn_int pn_double_to_int(pn_double d)
{
    return _mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvttpd_epi32(d.lo)), _mm512_cvttpd_epi32(d.hi), 1);
}
PN_FN pn_mask pn_dmask_to_mask(pn_dmask m)
{
    const __mmask8 lo = m.lo, hi = m.hi;
    return pn_mask(__mmask16(unsigned(lo) | (unsigned(hi) << 8)));
}
PN_FN pn_dmask pn_mask_to_dmask(pn_mask m)
{
    const unsigned bits = __mmask16(m);
    return {pn_dmask_half(__mmask8(bits & 0xFFu)), pn_dmask_half(__mmask8(bits >> 8))};
}
#elif defined(PN_ISA_avx2)
PN_FN pn_double pn_to_double(pn_float v)
{
    return {_mm256_cvtps_pd(_mm256_castps256_ps128(v)), _mm256_cvtps_pd(_mm256_extractf128_ps(v, 1))};
}
PN_FN pn_float pn_double_to_float(pn_double d) { return _mm256_set_m128(_mm256_cvtpd_ps(d.hi), _mm256_cvtpd_ps(d.lo)); }
PN_FN pn_double pn_int_to_double(pn_int v)
{
    return {_mm256_cvtepi32_pd(_mm256_castsi256_si128(v)), _mm256_cvtepi32_pd(_mm256_extracti128_si256(v, 1))};
}
// No unsigned conversion before AVX-512: flip the sign bit, convert as int32,
// add 2^31 back (exact in double).
PN_FN pn_double pn_uint_to_double(pn_uint v)
{
    const pn_int flipped = xsimd::bitwise_cast<pn_int>(v ^ pn_uint(0x80000000u));
    return pn_int_to_double(flipped) + 2147483648.0;
}
PN_FN pn_int pn_double_to_int(pn_double d) { return _mm256_set_m128i(_mm256_cvttpd_epi32(d.hi), _mm256_cvttpd_epi32(d.lo)); }
// Masks are all-ones lanes: keep the low 32 bits of each 64-bit lane.
PN_FN pn_mask pn_dmask_to_mask(pn_dmask m)
{
    const __m256i even = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
    const __m256i lo = _mm256_permutevar8x32_epi32(_mm256_castpd_si256(m.lo), even);
    const __m256i hi = _mm256_permutevar8x32_epi32(_mm256_castpd_si256(m.hi), even);
    return pn_mask(_mm256_castsi256_ps(_mm256_set_m128i(_mm256_castsi256_si128(hi), _mm256_castsi256_si128(lo))));
}
PN_FN pn_dmask pn_mask_to_dmask(pn_mask m)
{
    const __m256i bits = _mm256_castps_si256(m);
    return {pn_dmask_half(_mm256_castsi256_pd(_mm256_cvtepi32_epi64(_mm256_castsi256_si128(bits)))),
            pn_dmask_half(_mm256_castsi256_pd(_mm256_cvtepi32_epi64(_mm256_extracti128_si256(bits, 1))))};
}
#else
PN_FN pn_double pn_to_double(pn_float v) { return {_mm_cvtps_pd(v), _mm_cvtps_pd(_mm_movehl_ps(v, v))}; }
PN_FN pn_float pn_double_to_float(pn_double d) { return _mm_movelh_ps(_mm_cvtpd_ps(d.lo), _mm_cvtpd_ps(d.hi)); }
PN_FN pn_double pn_int_to_double(pn_int v) { return {_mm_cvtepi32_pd(v), _mm_cvtepi32_pd(_mm_unpackhi_epi64(v, v))}; }
PN_FN pn_double pn_uint_to_double(pn_uint v)
{
    const pn_int flipped = xsimd::bitwise_cast<pn_int>(v ^ pn_uint(0x80000000u));
    return pn_int_to_double(flipped) + 2147483648.0;
}
PN_FN pn_int pn_double_to_int(pn_double d) { return _mm_unpacklo_epi64(_mm_cvttpd_epi32(d.lo), _mm_cvttpd_epi32(d.hi)); }
PN_FN pn_mask pn_dmask_to_mask(pn_dmask m)
{
    return pn_mask(_mm_shuffle_ps(_mm_castpd_ps(m.lo), _mm_castpd_ps(m.hi), _MM_SHUFFLE(2, 0, 2, 0)));
}
PN_FN pn_dmask pn_mask_to_dmask(pn_mask m)
{
    const __m128i bits = _mm_castps_si128(m);
    return {pn_dmask_half(_mm_castsi128_pd(_mm_cvtepi32_epi64(bits))),
            pn_dmask_half(_mm_castsi128_pd(_mm_cvtepi32_epi64(_mm_unpackhi_epi64(bits, bits))))};
}
#endif
// Truncation of values in [0, 2^31).
PN_FN pn_uint pn_double_to_uint(pn_double d) { return xsimd::bitwise_cast<pn_uint>(pn_double_to_int(d)); }

#define PN_PLANE(ptr, dims, c) ((ptr) + (std::size_t)(c) * (std::size_t)(dims).plane_pitch)

template <class T>
using pn_batch_of = xsimd::batch<T, PN_ARCH>;

template <class T>
PN_FN pn_batch_of<T> pn_load_strip(const T* plane, pn_dims d, int x, int y)
{
    const T* p = plane + std::size_t(y) * std::size_t(d.pitch) + std::size_t(x);
    const int valid = d.width - x;
    if (valid >= kLanes) return pn_batch_of<T>::load_unaligned(p);
    alignas(64) T tail[kLanes] = {};
    std::memcpy(tail, p, sizeof(T) * std::size_t(valid > 0 ? valid : 0));
    return pn_batch_of<T>::load_aligned(tail);
}

// Non-temporal store of a whole aligned strip: the summed-area table is
// written once and not read back soon, so it should not evict the inputs.
template <class T>
PN_FN void pn_stream_store(T* p, pn_batch_of<T> v)
{
#if defined(PN_ISA_avx512)
    if constexpr (std::is_same_v<T, float>) _mm512_stream_ps(p, v);
    else _mm512_stream_si512(reinterpret_cast<__m512i*>(p), v);
#elif defined(PN_ISA_avx2)
    if constexpr (std::is_same_v<T, float>) _mm256_stream_ps(p, v);
    else _mm256_stream_si256(reinterpret_cast<__m256i*>(p), v);
#else
    if constexpr (std::is_same_v<T, float>) _mm_stream_ps(p, v);
    else _mm_stream_si128(reinterpret_cast<__m128i*>(p), v);
#endif
}

template <class T>
PN_FN void pn_store_strip(T* plane, pn_dims d, int x, int y, pn_batch_of<T> v, bool stream)
{
    T* p = plane + std::size_t(y) * std::size_t(d.pitch) + std::size_t(x);
    const int valid = d.width - x;
    if (valid >= kLanes) {
        if (stream && reinterpret_cast<std::uintptr_t>(p) % (sizeof(T) * kLanes) == 0)
            pn_stream_store(p, v);
        else
            v.store_unaligned(p);
        return;
    }
    alignas(64) T tail[kLanes];
    v.store_aligned(tail);
    std::memcpy(p, tail, sizeof(T) * std::size_t(valid > 0 ? valid : 0));
}

PN_FN pn_float pn_load(const float* plane, pn_dims d, int x, int y) { return pn_load_strip(plane, d, x, y); }
PN_FN void pn_store(float* plane, pn_dims d, int x, int y, pn_float v) { pn_store_strip(plane, d, x, y, v, false); }
PN_FN void pn_store_stream(float* plane, pn_dims d, int x, int y, pn_float v) { pn_store_strip(plane, d, x, y, v, true); }
PN_FN pn_uint pn_uload(const uint* plane, pn_dims d, int x, int y) { return pn_load_strip(plane, d, x, y); }
PN_FN void pn_ustore(uint* plane, pn_dims d, int x, int y, pn_uint v) { pn_store_strip(plane, d, x, y, v, false); }
PN_FN void pn_ustore_stream(uint* plane, pn_dims d, int x, int y, pn_uint v) { pn_store_strip(plane, d, x, y, v, true); }

// Gathers use the ISA's instruction directly: xsimd 8.1 picks its generic
// (scalar) gather for AVX-512 whatever the element type. Integer data is
// gathered as float bits, which the instruction moves unchanged. SSE4.2 has
// no gather instruction: a loop through memory.
PN_FN pn_float pn_gather(const float* ptr, pn_int index)
{
#if defined(PN_ISA_avx512)
    return _mm512_i32gather_ps(index, ptr, 4);
#elif defined(PN_ISA_avx2)
    return _mm256_i32gather_ps(ptr, index, 4);
#else
    alignas(64) std::int32_t lanes[kLanes];
    alignas(64) float values[kLanes];
    index.store_aligned(lanes);
    for (int i = 0; i < kLanes; ++i) values[i] = ptr[lanes[i]];
    return pn_float::load_aligned(values);
#endif
}
PN_FN pn_uint pn_ugather(const uint* ptr, pn_int index)
{
    return xsimd::bitwise_cast<pn_uint>(pn_gather(reinterpret_cast<const float*>(ptr), index));
}
// Two adjacent elements per lane, ptr[index] and ptr[index + 1]: one 64-bit
// gather element per lane instead of two 32-bit ones, then the pairs are
// split by a permute.
PN_FN void pn_ugather_pair(const uint* ptr, pn_int index, pn_uint* first, pn_uint* second)
{
#if defined(PN_ISA_avx512)
    // The masked form with a zero source: GCC 12's unmasked one warns of an
    // uninitialised source vector.
    const __m512i zero = _mm512_setzero_si512();
    const __m512i a = _mm512_mask_i32gather_epi64(zero, 0xFF, _mm512_castsi512_si256(index), ptr, 4);
    const __m512i b = _mm512_mask_i32gather_epi64(zero, 0xFF, _mm512_extracti64x4_epi64(index, 1), ptr, 4);
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    const __m512i odd = _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
    *first = _mm512_permutex2var_epi32(a, even, b);
    *second = _mm512_permutex2var_epi32(a, odd, b);
#elif defined(PN_ISA_avx2)
    const auto* base = reinterpret_cast<const long long*>(ptr);
    const __m256i split = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
    const __m256i a = _mm256_permutevar8x32_epi32(_mm256_i32gather_epi64(base, _mm256_castsi256_si128(index), 4), split);
    const __m256i b = _mm256_permutevar8x32_epi32(_mm256_i32gather_epi64(base, _mm256_extracti128_si256(index, 1), 4), split);
    *first = _mm256_permute2x128_si256(a, b, 0x20);
    *second = _mm256_permute2x128_si256(a, b, 0x31);
#else
    alignas(64) std::int32_t lanes[kLanes];
    alignas(64) uint a[kLanes], b[kLanes];
    index.store_aligned(lanes);
    for (int i = 0; i < kLanes; ++i) {
        a[i] = ptr[lanes[i]];
        b[i] = ptr[lanes[i] + 1];
    }
    *first = pn_uint::load_aligned(a);
    *second = pn_uint::load_aligned(b);
#endif
}
// A pair kept whole (kernels/dialect.h, pn_upair): the 64-bit gather
// elements as they arrive, lanes [0, N/2) in lo and [N/2, N) in hi, the
// halves of pn_double, so that neither subtraction nor join moves a lane
// across. Each 64-bit element holds first in its low and second in its high
// 32 bits; pn_uint's subtraction wraps each 32-bit part on its own.
struct pn_upair {
    pn_uint lo, hi;
};
PN_FN pn_upair operator-(pn_upair a, pn_upair b) { return {a.lo - b.lo, a.hi - b.hi}; }
PN_FN pn_upair pn_ugather_upair(const uint* ptr, pn_int index)
{
#if defined(PN_ISA_avx512)
    const __m512i zero = _mm512_setzero_si512();  // as pn_ugather_pair: the masked form
    return {_mm512_mask_i32gather_epi64(zero, 0xFF, _mm512_castsi512_si256(index), ptr, 4),
            _mm512_mask_i32gather_epi64(zero, 0xFF, _mm512_extracti64x4_epi64(index, 1), ptr, 4)};
#elif defined(PN_ISA_avx2)
    const auto* base = reinterpret_cast<const long long*>(ptr);
    return {_mm256_i32gather_epi64(base, _mm256_castsi256_si128(index), 4),
            _mm256_i32gather_epi64(base, _mm256_extracti128_si256(index, 1), 4)};
#else
    alignas(64) std::int32_t lanes[kLanes];
    alignas(64) uint pairs[2 * kLanes];
    index.store_aligned(lanes);
    for (int i = 0; i < kLanes; ++i) {
        pairs[2 * i] = ptr[lanes[i]];
        pairs[2 * i + 1] = ptr[lanes[i] + 1];
    }
    return {pn_uint::load_aligned(pairs), pn_uint::load_aligned(pairs + kLanes)};
#endif
}
// pn_ugather_upair of two planes at the same indices (a box's corners of
// values 0 and 1: VSM, VSSM's search): on AVX-512 and AVX2 one 64-bit load
// per lane and plane, each lane's index extracted once for both, instead of
// four 64-bit gathers (docs/moment_table.md, "Session 17").
PN_FN void pn_ugather_upair_both(const uint* a, const uint* b, pn_int index, pn_upair* from_a, pn_upair* from_b)
{
#if defined(PN_ISA_avx512) || defined(PN_ISA_avx2)
    alignas(64) std::int32_t lanes[kLanes];
    index.store_aligned(lanes);
    // Lanes i and i + 1 of one plane in one 128-bit part.
    const auto two = [&](const uint* plane, int i) {
        const __m128i low = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(plane + lanes[i]));
        return _mm_castpd_si128(_mm_loadh_pd(_mm_castsi128_pd(low), reinterpret_cast<const double*>(plane + lanes[i + 1])));
    };
#endif
#if defined(PN_ISA_avx512)
    const auto half = [&](const uint* plane, int i) {  // lanes i .. i + 7
        __m512i v = _mm512_castsi128_si512(two(plane, i));
        v = _mm512_inserti64x2(v, two(plane, i + 2), 1);
        v = _mm512_inserti64x2(v, two(plane, i + 4), 2);
        return _mm512_inserti64x2(v, two(plane, i + 6), 3);
    };
    *from_a = {half(a, 0), half(a, 8)};
    *from_b = {half(b, 0), half(b, 8)};
#elif defined(PN_ISA_avx2)
    const auto half = [&](const uint* plane, int i) {  // lanes i .. i + 3
        return _mm256_inserti128_si256(_mm256_castsi128_si256(two(plane, i)), two(plane, i + 2), 1);
    };
    *from_a = {half(a, 0), half(a, 4)};
    *from_b = {half(b, 0), half(b, 4)};
#else
    *from_a = pn_ugather_upair(a, index);
    *from_b = pn_ugather_upair(b, index);
#endif
}
// Two adjacent pairs per lane, ptr[index .. index + 3]: a fractional
// window's corners a and a + 1 of one row, 16 contiguous bytes. On AVX-512
// and AVX2 one 128-bit load per lane and a few inserts and unpacks instead
// of four 64-bit gathers: faster on Zen 5 for coherent and incoherent
// receivers alike (docs/moment_table.md, "Session 16"). The box corners'
// single pairs stay gathers (loads there sped up VSM but slowed MSM and
// EVSM4 by 15-25%), except two planes at once (pn_ugather_upair_both).
PN_FN void pn_ugather_upair2(const uint* ptr, pn_int index, pn_upair* first, pn_upair* second)
{
#if defined(PN_ISA_avx512) || defined(PN_ISA_avx2)
    alignas(64) std::int32_t lanes[kLanes];
    index.store_aligned(lanes);
    const auto lane = [&](int i) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(ptr + lanes[i])); };
#endif
    // Lanes i, i + 2, ... side by side, one 128-bit part each, and lanes
    // i + 1, i + 3, ... likewise: unpacking their low and high 64-bit halves
    // gives the lanes' first and second pairs in lane order.
#if defined(PN_ISA_avx512)
    const auto parts = [&](int i) {  // lanes i, i + 2, i + 4, i + 6
        __m512i v = _mm512_castsi128_si512(lane(i));
        v = _mm512_inserti64x2(v, lane(i + 2), 1);
        v = _mm512_inserti64x2(v, lane(i + 4), 2);
        return _mm512_inserti64x2(v, lane(i + 6), 3);
    };
    const __m512i e0 = parts(0), o0 = parts(1), e8 = parts(8), o8 = parts(9);
    *first = {_mm512_unpacklo_epi64(e0, o0), _mm512_unpacklo_epi64(e8, o8)};
    *second = {_mm512_unpackhi_epi64(e0, o0), _mm512_unpackhi_epi64(e8, o8)};
#elif defined(PN_ISA_avx2)
    const auto parts = [&](int i) { return _mm256_inserti128_si256(_mm256_castsi128_si256(lane(i)), lane(i + 2), 1); };
    const __m256i e0 = parts(0), o0 = parts(1), e4 = parts(4), o4 = parts(5);
    *first = {_mm256_unpacklo_epi64(e0, o0), _mm256_unpacklo_epi64(e4, o4)};
    *second = {_mm256_unpackhi_epi64(e0, o0), _mm256_unpackhi_epi64(e4, o4)};
#else
    *first = pn_ugather_upair(ptr, index);
    *second = pn_ugather_upair(ptr, index + 2);
#endif
}
// pn_ugather_upair2 of two planes at the same indices (VSSM's filter rows
// on AVX2, PN_FRACTIONAL_ROWS_IN_ORDER): each lane's index extracted once
// for both planes' loads. pn_ugather_upair2 itself is left as it was: routed
// through a shared template, MSM-soft's AVX2 code changed and measured 0.78x.
PN_FN void pn_ugather_upair2_both(const uint* a, const uint* b, pn_int index, pn_upair* from_a, pn_upair* from_b)
{
#if defined(PN_ISA_avx2)
    alignas(64) std::int32_t lanes[kLanes];
    index.store_aligned(lanes);
    const auto lane = [&](const uint* ptr, int i) {
        return _mm_loadu_si128(reinterpret_cast<const __m128i*>(ptr + lanes[i]));
    };
    const auto parts = [&](const uint* ptr, int i) {
        return _mm256_inserti128_si256(_mm256_castsi128_si256(lane(ptr, i)), lane(ptr, i + 2), 1);
    };
    const auto both_pairs = [&](const uint* ptr, pn_upair* out) {  // as pn_ugather_upair2
        const __m256i e0 = parts(ptr, 0), o0 = parts(ptr, 1), e4 = parts(ptr, 4), o4 = parts(ptr, 5);
        out[0] = {_mm256_unpacklo_epi64(e0, o0), _mm256_unpacklo_epi64(e4, o4)};
        out[1] = {_mm256_unpackhi_epi64(e0, o0), _mm256_unpackhi_epi64(e4, o4)};
    };
    both_pairs(a, from_a);
    both_pairs(b, from_b);
#else
    pn_ugather_upair2(a, index, &from_a[0], &from_a[1]);
    pn_ugather_upair2(b, index, &from_b[0], &from_b[1]);
#endif
}
// first 2^16 + second in 64-bit lanes (below 2^49), then to double; before
// AVX-512 by the exponent trick: OR-ing an integer below 2^52 under the
// exponent of 2^52 gives the double 2^52 + n exactly, and subtracting 2^52
// leaves n.
PN_FN pn_double_half pn_upair_join_half(pn_uint v)
{
#if defined(PN_ISA_avx512)
    // AVX-512: the low part times 2^16 in one unsigned 32x32 -> 64 multiply,
    // and AVX512DQ's exact uint64 -> double conversion (the value is below 2^53).
    const __m512i joined = _mm512_add_epi64(_mm512_mul_epu32(v, _mm512_set1_epi64(65536)), _mm512_srli_epi64(v, 32));
    return _mm512_cvtepu64_pd(joined);
#else
    using u64 = xsimd::batch<std::uint64_t, PN_ARCH>;
    const u64 x = xsimd::bitwise_cast<u64>(v);
    const u64 joined = ((x & u64(0xFFFFFFFFull)) << 16) + (x >> 32);
    const u64 biased = joined | u64(0x4330000000000000ull);
    return xsimd::bitwise_cast<pn_double_half>(biased) - pn_double_half(4503599627370496.0);
#endif
}
PN_FN pn_double pn_upair_join(pn_upair v) { return {pn_upair_join_half(v.lo), pn_upair_join_half(v.hi)}; }
// Two strips interleaved lane by lane, (first[i], second[i]) at elements
// 2 (y pitch + x + i) + 0 / 1: the pair planes of the limb tables
// (kernels/moment_table.h). The interleave is a two-source permute.
PN_FN void pn_ustore_pair_stream(uint* plane, pn_dims d, int x, int y, pn_uint first, pn_uint second)
{
#if defined(PN_ISA_avx512)
    const __m512i low = _mm512_setr_epi32(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
    const __m512i high = _mm512_setr_epi32(8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31);
    const pn_uint a = _mm512_permutex2var_epi32(first, low, second);
    const pn_uint b = _mm512_permutex2var_epi32(first, high, second);
#elif defined(PN_ISA_avx2)
    const __m256i u0 = _mm256_unpacklo_epi32(first, second);  // f0 s0 f1 s1 | f4 s4 f5 s5
    const __m256i u1 = _mm256_unpackhi_epi32(first, second);  // f2 s2 f3 s3 | f6 s6 f7 s7
    const pn_uint a = _mm256_permute2x128_si256(u0, u1, 0x20);
    const pn_uint b = _mm256_permute2x128_si256(u0, u1, 0x31);
#else
    const pn_uint a = _mm_unpacklo_epi32(first, second);
    const pn_uint b = _mm_unpackhi_epi32(first, second);
#endif
    uint* p = plane + 2 * (std::size_t(y) * std::size_t(d.pitch) + std::size_t(x));
    const int valid = d.width - x;
    if (valid >= kLanes) {
        if (reinterpret_cast<std::uintptr_t>(p) % (sizeof(uint) * kLanes) == 0) {
            pn_stream_store(p, a);
            pn_stream_store(p + kLanes, b);
        } else {
            a.store_unaligned(p);
            b.store_unaligned(p + kLanes);
        }
        return;
    }
    alignas(64) uint tail[2 * kLanes];
    a.store_aligned(tail);
    b.store_aligned(tail + kLanes);
    std::memcpy(p, tail, 2 * sizeof(uint) * std::size_t(valid > 0 ? valid : 0));
}
// Its inverse, lane by lane through memory: only the OpenCL-style join pass
// reads pair planes back, never on the CPU backends' hot paths.
PN_FN void pn_uload_pair(const uint* plane, pn_dims d, int x, int y, pn_uint* first, pn_uint* second)
{
    const uint* p = plane + 2 * (std::size_t(y) * std::size_t(d.pitch) + std::size_t(x));
    alignas(64) uint a[kLanes] = {}, b[kLanes] = {};
    for (int i = 0; i < kLanes && i < d.width - x; ++i) {
        a[i] = p[2 * i];
        b[i] = p[2 * i + 1];
    }
    *first = pn_uint::load_aligned(a);
    *second = pn_uint::load_aligned(b);
}
PN_FN pn_float pn_fetch(const float* plane, pn_dims d, pn_int x, pn_int y)
{
    const pn_int cx = pn_iclamp(x, pn_int(0), pn_int(d.width - 1));
    const pn_int cy = pn_iclamp(y, pn_int(0), pn_int(d.height - 1));
    return pn_gather(plane, cy * d.pitch + cx);
}
// Rows [first_row, first_row + height) of a taller image: the lanes' indices
// stay the image's (cy * pitch + cx, as pn_fetch's), and the gather's base
// moves back by first_row rows, computed once (a loop invariant) rather than
// a subtraction per tap. The base is moved as an integer: no C++ pointer
// leaves the buffer (the instruction adds base and index itself). SSE4.2's
// gather is a loop of scalar loads anyway, so it adds the offset per lane.
PN_FN pn_float pn_fetch_rows(const float* plane, pn_dims d, int first_row, pn_int x, pn_int y)
{
    const pn_int cx = pn_iclamp(x, pn_int(0), pn_int(d.width - 1));
    const pn_int cy = pn_iclamp(y, pn_int(first_row), pn_int(first_row + d.height - 1));
    const pn_int index = cy * d.pitch + cx;
    const std::ptrdiff_t offset = -std::ptrdiff_t(first_row) * d.pitch;
#if defined(PN_ISA_avx512) || defined(PN_ISA_avx2)
    const auto base = reinterpret_cast<const float*>(reinterpret_cast<std::uintptr_t>(plane) +
                                                     std::uintptr_t(offset) * sizeof(float));
    return pn_gather(base, index);
#else
    alignas(64) std::int32_t lanes[kLanes];
    alignas(64) float values[kLanes];
    index.store_aligned(lanes);
    for (int i = 0; i < kLanes; ++i) values[i] = plane[offset + lanes[i]];
    return pn_float::load_aligned(values);
#endif
}
// Lane i holds i: the column offsets of a strip's pixels.
PN_FN pn_int pn_int_lane_offsets()
{
    alignas(64) std::int32_t offsets[kLanes];
    for (int i = 0; i < kLanes; ++i) offsets[i] = i;
    return pn_int::load_aligned(offsets);
}
// Clamp-to-edge strip: one unaligned load when the strip lies inside the
// image (the hot path of a filter's taps, kept small so that it stays in the
// tap loop); a strip that crosses an edge (the first and last strips of a row,
// the rows above and below) takes the out-of-line path, which gathers its
// clamped columns.
[[gnu::noinline, gnu::cold]] static pn_float pn_load_clamped_edge(const float* plane, pn_dims d, int x, int y)
{
    const int cy = y < 0 ? 0 : (y >= d.height ? d.height - 1 : y);
    const float* row = plane + std::size_t(cy) * std::size_t(d.pitch);
    if (x >= 0 && x <= d.width - kLanes) return pn_float::load_unaligned(row + x);
    const pn_int columns = pn_iclamp(pn_int(x) + pn_int_lane_offsets(), pn_int(0), pn_int(d.width - 1));
    return pn_gather(row, columns);
}
PN_FN bool pn_strips_inside(pn_dims d, int x0, int x1) { return x0 >= 0 && x1 <= d.width - kLanes; }
PN_FN pn_float pn_load_inside(const float* plane, pn_dims d, int x, int y)
{
    return pn_float::load_unaligned(plane + std::size_t(y) * std::size_t(d.pitch) + std::size_t(x));
}
PN_FN pn_float pn_load_clamped(const float* plane, pn_dims d, int x, int y)
{
    // Unsigned compares: a negative x or y wraps high and fails them.
    if (unsigned(y) < unsigned(d.height) && unsigned(x) <= unsigned(d.width - kLanes) && d.width >= kLanes)
        return pn_float::load_unaligned(plane + std::size_t(y) * std::size_t(d.pitch) + std::size_t(x));
    return pn_load_clamped_edge(plane, d, x, y);
}

// Inclusive prefix sum across lanes: log2(lanes) steps of "shift up by k lanes
// (zeros enter) and add" (Hillis & Steele). The shift is a compile-time swizzle
// followed by a select that zeroes the lanes below k.
template <class T, unsigned K>
struct pn_shift_up_index {
    static constexpr unsigned get(unsigned i, unsigned) { return i >= K ? i - K : 0; }
};
template <class T, unsigned K>
struct pn_lane_at_least {
    static constexpr bool get(unsigned i, unsigned) { return i >= K; }
};
template <class T, unsigned K = 1>
PN_FN pn_batch_of<T> pn_scan_add_from(pn_batch_of<T> v)
{
    if constexpr (K >= unsigned(kLanes)) {
        return v;
    } else {
        using index_batch = xsimd::batch<std::uint32_t, PN_ARCH>;
        const auto index = xsimd::make_batch_constant<index_batch, pn_shift_up_index<T, K>>();
        const auto keep = xsimd::make_batch_bool_constant<pn_batch_of<T>, pn_lane_at_least<T, K>>();
        const pn_batch_of<T> shifted = xsimd::select(keep, xsimd::swizzle(v, index), pn_batch_of<T>(T(0)));
        return pn_scan_add_from<T, 2 * K>(v + shifted);
    }
}
template <class T>
struct pn_last_index {
    static constexpr unsigned get(unsigned, unsigned n) { return n - 1; }
};
template <class T>
PN_FN pn_batch_of<T> pn_broadcast_last(pn_batch_of<T> v)
{
    using index_batch = xsimd::batch<std::uint32_t, PN_ARCH>;
    return xsimd::swizzle(v, xsimd::make_batch_constant<index_batch, pn_last_index<T>>());
}

// Many strips (threads) may raise the same flag; only ones are written, but
// the store is atomic so that the race is defined.
PN_FN void pn_flag_any(int* flags, int i, pn_mask m)
{
    if (xsimd::any(m)) std::atomic_ref<int>(flags[i]).store(1, std::memory_order_relaxed);
}
// v - v is 0 for finite v and NaN for NaN and infinities.
PN_FN pn_mask pn_finite(pn_float v) { return (v - v) == 0.0f; }

#define PN_FOR_STRIPS(x, begin, end) for (int x = (begin); x < (end); x += kLanes)
#define PN_STRIP_AFTER(x) ((x) + kLanes)
PN_FN pn_float pn_scan_add(pn_float v) { return pn_scan_add_from<float>(v); }
PN_FN pn_float pn_last(pn_float v) { return pn_broadcast_last<float>(v); }
PN_FN pn_uint pn_uscan_add(pn_uint v) { return pn_scan_add_from<std::uint32_t>(v); }
PN_FN pn_uint pn_ulast(pn_uint v) { return pn_broadcast_last<std::uint32_t>(v); }
template <class T>
PN_FN T pn_last_lane(pn_batch_of<T> v)
{
    alignas(64) T lanes[kLanes];
    v.store_aligned(lanes);
    return lanes[kLanes - 1];
}
PN_FN float pn_last_value(pn_float v) { return pn_last_lane<float>(v); }
PN_FN uint pn_ulast_value(pn_uint v) { return pn_last_lane<std::uint32_t>(v); }

// Lane i holds float(i): the x offsets of a strip's pixels.
PN_FN pn_float pn_lane_offsets()
{
    alignas(64) float offsets[kLanes];
    for (int i = 0; i < kLanes; ++i) offsets[i] = float(i);
    return pn_float::load_aligned(offsets);
}

#define PN_PIXEL_ARGS int pn_strip_x, int pn_row_y
#define PN_PIXEL_BEGIN(width, height)                                     \
    const int pn_x = pn_strip_x;                                          \
    const int pn_y = pn_row_y;                                            \
    const pn_float pn_lane_x = pn_float(float(pn_x)) + pn_lane_offsets(); \
    const pn_mask pn_active = pn_lane_x < float(width);                   \
    (void)pn_lane_x;                                                      \
    (void)pn_active
#define PN_TASK_ARGS int pn_task_index
#define PN_TASK_BEGIN(count) \
    const int pn_task = pn_task_index; \
    (void)(count)
