// The one SIMD layer of the BVH build and traversal: a few float operations on N lanes, in
// three backends of the same API:
//   Scalar<N>  plain C++, any N, any target: the reference, and what BVH::simd=false runs;
//   Sse        4 lanes of SSE2, which every x86-64 CPU has;
//   Avx        8 lanes of AVX2 with FMA (only where __AVX2__ and __FMA__, e.g. -march=native);
//   Avx512     16 lanes of AVX-512 (only where __AVX512F__, __AVX512DQ__ and __AVX512VL__).
// Floats<N> is the best backend for N lanes on this target (Scalar<N> where there is none).
// Every operation is one IEEE operation per lane, so the backends agree bit for bit (a test
// runs them side by side, NaN and inf included): no tree and no hit depends on the backend.
#pragma once

#include "accel/bvh/simd/kernel_namespace.h"

#include <cmath>
#include <cstdint>
#include <type_traits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {
namespace simd {

// The NaN rule of every min and max in the BVH, that of SSE's minps/maxps: the second operand
// unless the first compares less (greater). So min(NaN, b) = b, min(a, NaN) = NaN and
// min(+0, -0) = -0. The box tests rely on it to drop NaN slab distances (box_test.h).
inline float min(float a, float b) { return a < b ? a : b; }
inline float max(float a, float b) { return a > b ? a : b; }
// a * b - c rounded once, for the one-lane (float) form of a formula.
inline float fmsub(float a, float b, float c) { return std::fma(a, b, -c); }

// Plain float as a one-lane backend, so that a formula written once serves the binary
// traversal's scalar box test and the wide one's lanes (box_test.h).
template <typename F>
F broadcast(float x) {
    if constexpr (std::is_same_v<F, float>) {
        return x;
    } else {
        return F::broadcast(x);
    }
}
inline float select(bool m, float a, float b) { return m ? a : b; }

template <int N>
struct Scalar {
    static constexpr int kLanes = N;
    struct Mask {
        uint32_t bits;  // lane i in bit i
        friend Mask operator&(Mask a, Mask b) { return {a.bits & b.bits}; }
        friend Mask operator|(Mask a, Mask b) { return {a.bits | b.bits}; }
    };
    float lane[N];

    static Scalar load(const float* p) { return loadu(p); }
    static Scalar loadu(const float* p) {
        Scalar v;
        for (int i = 0; i < N; ++i) v.lane[i] = p[i];
        return v;
    }
    static Scalar broadcast(float x) {
        Scalar v;
        for (int i = 0; i < N; ++i) v.lane[i] = x;
        return v;
    }
    // Lanes 0-2 = p[0..2], lane 3 = p[2]; may read p[-1], never past p[2]: the last vertex
    // of a triangle that may end its array.
    static Scalar loadLast3(const float* p) requires(N == 4) { return {{p[0], p[1], p[2], p[2]}}; }
    void store(float* p) const { storeu(p); }
    void storeu(float* p) const {
        for (int i = 0; i < N; ++i) p[i] = lane[i];
    }
    // Truncation towards zero; lanes must lie in int32's range (no NaN).
    void truncateToInt(int32_t* out) const {
        for (int i = 0; i < N; ++i) out[i] = int32_t(lane[i]);
    }

