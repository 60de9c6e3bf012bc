// The binary BVH: what every builder produces, the layout the binary traversal reads and the wide
// layouts are collapsed from. The statistics of a
// tree (node counts, depth, SAH cost, memory) are computed here, from the tree alone, so that
// every builder is measured by the same code.
#pragma once

#include "accel/bvh/layout/bvh_node.h"
#include "accel/bvh/layout/leaf_arrays.h"
#include "framework/core/accelerator.h"

#include <span>

namespace bvhlab {

// The binary layout. Root at 0, then an unused slot, then sibling pairs from index 2 on: every
// pair starts at an even index, i.e. on a cache line of its own. So nodes.size() is one more
// than the node count (0 when there is nothing to build over). Depth-first order, left
// subtree first. Leaf l holds leafTriangles[l.index .. l.index + l.count).
using BinaryBvh = NodeTree<BvhNode>;

// Fills the tree fields of BuildStats (nodes, leaves, leaf sizes and their histogram, depth, SAH;
// not the build time, the bytes nor EPO: end_point_overlap.h) from the nodes of a tree laid out as BinaryBvh. The SAH
// cost, the same formula for every builder, normalised by the root area:
//   C_trav * sum_inner A(n)/A(root) + C_isect * sum_leaves A(l)/A(root) * N(l).
void fillTreeStats(std::span<const BvhNode> nodes, double cTraversal, double cIntersect, BuildStats& stats);

// The same, and the tree's bytes.
template <typename Leaves>
void fillTreeStats(const NodeTree<BvhNode, Leaves>& tree, double cTraversal, double cIntersect, BuildStats& stats) {
    fillTreeStats(std::span<const BvhNode>(tree.nodes), cTraversal, cIntersect, stats);
    stats.bytes = tree.bytes();
}

// The statistics of two trees that every query traverses one after the other (triangles, then
// quadrics), into `first`: counts and bytes add up, and the SAH of each counts with the
// probability that a ray through the union of the two root boxes enters its root
// (A(root) / A(union)), i.e. both costs renormalised to the union's area. The leaf-size
// histograms add up; EPO stays only if both have one.
void combineTreeStats(BuildStats& first, const Bounds3& firstRoot, const BuildStats& second, const Bounds3& secondRoot);

}  // namespace bvhlab
