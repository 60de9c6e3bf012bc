// The traversal skeleton of the N-wide layout (wide_bvh.h), for either query: per step one SIMD
// test of a node's N child boxes (box_test.h); of the children hit one is visited next and the
// others are pushed (wide_stack.h). The loop keeps the ray's constants in vector
// registers and inlines the leaf test, so a node step reads the node and nothing else. N_TR
// counts the steps, i.e. wide nodes and leaves visited; Counting = false compiles the counters
// out. BVH::singleStep=octant compiles the loop once per direction octant (as tinybvh's
// BVH8_CPU), the ray's picked once per ray, so that a step finds the near and far bounds at
// fixed offsets (WideBoxTest::test<Octant>) and its stack order at a fixed shift.
#pragma once

#include "accel/bvh/layout/wide_bvh.h"
#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/traverse/box_test.h"
#include "accel/bvh/traverse/traversal.h"
#include "accel/bvh/traverse/triangle_block_test.h"
#include "accel/bvh/traverse/wide_stack.h"

#include <cassert>

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// The skeleton's loop from `current` (a wide_child word: the root, or a node where a packet left
// the ray alone, packet_traversal.h) for a query under way; adds its node steps and triangle
// tests when Counting. Octant: the ray's direction octant (RaySlabs::octant), or kAnyOctant.
template <bool Counting, int Octant = kAnyOctant, typename Query, bool NegativeT, bool Robust, int N>
[[gnu::always_inline]] inline void traverseFrom(const WideBvh<N>& bvh, const WideBoxTest<N, NegativeT, Robust>& boxTest,
                                                const BlockTriangleTest<Robust>& triangleTest, Query& query,
                                                uint32_t current, uint64_t& steps, uint64_t& tests) {
    using F = simd::Floats<N>;
    const WideNode<N>* nodes = bvh.nodes.data();
    const float tmin = boxTest.RaySlabs<Robust>::tmin;
    assert(Octant == kAnyOctant || Octant == boxTest.octant());
    const int shift = 3 * (Octant == kAnyOctant ? boxTest.octant() : Octant);

    WideStack<N> stack;
    for (;;) {
        if constexpr (Counting) ++steps;
        if (!wide_child::isLeaf(current)) {
            const WideNode<N>& node = nodes[current];
            const auto hits = boxTest.template test<Octant>(node, F::broadcast(query.tmax));
            const int mask = movemask(hits.mask);
            if (mask != 0) {
                if ((mask & (mask - 1)) == 0) {  // the common case: one child hit
                    current = node.child[__builtin_ctz(unsigned(mask))];
                    continue;
                }
                // Closest hit: nearest first. Any hit: in lane order, unsorted (as Embree's
                // occlusion traversal).
                if constexpr (Query::kStopsAtFirstHit) {
                    pushInLaneOrder(node, mask, stack);
                    current = stack.pop();
                } else {
                    current = visitNearestPushOthers(node, mask, hits.mask, hits.entry, shift, stack);
                }
                continue;
            }
        } else {
            const float before = query.tmax;
            if (testLeafBlocks<Counting>(query, triangleTest, bvh, current, tmin, tests)) break;
            // A closer hit: the children the ray enters behind it are skipped (an any-hit query
            // never shortens its interval).
            if constexpr (!Query::kStopsAtFirstHit) {
                if (query.tmax < before) stack.dropBeyond(query.tmax);
            }
        }
        if (stack.size == 0) break;
        current = stack.pop();
    }
}

// The skeleton for a ray of direction octant Octant (kAnyOctant: any), from the root. Each
// octant's loop is a function of its own with the ray's constants its own locals, so that they
// live in registers as in the loop for any octant.
template <bool Counting, int Octant, typename Query, bool NegativeT, bool Robust, int N>
Query traverseInOctant(const WideBvh<N>& bvh, const Ray& ray, QueryCounters& counters) {
    const WideBoxTest<N, NegativeT, Robust> boxTest(ray);
    const BlockTriangleTest<Robust> triangleTest(ray);
    Query query(ray);
    uint64_t steps = 0, tests = 0;
    traverseFrom<Counting, Octant>(bvh, boxTest, triangleTest, query, wide_child::inner(0), steps, tests);
    addWork<Counting>(counters, steps, tests);
    return query;
}

template <bool Counting, typename Query, bool NegativeT, bool Robust, SingleStep Step, int N>
Query traverse(const WideBvh<N>& bvh, const Ray& ray, QueryCounters& counters) {
    if constexpr (Step == SingleStep::Offsets) {
        return traverseInOctant<Counting, kAnyOctant, Query, NegativeT, Robust>(bvh, ray, counters);
    } else {
        switch (directionOctant(ray.dir)) {
            case 0:
                return traverseInOctant<Counting, 0, Query, NegativeT, Robust>(bvh, ray, counters);
            case 1:
                return traverseInOctant<Counting, 1, Query, NegativeT, Robust>(bvh, ray, counters);
            case 2:
                return traverseInOctant<Counting, 2, Query, NegativeT, Robust>(bvh, ray, counters);
            case 3:
                return traverseInOctant<Counting, 3, Query, NegativeT, Robust>(bvh, ray, counters);
            case 4:
                return traverseInOctant<Counting, 4, Query, NegativeT, Robust>(bvh, ray, counters);
            case 5:
                return traverseInOctant<Counting, 5, Query, NegativeT, Robust>(bvh, ray, counters);
            case 6:
                return traverseInOctant<Counting, 6, Query, NegativeT, Robust>(bvh, ray, counters);
            default:
                return traverseInOctant<Counting, 7, Query, NegativeT, Robust>(bvh, ray, counters);
        }
    }
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