    template <typename Op>
    friend Scalar zipWith(Scalar a, Scalar b, Op op) {
        for (int i = 0; i < N; ++i) a.lane[i] = op(a.lane[i], b.lane[i]);
        return a;
    }
    friend Scalar operator+(Scalar a, Scalar b) {
        return zipWith(a, b, [](float x, float y) { return x + y; });
    }
    friend Scalar operator-(Scalar a, Scalar b) {
        return zipWith(a, b, [](float x, float y) { return x - y; });
    }
    friend Scalar operator*(Scalar a, Scalar b) {
        return zipWith(a, b, [](float x, float y) { return x * y; });
    }
    friend Scalar operator/(Scalar a, Scalar b) {
        return zipWith(a, b, [](float x, float y) { return x / y; });
    }
    // float(double(a) * double(b) - double(c) * double(d)): both products are exact in double,
    // so the result's sign is that of the exact difference, and 0 only when it is 0.
    friend Scalar differenceOfProducts(Scalar a, Scalar b, Scalar c, Scalar d) {
        for (int i = 0; i < N; ++i)
            a.lane[i] = float(double(a.lane[i]) * double(b.lane[i]) - double(c.lane[i]) * double(d.lane[i]));
        return a;
    }
    // a * b + c and a * b - c, each rounded once (std::fma).
    friend Scalar fmadd(Scalar a, Scalar b, Scalar c) {
        for (int i = 0; i < N; ++i) a.lane[i] = std::fma(a.lane[i], b.lane[i], c.lane[i]);
        return a;
    }
    friend Scalar fmsub(Scalar a, Scalar b, Scalar c) {
        for (int i = 0; i < N; ++i) a.lane[i] = std::fma(a.lane[i], b.lane[i], -c.lane[i]);
        return a;
    }
    friend Scalar abs(Scalar a) {
        for (int i = 0; i < N; ++i) a.lane[i] = std::abs(a.lane[i]);
        return a;
    }
    friend Scalar min(Scalar a, Scalar b) {
        return zipWith(a, b, [](float x, float y) { return simd::min(x, y); });
    }
    friend Scalar max(Scalar a, Scalar b) {
        return zipWith(a, b, [](float x, float y) { return simd::max(x, y); });
    }
    friend Mask operator<=(Scalar a, Scalar b) {
        Mask m{0};
        for (int i = 0; i < N; ++i) m.bits |= uint32_t(a.lane[i] <= b.lane[i]) << i;
        return m;
    }
    friend Mask operator>=(Scalar a, Scalar b) { return b <= a; }
    friend Mask operator<(Scalar a, Scalar b) {
        Mask m{0};
        for (int i = 0; i < N; ++i) m.bits |= uint32_t(a.lane[i] < b.lane[i]) << i;
        return m;
    }
    friend Mask operator>(Scalar a, Scalar b) { return b < a; }
    // Unordered: true on NaN, as the scalar !=.
    friend Mask operator!=(Scalar a, Scalar b) {
        Mask m{0};
        for (int i = 0; i < N; ++i) m.bits |= uint32_t(a.lane[i] != b.lane[i]) << i;
        return m;
    }
    friend int movemask(Mask m) { return int(m.bits); }
    // Lane by lane: a where the mask is set, else b.
    friend Scalar select(Mask m, Scalar a, Scalar b) {
        for (int i = 0; i < N; ++i) a.lane[i] = (m.bits >> i & 1) ? a.lane[i] : b.lane[i];
        return a;
    }
};

#if defined(__SSE2__)
struct Sse {
    static constexpr int kLanes = 4;
    struct Mask {
        __m128 m;
        friend Mask operator&(Mask a, Mask b) { return {_mm_and_ps(a.m, b.m)}; }
        friend Mask operator|(Mask a, Mask b) { return {_mm_or_ps(a.m, b.m)}; }
    };
    __m128 v;

    static Sse load(const float* p) { return {_mm_load_ps(p)}; }  // p 16-byte aligned
    static Sse loadu(const float* p) { return {_mm_loadu_ps(p)}; }
    static Sse broadcast(float x) { return {_mm_set1_ps(x)}; }
    static Sse loadLast3(const float* p) {
        const __m128 shifted = _mm_loadu_ps(p - 1);
        return {_mm_shuffle_ps(shifted, shifted, _MM_SHUFFLE(3, 3, 2, 1))};
    }
    void store(float* p) const { _mm_store_ps(p, v); }
    void storeu(float* p) const { _mm_storeu_ps(p, v); }
    void truncateToInt(int32_t* out) const { _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_cvttps_epi32(v)); }

