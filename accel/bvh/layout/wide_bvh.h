// A 4-wide BVH collapsed from a finished binary one (as Embree's BVH4): each node holds the
// boxes of up to four children in SoA order, so that one SSE test checks all four, and a ray
// takes about half as many, wider steps. The collapse changes no leaf: the leaves, the
// triangles in leaf order and their primitive indices are the binary tree's.
#pragma once

#include "accel/bvh/layout/bvh.h"

#include <cstdint>
#include <vector>

namespace bvhlab {

struct alignas(64) WideNode {
    static constexpr int kWidth = 4;
    // Per axis, the four children's bounds; an empty lane has lower = +inf and upper = -inf,
    // which no ray overlaps (its slab distances are +inf in and -inf out, never NaN).
    float lower[3][kWidth];
    float upper[3][kWidth];
    uint32_t child[kWidth];  // inner child: index of its WideNode; leaf: first triangle (leaf order)
    uint32_t count[kWidth];  // 0: inner child (or an empty lane); else the leaf's triangle count
};
static_assert(sizeof(WideNode) == 128, "a 4-wide node fills two cache lines");

struct WideBvh {
    // Root at 0. Empty when there is nothing to build over.
    std::vector<WideNode, TraversalAllocator<WideNode>> nodes;
    std::vector<uint32_t> primIndices;  // as Bvh::primIndices
    std::vector<Triangle, TraversalAllocator<Triangle>> leafTriangles;  // as Bvh::leafTriangles

    bool empty() const { return nodes.empty(); }
    size_t bytes() const {
        return nodes.size() * sizeof(WideNode) + primIndices.size() * sizeof(uint32_t) +
               leafTriangles.size() * sizeof(Triangle);
    }
};

// Collapses `bvh` (its leaves and triangles are moved, not copied): every wide node takes the
// two children of a binary node and opens the child with the largest box until it has four.
// A binary tree that is a single leaf becomes a root with that leaf in lane 0.
WideBvh collapseToWide(Bvh&& bvh);

}  // namespace bvhlab
