// An N-wide BVH collapsed from a finished binary one (as Embree's BVH4 and BVH8): each node
// holds the boxes of up to N children in SoA order, so that one SIMD test checks all of them,
// and a ray takes fewer, wider steps. The collapse keeps every leaf of the binary tree, with its
// triangles in the same order, and stores them in SIMD blocks (triangle_blocks.h). sahbvh4 is
// N = 4, sahbvh8 N = 8.
#pragma once

#include "accel/bvh/layout/bvh.h"
#include "accel/bvh/layout/triangle_blocks.h"

#include <cstdint>

namespace bvhlab {

template <int N>
struct alignas(64) WideNode {
    static constexpr int kWidth = N;
    // Per axis, the N children's bounds; an empty lane has lower = +inf and upper = -inf,
    // which no ray overlaps (its slab distances are +inf in and -inf out, never NaN).
    float lower[3][N];
    float upper[3][N];
    uint32_t child[N];  // inner child: index of its WideNode; leaf: its first TriangleBlock
    uint32_t count[N];  // 0: inner child (or an empty lane); else the leaf's triangle count
};
static_assert(sizeof(WideNode<4>) == 128, "a 4-wide node fills two cache lines");
static_assert(sizeof(WideNode<8>) == 256, "an 8-wide node fills four cache lines");

// Root at 0. Empty when there is nothing to build over.
template <int N>
using WideBvh = NodeTree<WideNode<N>, TriangleBlockLeaves>;

// Collapses `bvh` (consumed): every wide node takes the two children of a binary node and opens
// the child with the largest box until it has N. Leaves get their blocks in lane order.
// A binary tree that is a single leaf becomes a root with that leaf in lane 0.
// Instantiated for N = 4 and 8.
template <int N>
WideBvh<N> collapseToWide(Bvh&& bvh);

}  // namespace bvhlab