    friend Sse operator+(Sse a, Sse b) { return {_mm_add_ps(a.v, b.v)}; }
    friend Sse operator-(Sse a, Sse b) { return {_mm_sub_ps(a.v, b.v)}; }
    friend Sse operator*(Sse a, Sse b) { return {_mm_mul_ps(a.v, b.v)}; }
    friend Sse operator/(Sse a, Sse b) { return {_mm_div_ps(a.v, b.v)}; }
    friend Sse differenceOfProducts(Sse a, Sse b, Sse c, Sse d) {
#if defined(__AVX__)
        const __m256d ab = _mm256_mul_pd(_mm256_cvtps_pd(a.v), _mm256_cvtps_pd(b.v));
        const __m256d cd = _mm256_mul_pd(_mm256_cvtps_pd(c.v), _mm256_cvtps_pd(d.v));
        return {_mm256_cvtpd_ps(_mm256_sub_pd(ab, cd))};
#else
        const auto half = [](__m128 a, __m128 b, __m128 c, __m128 d) {
            return _mm_cvtpd_ps(
                _mm_sub_pd(_mm_mul_pd(_mm_cvtps_pd(a), _mm_cvtps_pd(b)), _mm_mul_pd(_mm_cvtps_pd(c), _mm_cvtps_pd(d))));
        };
        const auto high = [](__m128 x) { return _mm_movehl_ps(x, x); };
        return {_mm_movelh_ps(half(a.v, b.v, c.v, d.v), half(high(a.v), high(b.v), high(c.v), high(d.v)))};
#endif
    }
#if defined(__FMA__)
    friend Sse fmadd(Sse a, Sse b, Sse c) { return {_mm_fmadd_ps(a.v, b.v, c.v)}; }
    friend Sse fmsub(Sse a, Sse b, Sse c) { return {_mm_fmsub_ps(a.v, b.v, c.v)}; }
#else  // no fused multiply-add in hardware: std::fma lane by lane, slow but bit for bit the same
    friend Sse fmadd(Sse a, Sse b, Sse c) {
        return viaScalar(a, b, c, [](auto x, auto y, auto z) { return fmadd(x, y, z); });
    }
    friend Sse fmsub(Sse a, Sse b, Sse c) {
        return viaScalar(a, b, c, [](auto x, auto y, auto z) { return fmsub(x, y, z); });
    }
    template <typename Op>
    static Sse viaScalar(Sse a, Sse b, Sse c, Op op) {
        Scalar<4> x, y, z;
        a.storeu(x.lane), b.storeu(y.lane), c.storeu(z.lane);
        return loadu(op(x, y, z).lane);
    }
#endif
    friend Sse abs(Sse a) { return {_mm_andnot_ps(_mm_set1_ps(-0.0f), a.v)}; }
    friend Sse min(Sse a, Sse b) { return {_mm_min_ps(a.v, b.v)}; }
    friend Sse max(Sse a, Sse b) { return {_mm_max_ps(a.v, b.v)}; }
    friend Mask operator<=(Sse a, Sse b) { return {_mm_cmple_ps(a.v, b.v)}; }
    friend Mask operator>=(Sse a, Sse b) { return {_mm_cmpge_ps(a.v, b.v)}; }
    friend Mask operator<(Sse a, Sse b) { return {_mm_cmplt_ps(a.v, b.v)}; }
    friend Mask operator>(Sse a, Sse b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
    friend Mask operator!=(Sse a, Sse b) { return {_mm_cmpneq_ps(a.v, b.v)}; }  // true on NaN
    friend int movemask(Mask m) { return _mm_movemask_ps(m.m); }
    friend Sse select(Mask m, Sse a, Sse b) { return {_mm_or_ps(_mm_and_ps(m.m, a.v), _mm_andnot_ps(m.m, b.v))}; }
};
#endif

#if defined(__AVX2__) && defined(__FMA__)
struct Avx {
    static constexpr int kLanes = 8;
    struct Mask {
        __m256 m;
        friend Mask operator&(Mask a, Mask b) { return {_mm256_and_ps(a.m, b.m)}; }
        friend Mask operator|(Mask a, Mask b) { return {_mm256_or_ps(a.m, b.m)}; }
    };
    __m256 v;

