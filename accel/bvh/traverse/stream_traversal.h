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
    Slots<StreamRay<Query, Robust, N>, K> stream;
    for (int k = 0; k < count; ++k) new (&stream[k]) StreamRay<Query, Robust, N>(rays[k]);
    const WideNode<N>* nodes = bvh.nodes.data();

    StreamEntry stack[kWideStackSize<N>];
    int size = 0;
    // Closest hit: each pushed child's entry distances of its rays, a stack beside the stack.
    float pool[kClosest ? kWideStackSize<N> * K : 1];
    uint32_t poolSize = 0;
    alignas(64) float entries[kClosest ? K : 1][N];  // the current node's, per ray and child

    uint64_t live = ~uint64_t(0) >> (K - count);  // rays not yet answered (an any-hit ray leaves when occluded)
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
            uint64_t childRays[N]{};
            for (uint64_t m = active; m != 0; m &= m - 1) {
                const int k = std::countr_zero(m);
                StreamRay<Query, Robust, N>& r = stream[k];
                if constexpr (Counting) ++r.steps;
                int hits;
                if constexpr (kClosest) {
                    hits = r.boxTest.intersect(node, r.query.tmax, entries[k]);
                } else {
                    hits = movemask(r.boxTest.test(node, simd::Floats<N>::broadcast(r.query.tmax)).mask);
                }
                for (; hits != 0; hits &= hits - 1) childRays[std::countr_zero(unsigned(hits))] |= uint64_t(1) << k;
            }
            int order[N];  // the children hit: closest hit far to near for the octant, any hit in lane order
            int hitCount = 0;
            for (int p = 0; p < N; ++p) {
                const int c = kClosest ? int(node.order[p] >> (3 * octant) & 7) : p;
                if (childRays[c] != 0) order[hitCount++] = c;
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
                        for (uint64_t m = childRays[c]; m != 0; m &= m - 1) pool[poolSize++] = entries[std::countr_zero(m)][c];
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
