// What the binary layout stores besides its nodes: the leaves' triangles, in leaf order. A
// leaf names a range [first, first + count) of these arrays. (The wide layouts store theirs
// in SIMD blocks: triangle_blocks.h.)
#pragma once

#include <bvhlab/triangle.h>
#include "accel/bvh/layout/traversal_allocator.h"

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
// build over) and its leaves' arrays.
template <typename Node, typename Leaves = LeafArrays>
struct NodeTree : Leaves {
    std::vector<Node, TraversalAllocator<Node>> nodes;

    bool empty() const { return nodes.empty(); }
    size_t bytes() const { return nodes.size() * sizeof(Node) + this->leafBytes(); }
};

}  // namespace bvhlab
