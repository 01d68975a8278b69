// What an exact VSM table build could cost at best on this machine: hand-written
// AVX-512 loops outside the library (no dialect, no TBB, no tails, no range
// flags kept, no carries handed between the two threads' column halves), timed
// against a memcpy of the same bytes in the same run (docs/moment_table.md,
// "Session 22"). Issue 9 asks the library's build for 0.85 of that memcpy.
//
//   traffic      the map read, 16 B/texel streamed into two planes, no arithmetic
//   limbs        the library's format (two uint32 pair planes of 16-bit limb sums):
//                z's limbs at float width, z^2's in double, four 32-bit lane scans,
//                the column sums, the pairs interleaved and streamed
//   sums64       a format the library does not have: one uint64 plane of wrapping
//                sums of floor(v 2^32 + 1/2) per value, the same 16 B/texel, the
//                values formed and scanned in 64-bit lanes (no limbs, no interleave)
//   *, no stores the same arithmetic and column sums with the table stores left out
//
// Usage: table_build_bounds [size]   (default 4096; prints medians of 9, three rounds)
// GCC 12's AVX-512 conversion intrinsics start from _mm512_undefined_*, which
// -Wmaybe-uninitialized reports inside its own header.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace {

#define PN_AVX512 __attribute__((target("avx512f,avx512dq,avx512bw,avx512vl")))

struct Buffers {
    int n = 0;
    float* depth = nullptr;
    std::uint32_t* table = nullptr;    // 16 B/texel
    std::uint32_t* columns = nullptr;  // 16 B per column
    char* copy_from = nullptr;         // memcpy: 10 B/texel each way
    char* copy_to = nullptr;
};

using Rows = std::function<void(const Buffers&, int x0, int x1)>;

PN_AVX512 __m512i scan32(__m512i v)
{
    const __m512i zero = _mm512_setzero_si512();
    v = _mm512_add_epi32(v, _mm512_alignr_epi32(v, zero, 15));
    v = _mm512_add_epi32(v, _mm512_alignr_epi32(v, zero, 14));
    v = _mm512_add_epi32(v, _mm512_alignr_epi32(v, zero, 12));
    return _mm512_add_epi32(v, _mm512_alignr_epi32(v, zero, 8));
}

PN_AVX512 __m512i scan64(__m512i v)
{
    const __m512i zero = _mm512_setzero_si512();
    v = _mm512_add_epi64(v, _mm512_alignr_epi64(v, zero, 7));
    v = _mm512_add_epi64(v, _mm512_alignr_epi64(v, zero, 6));
    return _mm512_add_epi64(v, _mm512_alignr_epi64(v, zero, 4));
}

PN_AVX512 __m512 clamped_depth(const float* row, int x, __mmask16* bad)
{
    const __m512 z = _mm512_loadu_ps(row + x);
    *bad |= _mm512_cmp_ps_mask(z, _mm512_setzero_ps(), _CMP_NGE_UQ) | _mm512_cmp_ps_mask(z, _mm512_set1_ps(1.0f), _CMP_NLE_UQ);
    return _mm512_min_ps(_mm512_max_ps(z, _mm512_setzero_ps()), _mm512_set1_ps(1.0f));
}

// The 16-bit limbs of floor(v 2^32 + 1/2), from double.
PN_AVX512 void double_limbs(__m512d v, __m256i* first, __m256i* second)
{
    const __m512d q = _mm512_fmadd_pd(v, _mm512_set1_pd(4294967296.0), _mm512_set1_pd(0.5));
    const __m512d high = _mm512_roundscale_pd(_mm512_mul_pd(q, _mm512_set1_pd(1.0 / 65536.0)), _MM_FROUND_TO_NEG_INF);
    *first = _mm512_cvttpd_epu32(high);
    *second = _mm512_cvttpd_epu32(_mm512_roundscale_pd(_mm512_fnmadd_pd(high, _mm512_set1_pd(65536.0), q),
                                                       _MM_FROUND_TO_NEG_INF));
}

