// Refitting: a finished tree made to fit its primitives again after they moved, its topology
// kept. The leaves' copies of the primitives (a binary leaf's triangles, a wide leaf's SIMD
// blocks, the quadric tree's shapes) are read again through the leaves' primitive indices, and
// every box is recomputed bottom up: a leaf's is the box of its primitives, an inner node's
// the union of its children's. The tree answers as a fresh build would; only its SAH grows as
// the primitives drift from where they were built. Over the primitives of the last build the
// boxes come out as the build made them (but sbvh's, whose leaves hold clipped parts of
// triangles: a refit gives them whole triangles' boxes).
//
// Parallel as the builders are: the subtrees of the top levels are TBB tasks (in the caller's
// arena), the rest a recursion that allocates nothing.
#pragma once

#include "accel/bvh/layout/binary_bvh.h"
#include "accel/bvh/layout/quadric_leaves.h"
#include "accel/bvh/layout/wide_bvh.h"

namespace bvhlab {

// `bvh.primIndices` index `prims`; bvh.leafTriangles is written whole (sized as primIndices).
void refitBinary(BinaryBvh& bvh, const PrimitiveSet& prims);

// The spheres and cones, read again by their primitive indices into leafShapes.
void refitQuadrics(QuadricBvh& bvh, const PrimitiveSet& prims);

// The blocks read again lane by lane (padding lanes repeat their leaf's last triangle, as
// TriangleBlockLeaves::writeLeaf makes them), the lanes' boxes recomputed and each node's
// children ordered again per octant (orderChildren). Instantiated for N = 4 and 8.
template <int N>
void refitWide(WideBvh<N>& bvh, const PrimitiveSet& prims);

}  // namespace bvhlab
