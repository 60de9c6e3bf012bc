// The traversal skeleton of the N-wide layout (wide_bvh.h), for either query: per step one SIMD
// test of a node's N child boxes (box_test.h), the children hit pushed far to near, so that the
// nearest is visited first. N_TR counts the steps, i.e. wide nodes and leaves visited.
#pragma once

#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/layout/wide_bvh.h"
#include "accel/bvh/traverse/box_test.h"
#include "accel/bvh/traverse/traversal.h"
#include "accel/bvh/traverse/triangle_block_test.h"

#include <cassert>

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

namespace wide_traversal {

// A child to visit: a wide node (count 0) or a leaf (its first block and triangle count), and
// where the ray enters its box.
struct StackEntry {
    uint32_t child;
    uint32_t count;
    float entry;
};

// Each step pops one entry and pushes at most N: the stack never holds more than N - 1 per
// level plus one (the wide tree is no deeper than the binary one).
template <int N>
inline constexpr int kStackSize = (N - 1) * kBvhMaxDepth + 1;

// The next child to visit among the lanes in `mask` (not 0): the nearest. The others are
// pushed far to near, so that the next nearest is popped first; what they will read starts
// loading now.
template <int N>
[[gnu::always_inline]] inline StackEntry nextChild(const WideNode<N>& node, int mask, const float entry[N], StackEntry* stack,
                                                  int& size, const WideNode<N>* nodes, const TriangleBlock* blocks) {
    const int first = __builtin_ctz(unsigned(mask));
    mask &= mask - 1;
    StackEntry nearest{node.child[first], node.count[first], entry[first]};
    if (mask == 0) return nearest;  // the common case: one child hit
    StackEntry hits[N];
    int k = 0;
    hits[k++] = nearest;
    while (mask != 0) {
        const int i = __builtin_ctz(unsigned(mask));
        mask &= mask - 1;
        const StackEntry e{node.child[i], node.count[i], entry[i]};
        int j = k++;
        for (; j > 0 && hits[j - 1].entry < e.entry; --j) hits[j] = hits[j - 1];
        hits[j] = e;
    }
    assert(size + k - 1 <= kStackSize<N>);
    for (int i = 0; i < k - 1; ++i) {
        const StackEntry& e = hits[i];
        __builtin_prefetch(e.count != 0 ? static_cast<const void*>(blocks + e.child)
                                        : static_cast<const void*>(nodes + e.child));
        stack[size++] = e;
    }
    return hits[k - 1];
}

// For an any-hit query: the first child hit in lane order is visited next, the others are
// pushed as they come, their reads started.
template <int N>
[[gnu::always_inline]] inline StackEntry anyChild(const WideNode<N>& node, int mask, const float entry[N], StackEntry* stack,
                                                 int& size, const WideNode<N>* nodes, const TriangleBlock* blocks) {
    const int first = __builtin_ctz(unsigned(mask));
    const StackEntry next{node.child[first], node.count[first], entry[first]};
    for (mask &= mask - 1; mask != 0; mask &= mask - 1) {
        const int i = __builtin_ctz(unsigned(mask));
        const StackEntry e{node.child[i], node.count[i], entry[i]};
        __builtin_prefetch(e.count != 0 ? static_cast<const void*>(blocks + e.child)
                                        : static_cast<const void*>(nodes + e.child));
        stack[size++] = e;
    }
    return next;
}

}  // namespace wide_traversal

// The skeleton's loop from `current` (the root, or a node where a packet left the ray alone:
// packet_traversal.h) for a query under way; adds its node steps and triangle tests.
template <typename Query, bool NegativeT, bool Robust, int N>
[[gnu::always_inline]] inline void traverseFrom(const WideBvh<N>& bvh, const WideBoxTest<N, NegativeT, Robust>& boxTest,
                                               const BlockTriangleTest<Robust>& triangleTest, Query& query,
                                               wide_traversal::StackEntry current, uint64_t& steps, uint64_t& tests) {
    using namespace wide_traversal;
    const WideNode<N>* nodes = bvh.nodes.data();
    const TriangleBlock* blocks = bvh.blocks.data();
    const float tmin = boxTest.tmin;

    StackEntry stack[kStackSize<N>];
    int size = 0;
    for (;;) {
        ++steps;
        if (current.count == 0) {
            const WideNode<N>& node = nodes[current.child];
            float entry[N];
            const int mask = boxTest.intersect(node, query.tmax, entry);
            if (mask != 0) {
                // Closest hit: nearest first. Any hit: in lane order, unsorted (as Embree's
                // occlusion traversal); sorting cost more than it saved (bench: -8 % shadow).
                if constexpr (Query::kStopsAtFirstHit) {
                    current = anyChild(node, mask, entry, stack, size, nodes, blocks);
                } else {
                    current = nextChild(node, mask, entry, stack, size, nodes, blocks);
                }
                continue;
            }
        } else {
            if (testLeafBlocks(query, triangleTest, blocks, current.child, current.count, tmin, tests)) break;
        }
        // Pop the next child the ray enters before the closest hit so far (an any-hit query
        // never shortens its interval: nothing to skip).
        if constexpr (!Query::kStopsAtFirstHit) {
            while (size > 0 && stack[size - 1].entry > query.tmax) --size;
        }
        if (size == 0) break;
        current = stack[--size];
    }
}

template <typename Query, bool NegativeT, bool Robust, int N>
Query traverse(const WideBvh<N>& bvh, const Ray& ray, QueryCounters& counters) {
    const WideBoxTest<N, NegativeT, Robust> boxTest(ray);
    const BlockTriangleTest<Robust> triangleTest(ray);
    Query query(ray);
    uint64_t steps = 0, tests = 0;
    traverseFrom(bvh, boxTest, triangleTest, query, {0, 0, ray.tmin}, steps, tests);  // from the root
    counters.traversalSteps += steps;
    counters.intersectionTests += tests;
    return query;
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