    static Avx load(const float* p) { return {_mm256_load_ps(p)}; }  // p 32-byte aligned
    static Avx loadu(const float* p) { return {_mm256_loadu_ps(p)}; }
    static Avx broadcast(float x) { return {_mm256_set1_ps(x)}; }
    void store(float* p) const { _mm256_store_ps(p, v); }
    void storeu(float* p) const { _mm256_storeu_ps(p, v); }
    void truncateToInt(int32_t* out) const {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_cvttps_epi32(v));
    }

    friend Avx operator+(Avx a, Avx b) { return {_mm256_add_ps(a.v, b.v)}; }
    friend Avx operator-(Avx a, Avx b) { return {_mm256_sub_ps(a.v, b.v)}; }
    friend Avx operator*(Avx a, Avx b) { return {_mm256_mul_ps(a.v, b.v)}; }
    friend Avx operator/(Avx a, Avx b) { return {_mm256_div_ps(a.v, b.v)}; }
    friend Avx differenceOfProducts(Avx a, Avx b, Avx c, Avx d) {
        const auto half = [](__m128 a, __m128 b, __m128 c, __m128 d) {
            return _mm256_cvtpd_ps(_mm256_sub_pd(_mm256_mul_pd(_mm256_cvtps_pd(a), _mm256_cvtps_pd(b)),
                                                 _mm256_mul_pd(_mm256_cvtps_pd(c), _mm256_cvtps_pd(d))));
        };
        const auto lo = [](__m256 x) { return _mm256_castps256_ps128(x); };
        const auto hi = [](__m256 x) { return _mm256_extractf128_ps(x, 1); };
        return {_mm256_set_m128(half(hi(a.v), hi(b.v), hi(c.v), hi(d.v)), half(lo(a.v), lo(b.v), lo(c.v), lo(d.v)))};
    }
    // AVX2 machines have FMA (the two came together); -march=native defines both.
    friend Avx fmadd(Avx a, Avx b, Avx c) { return {_mm256_fmadd_ps(a.v, b.v, c.v)}; }
    friend Avx fmsub(Avx a, Avx b, Avx c) { return {_mm256_fmsub_ps(a.v, b.v, c.v)}; }
    friend Avx abs(Avx a) { return {_mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.v)}; }
    friend Avx min(Avx a, Avx b) { return {_mm256_min_ps(a.v, b.v)}; }
    friend Avx max(Avx a, Avx b) { return {_mm256_max_ps(a.v, b.v)}; }
    // Ordered predicates: false on NaN, as the scalar <= and SSE's cmpleps.
    friend Mask operator<=(Avx a, Avx b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)}; }
    friend Mask operator>=(Avx a, Avx b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ)}; }
    friend Mask operator<(Avx a, Avx b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)}; }
    friend Mask operator>(Avx a, Avx b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
    friend Mask operator!=(Avx a, Avx b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_NEQ_UQ)}; }  // true on NaN
    friend int movemask(Mask m) { return _mm256_movemask_ps(m.m); }
    friend Avx select(Mask m, Avx a, Avx b) { return {_mm256_blendv_ps(b.v, a.v, m.m)}; }
};
#endif

#if defined(__AVX512F__) && defined(__AVX512DQ__) && defined(__AVX512VL__)
// GCC 12's AVX-512 intrinsics start from _mm512_undefined_*(), which -Wuninitialized and
// -Wmaybe-uninitialized report once inlined (GCC bug 105593, fixed in 13): not ours to fix.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
struct Avx512 {
    static constexpr int kLanes = 16;
    struct Mask {
        __mmask16 m;  // lane i in bit i
        friend Mask operator&(Mask a, Mask b) { return {__mmask16(a.m & b.m)}; }
        friend Mask operator|(Mask a, Mask b) { return {__mmask16(a.m | b.m)}; }
    };
    __m512 v;

    static Avx512 load(const float* p) { return {_mm512_load_ps(p)}; }  // p 64-byte aligned
    static Avx512 loadu(const float* p) { return {_mm512_loadu_ps(p)}; }
    static Avx512 broadcast(float x) { return {_mm512_set1_ps(x)}; }
    void store(float* p) const { _mm512_store_ps(p, v); }
    void storeu(float* p) const { _mm512_storeu_ps(p, v); }
    void truncateToInt(int32_t* out) const { _mm512_storeu_si512(out, _mm512_cvttps_epi32(v)); }

