// The stack of the wide layouts' single-ray traversal (wide_bvh_traversal.h): child words and
// entry distances in separate arrays, filled a node's hit children at a time without a branch
// per child. A closest-hit step visits the nearest child next (a vector minimum) and pushes the
// others far to near in the node's order for the ray's octant (WideNode::order): one
// permutation and a compression, as tinybvh's BVH8_CPU does, instead of sorting distances.
// (The octant order alone for the next child too visited 13 % more triangles on sibenik's
// primary rays.) An any-hit step pushes them in lane order and stores no distances.
#pragma once

#include "accel/bvh/layout/wide_bvh.h"
#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/simd/simd.h"

#include <array>
#include <bit>
#include <cstdint>
#include <type_traits>

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// Each step pops one entry and pushes at most N: the stack never holds more than N - 1 per
// level plus one (the wide tree is no deeper than the binary one).
template <int N>
inline constexpr int kWideStackSize = (N - 1) * kBvhMaxDepth + 1;

template <int N>
struct WideStack {
    // N more than the stack ever holds: a step stores whole vectors past the top.
    uint32_t child[kWideStackSize<N> + N];
    float entry[kWideStackSize<N> + N];
    int size = 0;

    uint32_t pop() { return child[--size]; }

    // Drops the children the ray enters behind t (a closest hit at t was just found), keeping the
    // order of the others.
    [[gnu::always_inline]] void dropBeyond(float t) {
        int kept = 0;
        for (int i = 0; i < size; ++i) {
            child[kept] = child[i];
            entry[kept] = entry[i];
            kept += entry[i] <= t ? 1 : 0;
        }
        size = kept;
    }
};

namespace wide_stack {

// kCompress[m]: the indices of the set bits of m, ascending, one per byte (8-lane compression
// by a permutation where AVX-512 has no vpcompressd).
inline constexpr std::array<uint64_t, 256> kCompress = [] {
    std::array<uint64_t, 256> table{};
    for (int m = 0; m < 256; ++m) {
        int k = 0;
        for (int i = 0; i < 8; ++i)
            if (m >> i & 1) table[m] |= uint64_t(i) << (8 * k++);
    }
    return table;
}();

#if defined(__AVX2__) && defined(__FMA__)
// The lanes of `index` in the positions of the set bits of m, first ones first.
[[gnu::always_inline]] inline __m256i compress(__m256i index, int m) {
#if defined(__AVX512VL__)
    return _mm256_maskz_compress_epi32(__mmask8(m), index);
#else
    const __m256i positions = _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&kCompress[m])));
    return _mm256_permutevar8x32_epi32(index, positions);
#endif
}
#endif

}  // namespace wide_stack

// The lane of the least entry among the lanes in `hit` (`mask` in lanes, not 0), the lowest of
// equal ones.
template <typename F>
[[gnu::always_inline]] inline int nearestLane(F entry, typename F::Mask hit, int mask) {
#if defined(__AVX2__) && defined(__FMA__)
    if constexpr (std::is_same_v<F, simd::Avx>) {
        const __m256 e = _mm256_blendv_ps(_mm256_set1_ps(kInfinity), entry.v, hit.m);
        __m256 least = _mm256_min_ps(e, _mm256_permute2f128_ps(e, e, 1));
        least = _mm256_min_ps(least, _mm256_permute_ps(least, 0x4E));
        least = _mm256_min_ps(least, _mm256_permute_ps(least, 0xB1));
        return __builtin_ctz(unsigned(_mm256_movemask_ps(_mm256_cmp_ps(e, least, _CMP_EQ_OQ)) & mask));
    }
#endif
    (void)hit;
    alignas(64) float entries[F::kLanes];
    entry.storeu(entries);
    int nearest = __builtin_ctz(unsigned(mask));
    for (int m = mask & (mask - 1); m != 0; m &= m - 1) {
        const int lane = __builtin_ctz(unsigned(m));
        if (entries[lane] < entries[nearest]) nearest = lane;
    }
    return nearest;
}

// Of the children of `node` in `mask` (at least two), returns the nearest (by where the ray
// enters them: `entry`, and `hit` is `mask` in lanes) and pushes the others far to near in the
// node's order for the ray's octant (`shift` = 3 * octant): the next child is always the
// nearest, the order of the rest is the octant's estimate.
template <int N, typename F>
[[gnu::always_inline]] inline uint32_t visitNearestPushOthers(const WideNode<N>& node, int mask, typename F::Mask hit,
                                                              F entry, int shift, WideStack<N>& stack) {
    const int nearest = nearestLane(entry, hit, mask);
    const int others = mask & ~(1 << nearest);
#if defined(__AVX2__) && defined(__FMA__)
    if constexpr (N == 8 && std::is_same_v<F, simd::Avx>) {
        const __m256i order =
            _mm256_srl_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(node.order)), _mm_cvtsi32_si128(shift));
        // Bit p of `ordered`: the child at position p is pushed.
        const __m256i lanes = _mm256_and_si256(order, _mm256_set1_epi32(7));
        const __m256i bits = _mm256_sllv_epi32(_mm256_set1_epi32(1), lanes);
        const int ordered = _mm256_movemask_ps(
            _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(bits, _mm256_set1_epi32(others)), bits)));
        const __m256i index = wide_stack::compress(order, ordered);
        const __m256i children = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.child));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(stack.child + stack.size),
                            _mm256_permutevar8x32_epi32(children, index));
        _mm256_storeu_ps(stack.entry + stack.size, _mm256_permutevar8x32_ps(entry.v, index));
        stack.size += std::popcount(unsigned(others));
        return node.child[nearest];
    }
#endif
    alignas(64) float entries[N];
    entry.storeu(entries);
    for (int p = 0; p < N; ++p) {
        const int lane = int(node.order[p] >> shift & 7);
        stack.child[stack.size] = node.child[lane];
        stack.entry[stack.size] = entries[lane];
        stack.size += others >> lane & 1;
    }
    return node.child[nearest];
}

// Pushes the children of `node` in `mask` (not 0) in lane order, without distances: an any-hit
// query visits children in no particular order.
template <int N>
[[gnu::always_inline]] inline void pushInLaneOrder(const WideNode<N>& node, int mask, WideStack<N>& stack) {
#if defined(__AVX2__) && defined(__FMA__)
    if constexpr (N == 8) {
        const __m256i children = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.child));
        const __m256i lanes = wide_stack::compress(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), mask);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(stack.child + stack.size),
                            _mm256_permutevar8x32_epi32(children, lanes));
        stack.size += std::popcount(unsigned(mask));
        return;
    }
#endif
    for (int lane = 0; lane < N; ++lane) {
        stack.child[stack.size] = node.child[lane];
        stack.size += mask >> lane & 1;
    }
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
