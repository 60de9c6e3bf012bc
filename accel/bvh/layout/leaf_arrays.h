// What every BVH layout stores besides its nodes: the leaves' primitives, in leaf order. A
// leaf of any layout names a range [first, first + count) of these arrays.
#pragma once

#include "accel/bvh/layout/traversal_allocator.h"
#include "framework/core/triangle.h"

#include <cstdint>
#include <vector>

namespace bvhlab {

struct LeafArrays {
    // The primitive index of each triangle, reported in Hit::primitive.
    std::vector<uint32_t> primIndices;
    // The same triangles copied in leaf order, so that a leaf reads contiguous memory.
    std::vector<Triangle, TraversalAllocator<Triangle>> leafTriangles;

    size_t leafBytes() const { return primIndices.size() * sizeof(uint32_t) + leafTriangles.size() * sizeof(Triangle); }
};

// A finished tree of one node layout: its nodes (root at 0; none when there is nothing to
// build over) and its leaf arrays.
template <typename Node>
struct NodeTree : LeafArrays {
    std::vector<Node, TraversalAllocator<Node>> nodes;

    bool empty() const { return nodes.empty(); }
    size_t bytes() const { return nodes.size() * sizeof(Node) + leafBytes(); }
};

}  // namespace bvhlab
