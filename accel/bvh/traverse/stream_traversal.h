// Streams of incoherent rays over the N-wide layout, after Embree 3's incoherent stream
// traversal (occludedIncoherent in kernels/bvh/bvh_intersector_stream.cpp): up to
// kStreamSize rays of one direction octant walk the tree together as a bit mask, without a
// stack per ray. At a node each active ray runs its own single-ray test of all N child boxes
// (WideBoxTest), and its hit lanes are ORed into one ray mask per child; the children hit by
// any ray are visited with their masks, nearest first in the node's order for the octant
// (WideNode::order; any hit: in lane order). At a leaf each active ray runs its own block
// triangle test; an occluded any-hit ray leaves the stream. Where packets (packet_traversal.h)
// test one box against many rays, which pays only while the rays agree, a stream's cost per
// node is that of its active rays' single-ray tests: it amortises the node's fetch and the
// stack over the rays that reach it, and loses nothing when they scatter.
//
// Answers equal the single-ray traversal's bit for bit: each ray runs WideBoxTest and
// BlockTriangleTest on its own values, and the closest hit's tie rule does not depend on the
// visit order (ClosestHitQuery::record). A closest-hit ray keeps where it enters each child
// pushed for it, so that a child it enters behind its closest hit, found meanwhile, is
// dropped for it when popped, as the single-ray stack drops it (WideStack::dropBeyond).
//
// Counters per ray, as packets count them (docs/architecture.md): N_TR counts each node where
// the ray is active (the root; a node its own box test hit, which when popped it still enters
// before its closest hit so far), N_IT the triangles of the leaves where it is active, as
// testLeafBlocks counts them. The visit order is the stream's, not the ray's: totals differ
// from single-ray totals.
#pragma once

#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/traverse/octant_groups.h"
#include "accel/bvh/traverse/wide_bvh_traversal.h"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <new>
#include <span>
#include <type_traits>

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// Rays per stream: one bit each in a uint64_t mask.
inline constexpr int kStreamSize = 64;

namespace stream_traversal {

// What a ray of a stream keeps for the whole walk: its single-ray tests, its query and its
// tallies.
template <typename Query, bool Robust, int N>
struct StreamRay {
    WideBoxTest<N, false, Robust> boxTest;
    Query query;
    uint64_t steps = 0, tests = 0;
    BlockTriangleTest<Robust> triangleTest;

    explicit StreamRay(const Ray& ray) : boxTest(ray), query(ray), triangleTest(ray) {}
    float tmin() const { return boxTest.RaySlabs<Robust>::tmin; }
};

// Room for up to K objects constructed in place, only as many as a stream has rays (T has no
// default constructor, and a short stream should not pay for K).
template <typename T, int K>
struct Slots {
    static_assert(std::is_trivially_destructible_v<T>);
    alignas(T) std::byte bytes[K * sizeof(T)];
    T& operator[](int k) { return std::launder(reinterpret_cast<T*>(bytes))[k]; }
};

// The rays that hit each child at a node step: ray k's hit lanes become bit k of those children's
// masks, a transpose of the K x N hit bits done ray by ray without a branch (how many children
// a ray hits is not predictable). AVX2 widens the lanes' compare masks to 64 bits and ORs the
// ray's bit in (two registers for N = 8), AVX-512 ORs it into the hit lanes alone; elsewhere
// lane by lane.
template <int N>
struct ChildRays {
    using F = simd::Floats<N>;
#if defined(__AVX512F__) && defined(__AVX512VL__)
    __m512i masks = _mm512_setzero_si512();  // lanes past N stay 0
    static_assert(N == 4 || N == 8);

    [[gnu::always_inline]] void add(typename F::Mask, int hitLanes, int k) {
        masks = _mm512_mask_or_epi64(masks, __mmask8(hitLanes), masks, _mm512_set1_epi64(int64_t(uint64_t(1) << k)));
    }
    [[gnu::always_inline]] void store(uint64_t out[N]) const {
        _mm512_mask_storeu_epi64(out, __mmask8((1 << N) - 1), masks);
    }
#elif defined(__AVX2__) && defined(__FMA__)
    __m256i masks[N / 4] = {};
    static_assert(N == 4 || N == 8);