    friend Avx512 operator+(Avx512 a, Avx512 b) { return {_mm512_add_ps(a.v, b.v)}; }
    friend Avx512 operator-(Avx512 a, Avx512 b) { return {_mm512_sub_ps(a.v, b.v)}; }
    friend Avx512 operator*(Avx512 a, Avx512 b) { return {_mm512_mul_ps(a.v, b.v)}; }
    friend Avx512 operator/(Avx512 a, Avx512 b) { return {_mm512_div_ps(a.v, b.v)}; }
    friend Avx512 differenceOfProducts(Avx512 a, Avx512 b, Avx512 c, Avx512 d) {
        const auto half = [](__m256 a, __m256 b, __m256 c, __m256 d) {
            return _mm512_cvtpd_ps(_mm512_sub_pd(_mm512_mul_pd(_mm512_cvtps_pd(a), _mm512_cvtps_pd(b)),
                                                 _mm512_mul_pd(_mm512_cvtps_pd(c), _mm512_cvtps_pd(d))));
        };
        const auto lo = [](__m512 x) { return _mm512_castps512_ps256(x); };
        const auto hi = [](__m512 x) { return _mm512_extractf32x8_ps(x, 1); };
        const __m256 low = half(lo(a.v), lo(b.v), lo(c.v), lo(d.v));
        const __m256 high = half(hi(a.v), hi(b.v), hi(c.v), hi(d.v));
        return {_mm512_insertf32x8(_mm512_castps256_ps512(low), high, 1)};
    }
    friend Avx512 fmadd(Avx512 a, Avx512 b, Avx512 c) { return {_mm512_fmadd_ps(a.v, b.v, c.v)}; }
    friend Avx512 fmsub(Avx512 a, Avx512 b, Avx512 c) { return {_mm512_fmsub_ps(a.v, b.v, c.v)}; }
    friend Avx512 abs(Avx512 a) { return {_mm512_abs_ps(a.v)}; }
    // vminps/vmaxps: the second operand when either is NaN, as minps.
    friend Avx512 min(Avx512 a, Avx512 b) { return {_mm512_min_ps(a.v, b.v)}; }
    friend Avx512 max(Avx512 a, Avx512 b) { return {_mm512_max_ps(a.v, b.v)}; }
    friend Mask operator<=(Avx512 a, Avx512 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ)}; }
    friend Mask operator>=(Avx512 a, Avx512 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GE_OQ)}; }
    friend Mask operator<(Avx512 a, Avx512 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LT_OQ)}; }
    friend Mask operator>(Avx512 a, Avx512 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GT_OQ)}; }
    friend Mask operator!=(Avx512 a, Avx512 b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_NEQ_UQ)}; }  // true on NaN
    friend int movemask(Mask m) { return int(m.m); }
    friend Avx512 select(Mask m, Avx512 a, Avx512 b) { return {_mm512_mask_blend_ps(m.m, b.v, a.v)}; }
};
#pragma GCC diagnostic pop
#endif

namespace detail {
template <int N>
struct Best {
    using type = Scalar<N>;
};
#if defined(__SSE2__)
template <>
struct Best<4> {
    using type = Sse;
};
#endif
#if defined(__AVX2__) && defined(__FMA__)
template <>
struct Best<8> {
    using type = Avx;
};
#endif
#if defined(__AVX512F__) && defined(__AVX512DQ__) && defined(__AVX512VL__)
template <>
struct Best<16> {
    using type = Avx512;
};
#endif
}  // namespace detail

template <int N>
using Floats = typename detail::Best<N>::type;

// Runs f(Floats<4>{}) or, with vector = false (BVH::simd=false), f(Scalar<4>{}): code written
// once against the API, its backend chosen at run time.
template <typename F>
decltype(auto) withFloats4(bool vector, F&& f) {
    if (vector) return f(Floats<4>{});
    return f(Scalar<4>{});
}

}  // namespace simd
}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
