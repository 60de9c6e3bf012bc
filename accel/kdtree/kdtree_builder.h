// The SAH kd-tree of Wald and Havran (2006, "On building fast kd-trees for ray tracing, and on
// doing that in O(N log N)"): the events of every primitive's box sorted once per axis; at each
// node one sweep over them finds the plane of least SAH (with the empty-space bonus), the
// primitives are classified against it, those on one side keep their events in order and only
// those that straddle it are clipped to each child (perfect splits), their few new events sorted
// and merged in. A node becomes a leaf where no plane beats K_I * N, or at the maximum depth.
#pragma once

#include "accel/kdtree/kdtree_node.h"

#include <bvhlab/primitive_set.h>

#include <cstdint>
#include <vector>

namespace bvhlab::kdtree {

struct KdTreeParameters {
    double cTraversal = 15.0;  // K_T
    double cIntersect = 20.0;  // K_I
    double emptyBonus = 0.2;   // lambda = 1 - emptyBonus when a side is empty
    int maxDepth = 0;          // 0: autoMaxDepth(N)
};

// 8 + 1.3 log2 N, rounded, within [1, 64] (Wald and Havran's rule of thumb).
int autoMaxDepth(size_t primitives);

struct KdTree {
    Bounds3 bounds;                    // the root's box: the valid primitives' bounds
    std::vector<KdNode> nodes;         // depth first; empty when nothing was built
    std::vector<uint32_t> references;  // the leaves' primitives
    int maxDepth = 0;                  // the bound the build kept to
    // The build's figures.
    size_t leaves = 0, emptyLeaves = 0, maxLeafReferences = 0;
    int deepestLeaf = 0;
    uint64_t eventsSwept = 0;  // the events of every node's sweep: the build's work, O(N log N)

    size_t bytes() const { return nodes.size() * sizeof(KdNode) + references.size() * sizeof(uint32_t); }
};

// The margin the build clips with, and the traversal's positional margin per unit of magnitude:
// the traversal visits every leaf whose box, enlarged by kRayMargin * (the larger of the scene's
// and the ray origin's largest coordinate), the ray passes through, which covers the rounding of
// the watertight test (a few float ulps of the coordinates).
inline constexpr double kClipMargin = 1e-9;
inline constexpr double kRayMargin = 4e-6;

KdTree buildKdTree(const PrimitiveSet& prims, const KdTreeParameters& parameters);

// The tree's SAH cost normalised by the root's area: cTraversal * sum over inner nodes of
// A(n)/A(root) + cIntersect * sum over leaves of A(l)/A(root) * N(l).
double sahCost(const KdTree& tree, double cTraversal, double cIntersect);

}  // namespace bvhlab::kdtree