    [[gnu::always_inline]] void add(typename F::Mask hit, int, int k) {
        const __m256i bit = _mm256_set1_epi64x(int64_t(uint64_t(1) << k));
        const auto orIn = [&](__m256i& four, __m128i lanes) {  // four lanes' 32-bit masks
            four = _mm256_or_si256(four, _mm256_and_si256(bit, _mm256_cvtepi32_epi64(lanes)));
        };
        if constexpr (N == 8) {
            const __m256i lanes = _mm256_castps_si256(hit.m);
            orIn(masks[0], _mm256_castsi256_si128(lanes));
            orIn(masks[1], _mm256_extracti128_si256(lanes, 1));
        } else {
            orIn(masks[0], _mm_castps_si128(hit.m));
        }
    }
    [[gnu::always_inline]] void store(uint64_t out[N]) const {
        for (int i = 0; i < N / 4; ++i) _mm256_storeu_si256(reinterpret_cast<__m256i*>(out) + i, masks[i]);
    }
#else
    uint64_t masks[N] = {};

    [[gnu::always_inline]] void add(typename F::Mask, int hitLanes, int k) {
        for (int c = 0; c < N; ++c) masks[c] |= (uint64_t(1) << k) & (uint64_t(0) - uint64_t(hitLanes >> c & 1));
    }
    [[gnu::always_inline]] void store(uint64_t out[N]) const {
        for (int c = 0; c < N; ++c) out[c] = masks[c];
    }
#endif
};

// A child to visit (a wide_child word) with the rays (a bit mask) that hit it; a closest-hit
// stream keeps their entry distances from `entries` on in its entry pool, in ray order.
struct StreamEntry {
    uint32_t child;
    uint32_t entries;
    uint64_t rays;
};

}  // namespace stream_traversal