template <bool kStore>
PN_AVX512 void limb_rows(const Buffers& b, int x0, int x1)
{
    const __m512i last = _mm512_set1_epi32(15);
    const __m512i low = _mm512_setr_epi32(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
    const __m512i high = _mm512_setr_epi32(8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31);
    const std::size_t n = std::size_t(b.n);
    __mmask16 bad = 0;
    for (std::size_t y = 0; y < n; ++y) {
        const float* row = b.depth + y * n;
        std::uint32_t* z_pairs = b.table + 2 * y * n;
        std::uint32_t* square_pairs = z_pairs + 2 * n * n;
        __m512i carry[4] = {_mm512_setzero_si512(), _mm512_setzero_si512(), _mm512_setzero_si512(), _mm512_setzero_si512()};
        for (int x = x0; x < x1; x += 16) {
            const __m512 z = clamped_depth(row, x, &bad);
            // z's limbs at float width (the library's sat_depth_limbs2).
            const __m512 t = _mm512_mul_ps(z, _mm512_set1_ps(4294967296.0f));
            const __m512 whole = _mm512_roundscale_ps(t, _MM_FROUND_TO_NEG_INF);
            const __mmask16 up = _mm512_cmp_ps_mask(_mm512_sub_ps(t, whole), _mm512_set1_ps(0.5f), _CMP_GE_OQ);
            const __m512 q = _mm512_mask_add_ps(whole, up, whole, _mm512_set1_ps(1.0f));
            const __m512 l0 = _mm512_roundscale_ps(_mm512_mul_ps(q, _mm512_set1_ps(1.0f / 65536.0f)), _MM_FROUND_TO_NEG_INF);
            __m512i limb[4];
            limb[0] = _mm512_cvttps_epu32(l0);
            limb[1] = _mm512_cvttps_epu32(_mm512_fnmadd_ps(l0, _mm512_set1_ps(65536.0f), q));
            // z^2's in double, two halves of 8.
            const __m512d lo = _mm512_cvtps_pd(_mm512_castps512_ps256(z));
            const __m512d hi = _mm512_cvtps_pd(_mm512_extractf32x8_ps(z, 1));
            __m256i a0, a1, b0, b1;
            double_limbs(_mm512_mul_pd(lo, lo), &a0, &a1);
            double_limbs(_mm512_mul_pd(hi, hi), &b0, &b1);
            limb[2] = _mm512_inserti64x4(_mm512_castsi256_si512(a0), b0, 1);
            limb[3] = _mm512_inserti64x4(_mm512_castsi256_si512(a1), b1, 1);
            std::uint32_t* column = b.columns + 4 * std::size_t(x);
            for (int k = 0; k < 4; ++k) {
                const __m512i prefix = _mm512_add_epi32(scan32(limb[k]), carry[k]);
                carry[k] = _mm512_permutexvar_epi32(last, prefix);
                limb[k] = _mm512_add_epi32(prefix, _mm512_load_si512(column + 16 * k));
                _mm512_store_si512(column + 16 * k, limb[k]);
            }
            if (kStore) {
                _mm512_stream_si512(reinterpret_cast<__m512i*>(z_pairs + 2 * x), _mm512_permutex2var_epi32(limb[0], low, limb[1]));
                _mm512_stream_si512(reinterpret_cast<__m512i*>(z_pairs + 2 * x + 16), _mm512_permutex2var_epi32(limb[0], high, limb[1]));
                _mm512_stream_si512(reinterpret_cast<__m512i*>(square_pairs + 2 * x), _mm512_permutex2var_epi32(limb[2], low, limb[3]));
                _mm512_stream_si512(reinterpret_cast<__m512i*>(square_pairs + 2 * x + 16), _mm512_permutex2var_epi32(limb[2], high, limb[3]));
            }
        }
    }
    _mm_sfence();
    if (bad == 0xFFFF) std::puts("(a depth outside [0, 1])");
}

PN_AVX512 __m512i fixed_point(__m512d v)
{
    const __m512d q = _mm512_fmadd_pd(v, _mm512_set1_pd(4294967296.0), _mm512_set1_pd(0.5));
    return _mm512_cvttpd_epu64(_mm512_roundscale_pd(q, _MM_FROUND_TO_NEG_INF));
}

template <bool kStore>
PN_AVX512 void sums64_rows(const Buffers& b, int x0, int x1)
{
    const __m512i last = _mm512_set1_epi64(7);
    const std::size_t n = std::size_t(b.n);
    auto* table = reinterpret_cast<std::uint64_t*>(b.table);
    auto* columns = reinterpret_cast<std::uint64_t*>(b.columns);
    __mmask16 bad = 0;
    for (std::size_t y = 0; y < n; ++y) {
        const float* row = b.depth + y * n;
        std::uint64_t* z_sums = table + y * n;
        std::uint64_t* square_sums = z_sums + n * n;
        __m512i carry[2] = {_mm512_setzero_si512(), _mm512_setzero_si512()};
        for (int x = x0; x < x1; x += 16) {
            const __m512 z = clamped_depth(row, x, &bad);
            const __m512d lo = _mm512_cvtps_pd(_mm512_castps512_ps256(z));
            const __m512d hi = _mm512_cvtps_pd(_mm512_extractf32x8_ps(z, 1));
            __m512i v[4] = {scan64(fixed_point(lo)), scan64(fixed_point(hi)), scan64(fixed_point(_mm512_mul_pd(lo, lo))),
                            scan64(fixed_point(_mm512_mul_pd(hi, hi)))};
            std::uint64_t* column = columns + 2 * std::size_t(x);
            for (int k = 0; k < 2; ++k) {
                v[2 * k] = _mm512_add_epi64(v[2 * k], carry[k]);
                v[2 * k + 1] = _mm512_add_epi64(v[2 * k + 1], _mm512_permutexvar_epi64(last, v[2 * k]));
                carry[k] = _mm512_permutexvar_epi64(last, v[2 * k + 1]);
            }
            for (int k = 0; k < 4; ++k) {
                v[k] = _mm512_add_epi64(v[k], _mm512_load_si512(column + 8 * k));
                _mm512_store_si512(column + 8 * k, v[k]);
            }
            if (kStore) {
                _mm512_stream_si512(reinterpret_cast<__m512i*>(z_sums + x), v[0]);
                _mm512_stream_si512(reinterpret_cast<__m512i*>(z_sums + x + 8), v[1]);
                _mm512_stream_si512(reinterpret_cast<__m512i*>(square_sums + x), v[2]);
                _mm512_stream_si512(reinterpret_cast<__m512i*>(square_sums + x + 8), v[3]);
            }
        }
    }
    _mm_sfence();
    if (bad == 0xFFFF) std::puts("(a depth outside [0, 1])");
}

// The map read and the pairs streamed into two planes, no arithmetic.
PN_AVX512 void traffic_rows(const Buffers& b, int x0, int x1)
{
    const std::size_t n = std::size_t(b.n);
    for (std::size_t y = 0; y < n; ++y) {
        const float* row = b.depth + y * n;
        std::uint32_t* first = b.table + 2 * y * n;
        std::uint32_t* second = first + 2 * n * n;
        for (int x = x0; x < x1; x += 16) {
            const __m512i bits = _mm512_castps_si512(_mm512_loadu_ps(row + x));
            const __m512i a = _mm512_unpacklo_epi32(bits, bits), c = _mm512_unpackhi_epi32(bits, bits);
            _mm512_stream_si512(reinterpret_cast<__m512i*>(first + 2 * x), a);
            _mm512_stream_si512(reinterpret_cast<__m512i*>(first + 2 * x + 16), c);
            _mm512_stream_si512(reinterpret_cast<__m512i*>(second + 2 * x), c);
            _mm512_stream_si512(reinterpret_cast<__m512i*>(second + 2 * x + 16), a);
        }
    }
    _mm_sfence();
}

// std::memcpy of 10 B/texel (20 B moved), each thread its half of the rows' bytes.
void memcpy_rows(const Buffers& b, int x0, int x1)
{
    const std::size_t bytes = std::size_t(b.n) * std::size_t(b.n) * 10, begin = bytes * std::size_t(x0) / std::size_t(b.n),
                      end = bytes * std::size_t(x1) / std::size_t(b.n);
    constexpr std::size_t kChunk = std::size_t(1) << 20;
    for (std::size_t off = begin; off < end; off += kChunk)
        std::memcpy(b.copy_to + off, b.copy_from + off, std::min(kChunk, end - off));
}

double run_ms(const Rows& rows, const Buffers& b, int threads)
{
    const auto start = std::chrono::steady_clock::now();
    if (threads == 1) {
        rows(b, 0, b.n);
    } else {
        std::thread other([&] { rows(b, 0, b.n / 2); });
        rows(b, b.n / 2, b.n);
        other.join();
    }
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

template <class T>
T* allocate(std::size_t count)
{
    void* p = std::aligned_alloc(64, (count * sizeof(T) + 63) / 64 * 64);
    if (!p) {
        std::fprintf(stderr, "table_build_bounds: out of memory\n");
        std::exit(1);
    }
    std::memset(p, 0, count * sizeof(T));  // every page touched before timing
    return static_cast<T*>(p);
}

}  // namespace

int main(int argc, char** argv)
{
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("avx512dq") || !__builtin_cpu_supports("avx512bw")) {
        std::puts("table_build_bounds: this CPU has no AVX-512 (F, DQ, BW); nothing measured");
        return 0;
    }
    const int n = argc > 1 ? std::atoi(argv[1]) : 4096;
    if (n < 64 || n > 16384 || n % 64 != 0) {
        std::fprintf(stderr, "table_build_bounds: size must be a multiple of 64 in [64, 16384], got %s\n", argv[1]);
        return 2;
    }
    Buffers b;
    b.n = n;
    const std::size_t texels = std::size_t(n) * std::size_t(n);
    b.depth = allocate<float>(texels);
    b.table = allocate<std::uint32_t>(4 * texels);
    b.columns = allocate<std::uint32_t>(4 * std::size_t(n));
    b.copy_from = allocate<char>(10 * texels);
    b.copy_to = allocate<char>(10 * texels);
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (std::size_t i = 0; i < texels; ++i) b.depth[i] = unit(random);

    const std::vector<std::pair<std::string, Rows>> cases{
        {"memcpy of the same bytes", memcpy_rows},
        {"traffic", traffic_rows},
        {"limbs", limb_rows<true>},
        {"limbs, no stores", limb_rows<false>},
        {"sums64", sums64_rows<true>},
        {"sums64, no stores", sums64_rows<false>}};
    std::printf("%dx%d, ms, medians of 9 (1 thread / 2 threads), each case's ratio memcpy / case\n", n, n);
    for (int round = 1; round <= 3; ++round) {
        std::printf("round %d\n", round);
        double memcpy_ms[3] = {};
        for (const auto& [name, rows] : cases) {
            std::printf("  %-26s", name.c_str());
            for (int threads : {1, 2}) {
                std::vector<double> ms;
                for (int i = 0; i < 9; ++i) ms.push_back(run_ms(rows, b, threads));
                std::nth_element(ms.begin(), ms.begin() + 4, ms.end());
                if (name.rfind("memcpy", 0) == 0) memcpy_ms[threads] = ms[4];
                std::printf("  %7.2f (%.2f)", ms[4], memcpy_ms[threads] / ms[4]);
            }
            std::printf("\n");
        }
    }
}
