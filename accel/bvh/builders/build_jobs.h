// How a build runs its subtrees as parallel jobs and still makes one tree whatever the thread
// count: the nodes above the jobs are built first, each job's subtree (root at 0, a padding
// slot, sibling pairs) on its own, and the subtrees are appended in the order the jobs were
// deferred. Shared by the in-place builders (bvh_builder.cpp), sbvh (sbvh_builder.cpp) and
// ploc's tree of clusters (cluster_tree.cpp).
#pragma once

#include "accel/bvh/builders/build_threads.h"
#include "accel/bvh/layout/binary_bvh.h"

#include <cassert>
#include <vector>

namespace bvhlab {

using BvhNodes = std::vector<BvhNode, TraversalAllocator<BvhNode>>;

// Subtrees over fewer primitives than this are built as independent jobs, in parallel, after
// the nodes above them; large enough that a job outweighs its scheduling, small enough that
// there are many more jobs than threads.
inline constexpr uint32_t kJobPrimitives = 4096;

// Puts the subtree built by a job into the tree: its root into its slot, its pairs appended (an
// even offset: pairs stay on cache lines of their own), its leaves' indices moved by leafShift
// (a job that numbers its leaf entries from 0).
inline void appendSubtree(BvhNodes& nodes, uint32_t slot, const BvhNodes& subtree, uint32_t leafShift = 0) {
    assert(nodes.size() % 2 == 0);
    const uint32_t shift = uint32_t(nodes.size()) - 2;  // subtree index 2 lands at nodes.size()
    const auto moved = [shift, leafShift](BvhNode n) {
        n.index += n.isLeaf() ? leafShift : shift;
        return n;
    };
    nodes[slot] = moved(subtree[0]);
    for (size_t i = 2; i < subtree.size(); ++i) nodes.push_back(moved(subtree[i]));
}

}  // namespace bvhlab