// Traces rays[0, count) (0 < count <= kStreamSize; every ray valid with tmin >= 0 and of
// direction octant `octant`; the tree not empty) as one stream, then calls answer(k, query,
// work) for each ray k with its query and its work (queries = 1; its steps and tests when
// Counting).
template <bool Counting, typename Query, bool Robust, int N, typename Answer>
void traceStream(const WideBvh<N>& bvh, const Ray* rays, int count, int octant, Answer&& answer) {
    using namespace stream_traversal;
    constexpr int K = kStreamSize;
    constexpr bool kClosest = !Query::kStopsAtFirstHit;
    using F = simd::Floats<N>;
    Slots<StreamRay<Query, Robust, N>, K> stream;
    for (int k = 0; k < count; ++k) new (&stream[k]) StreamRay<Query, Robust, N>(rays[k]);
    const WideNode<N>* nodes = bvh.nodes.data();
    const WideBoxTest<N, false, Robust>& first = stream[0].boxTest;  // where the octant's near and far bounds lie

    StreamEntry stack[kWideStackSize<N>];
    int size = 0;
    // Closest hit: each pushed child's entry distances of its rays, a stack beside the stack.
    float pool[kClosest ? kWideStackSize<N> * K : 1];
    uint32_t poolSize = 0;
    alignas(64) float entries[kClosest ? K : 1][N];  // the current node's, per ray and child

    uint64_t live = ~uint64_t(0) >> (64 - count);        // rays not yet answered (an any-hit ray leaves when occluded)
    StreamEntry current{wide_child::inner(0), 0, live};  // the root
    for (;;) {
        const uint64_t active = current.rays;
        if (wide_child::isLeaf(current.child)) {
            for (uint64_t m = active; m != 0; m &= m - 1) {
                const int k = std::countr_zero(m);
                StreamRay<Query, Robust, N>& r = stream[k];
                if constexpr (Counting) ++r.steps;
                if (testLeafBlocks<Counting>(r.query, r.triangleTest, bvh, current.child, r.tmin(), r.tests))
                    live &= ~(uint64_t(1) << k);
            }
            if (live == 0) break;
        } else {
            const WideNode<N>& node = nodes[current.child];
            F nearBounds[3], farBounds[3];  // every ray's of the stream (one octant)
            for (int a = 0; a < 3; ++a) {
                nearBounds[a] = F::load(WideBoxTest<N, false, Robust>::bounds(node, first.nearOffset[a]));
                farBounds[a] = F::load(WideBoxTest<N, false, Robust>::bounds(node, first.farOffset[a]));
            }
            ChildRays<N> hitBy;
            int hitLanes = 0;  // the children hit by any ray
            for (uint64_t m = active; m != 0; m &= m - 1) {
                const int k = std::countr_zero(m);
                StreamRay<Query, Robust, N>& r = stream[k];
                if constexpr (Counting) ++r.steps;
                const auto hits = r.boxTest.test(nearBounds, farBounds, F::broadcast(r.query.tmax));
                if constexpr (kClosest) hits.entry.storeu(entries[k]);
                const int lanes = movemask(hits.mask);
                hitBy.add(hits.mask, lanes, k);
                hitLanes |= lanes;
            }
            alignas(64) uint64_t childRays[N];
            hitBy.store(childRays);
            // The children hit: closest hit far to near for the octant, any hit in lane order.
            int order[N];
            int hitCount = 0;
            for (int p = 0; p < N; ++p) {
                const int c = kClosest ? int(node.order[p] >> (3 * octant) & 7) : p;
                order[hitCount] = c;
                hitCount += hitLanes >> c & 1;
            }
            if (hitCount != 0) {
                // Closest hit: the nearest next, the others pushed far to near. Any hit: the
                // first in lane order next.
                const int next = kClosest ? hitCount - 1 : 0;
                assert(size + hitCount - 1 <= kWideStackSize<N>);
                for (int j = 0; j < hitCount; ++j) {
                    if (j == next) continue;
                    const int c = order[j];
                    stack[size++] = {node.child[c], poolSize, childRays[c]};
                    if constexpr (kClosest) {
                        for (uint64_t m = childRays[c]; m != 0; m &= m - 1)
                            pool[poolSize++] = entries[std::countr_zero(m)][c];
                    }
                }
                const int c = order[next];
                current = {node.child[c], 0, childRays[c]};
                continue;
            }
        }
        // Pop the next child that one of its rays still enters before its closest hit (any
        // hit: that is not yet occluded).
        bool popped = false;
        while (!popped && size > 0) {
            current = stack[--size];
            if constexpr (kClosest) {
                poolSize = current.entries;
                uint64_t entering = 0;
                const float* entry = pool + current.entries;
                for (uint64_t m = current.rays; m != 0; m &= m - 1) {
                    const int k = std::countr_zero(m);
                    entering |= uint64_t(*entry++ <= stream[k].query.tmax) << k;
                }
                current.rays = entering;
            } else {
                current.rays &= live;
            }
            popped = current.rays != 0;
        }
        if (!popped) break;
    }
    for (int k = 0; k < count; ++k) {
        QueryCounters work;
        work.queries = 1;
        if constexpr (Counting) work.traversalSteps = stream[k].steps, work.intersectionTests = stream[k].tests;
        answer(k, stream[k].query, work);
    }
}

// A batch: its valid rays with tmin >= 0 in streams of up to kStreamSize of one direction
// octant, the others alone (octant_groups.h). Calls answer(i, query, work) once per ray i, not
// in order, with its query and its work (queries = 1).
template <bool Counting, typename Query, bool Robust, int N, typename Answer>
void traceAsStreams(const WideBvh<N>& bvh, std::span<const Ray> rays, Answer&& answer) {
    traceInOctantGroups<Counting, Query, Robust, kStreamSize>(
        bvh, rays,
        [&](const Ray* group, int count, int octant, auto&& answerInGroup) {
            traceStream<Counting, Query, Robust>(bvh, group, count, octant, answerInGroup);
        },
        answer);
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
