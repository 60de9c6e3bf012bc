// A binary tree built bottom-up (ploc's clustering): one leaf node per primitive, inner nodes in
// the order they were merged. bvhNodesFromClusterTree turns it into the BinaryBvh layout: it forms
// multi-primitive leaves by SAH and keeps the depth below kBvhMaxDepth.
#pragma once

#include "accel/bvh/builders/build_config.h"
#include "accel/bvh/layout/binary_bvh.h"

#include <bvhlab/prim_ref.h>

#include <span>
#include <vector>

namespace bvhlab {

struct alignas(32) ClusterBox {
    float lower[4];  // lane 3 unused: loaded as 4-float SIMD registers
    float upper[4];

    Bounds3 bounds() const { return {{lower[0], lower[1], lower[2]}, {upper[0], upper[1], upper[2]}}; }
};

struct ClusterTree {
    uint32_t leafCount = 0;          // nodes [0, leafCount) are the primitives, in leafRefs order
    std::vector<ClusterBox> boxes;   // every node's box
    std::vector<uint32_t> children;  // inner node leafCount + m: children[2m] (left), children[2m + 1]
    // The leaf forming, decided per node as it is made (formNode), bottom-up:
    std::vector<uint32_t> prims;   // primitives below the node
    std::vector<uint32_t> height;  // of the node's subtree once leaves are formed (0: a leaf)
    std::vector<float> cost;       // SAH cost of that subtree, unnormalised (areas, not ratios)
    std::vector<uint8_t> leaf;     // 1: the node becomes a leaf of all its primitives

    void resize(uint32_t leaves);
    uint32_t root() const { return uint32_t(boxes.size()) - 1; }
};

// Decides the leaf forming of `node`, whose box is set and whose children (if any) are formed:
// its cheapest form, a leaf (C_isect * tests * A, at most the leaf cap; always at most maxLeaf)
// or an inner node (C_trav * A + its children's costs), as the top-down SAH builders decide but
// with the children's whole subtrees known.
void formNode(ClusterTree& tree, uint32_t node, const BuildConfig& config);

// The BinaryBvh nodes over `tree` (not empty, every node formed) whose leaf l is `leafRefs[l]`; writes
// the PrimRefs in the tree's leaf order to `ordered`. Nodes formed as leaves become leaves of all
// the primitives below them, left to right. A subtree that
// would reach kBvhMaxDepth (a clustered tree can be a chain, N - 1 deep) is rebuilt at depth
// kBvhMaxDepth / 2 by binned SAH (its default bins), whose median rule keeps it within the bound.
std::vector<BvhNode, TraversalAllocator<BvhNode>> bvhNodesFromClusterTree(const ClusterTree& tree,
                                                                          std::span<const PrimRef> leafRefs,
                                                                          const BuildConfig& config,
                                                                          std::span<PrimRef> ordered);

}  // namespace bvhlab
