// Every operation of the SIMD layer's API on lanes a, b and c, its results as bits, in a fixed
// order: what the backend test (test_simd.cpp) compares between a vector backend and
// Scalar<N>. A header, so that a test object compiled for another ISA (simd_ops_avx512.cpp)
// runs it on that ISA's backend; in the kernel namespace and free of the standard library's
// templates, so that such an object shares no code with the rest under one name.
#pragma once

#include "accel/bvh/simd/simd.h"

#include <bit>
#include <cstdint>

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// How many results simdOpResults<F> writes: 13 float operations and the truncation of N lanes
// each, 7 masks, and loadLast3's 4 lanes where N is 4.
constexpr int simdOpResultCount(int n) { return 14 * n + 7 + (n == 4 ? 4 : 0); }

// a, b: any floats (NaN, inf, signed zeros, denormals); c: finite, in int32's range (truncated).
template <typename F>
void simdOpResults(const float* a, const float* b, const float* c, uint32_t* out) {
    constexpr int N = F::kLanes;
    const F va = F::loadu(a), vb = F::loadu(b);
    const auto put = [&out](const F& v) {
        alignas(64) float lanes[N];
        v.storeu(lanes);
        for (int i = 0; i < N; ++i) *out++ = std::bit_cast<uint32_t>(lanes[i]);
    };
    put(va + vb), put(va - vb), put(va * vb), put(va / vb);
    put(differenceOfProducts(va, vb, vb, vb * va));
    put(fmadd(va, vb, vb * va)), put(fmsub(va, vb, vb * va));
    put(abs(va)), put(min(va, vb)), put(max(va, vb));
    put(select(va >= vb, va, vb)), put(F::broadcast(a[0]));
    put(F::load(a));  // a is aligned for N lanes
    const int masks[] = {movemask(va <= vb),
                         movemask(va >= vb),
                         movemask(va < vb),
                         movemask(va > vb),
                         movemask(va != vb),
                         movemask((va < vb) & (va != vb)),
                         movemask((va < vb) | (va > vb))};
    for (int m : masks) *out++ = uint32_t(m);
    int32_t truncated[N];
    F::loadu(c).truncateToInt(truncated);
    for (int i = 0; i < N; ++i) *out++ = uint32_t(truncated[i]);
    if constexpr (N == 4) put(F::loadLast3(a + 1));
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
