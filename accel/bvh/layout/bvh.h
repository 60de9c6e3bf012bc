// A finished BVH: what every builder produces and the one traversal reads. The statistics of a
// tree (node counts, depth, SAH cost, memory) are computed here, from the tree alone, so that
// every builder is measured by the same code.
#pragma once

#include "accel/bvh/layout/bvh_node.h"
#include "accel/bvh/layout/traversal_allocator.h"
#include "framework/core/accelerator.h"

#include <vector>

namespace bvhlab {

struct Bvh {
    // Root at 0, then an unused slot, then sibling pairs from index 2 on: every pair starts
    // at an even index, i.e. on a cache line of its own. So nodes.size() is one more than the
    // node count (0 when there is nothing to build over). Depth-first order, left subtree first.
    std::vector<BvhNode, TraversalAllocator<BvhNode>> nodes;
    // Leaf l holds primIndices[l.index .. l.index + l.count): the primitive index of each
    // triangle, reported in Hit::primitive.
    std::vector<uint32_t> primIndices;
    // The same triangles copied in leaf order, so that a leaf reads contiguous memory.
    std::vector<Triangle, TraversalAllocator<Triangle>> leafTriangles;

    bool empty() const { return nodes.empty(); }
    size_t bytes() const {
        return nodes.size() * sizeof(BvhNode) + primIndices.size() * sizeof(uint32_t) +
               leafTriangles.size() * sizeof(Triangle);
    }
};

// Fills the tree fields of BuildStats (nodes, leaves, leaf sizes, depth, SAH, bytes; not the
// build time). The SAH cost, the same formula for every builder, normalised by the root area:
//   C_trav * sum_inner A(n)/A(root) + C_isect * sum_leaves A(l)/A(root) * N(l).
void fillTreeStats(const Bvh& bvh, double cTraversal, double cIntersect, BuildStats& stats);

}  // namespace bvhlab
