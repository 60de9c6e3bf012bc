// A binary tree built bottom-up (ploc's clustering): one leaf node per primitive, inner nodes in
// the order they were merged. bvhNodesFromClusterTree turns it into the Bvh layout: it forms
// multi-primitive leaves by SAH and keeps the depth below kBvhMaxDepth.
#pragma once

#include "accel/bvh/build/bvh_builder.h"

#include <span>
#include <vector>

namespace bvhlab {

struct alignas(32) ClusterBox {
    float lower[4];  // lane 3 unused: loaded as 4-float SIMD registers
    float upper[4];

    Bounds3 bounds() const { return {{lower[0], lower[1], lower[2]}, {upper[0], upper[1], upper[2]}}; }
};

struct ClusterTree {
    uint32_t leafCount = 0;            // nodes [0, leafCount) are the primitives, in leafRefs order
    std::vector<ClusterBox> boxes;     // every node's box
    std::vector<uint32_t> children;    // inner node leafCount + m: children[2m] (left), children[2m + 1]
    std::vector<uint32_t> mergeEnds;   // the inner nodes of iteration k end at mergeEnds[k]: each depends
                                       // only on nodes of earlier iterations
    uint32_t root() const { return uint32_t(boxes.size()) - 1; }
};

// The Bvh nodes over `tree` (not empty) whose leaf l is `leafRefs[l]`; writes the PrimRefs in the
// tree's leaf order to `ordered`. Subtrees charged by SAH as cheapest as one leaf (at most the
// leaf cap, charged by config.sahTests; always at most maxLeaf) become leaves. A subtree that
// would reach kBvhMaxDepth (a clustered tree can be a chain, N - 1 deep) is rebuilt at depth
// kBvhMaxDepth / 2 by binned SAH, whose median rule keeps it within the bound.
std::vector<BvhNode, TraversalAllocator<BvhNode>> bvhNodesFromClusterTree(const ClusterTree& tree,
                                                                          std::span<const PrimRef> leafRefs,
                                                                          const BvhBuildConfig& config,
                                                                          std::span<PrimRef> ordered);

}  // namespace bvhlab
