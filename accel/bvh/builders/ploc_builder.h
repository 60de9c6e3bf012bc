// ploc: Parallel Locally-Ordered Clustering (Meister and Bittner, "Parallel Locally-Ordered
// Clustering for Bounding Volume Hierarchy Construction", IEEE TVCG 24(3), 2018). Bottom-up:
// the primitives sorted by the Morton code of their centres are the first clusters; then, until
// one is left, every cluster finds its nearest neighbour (the smallest box around both) among
// the plocRadius clusters on either side, mutual nearest neighbours merge into a node at the
// place of the first, and the rest close ranks. Every step is a TBB loop over fixed chunks whose
// results do not depend on the chunking: one tree whatever BvhBuildConfig::threads.
#pragma once

#include "accel/bvh/builders/bvh_builder.h"

namespace bvhlab {

// The Bvh of ploc over the valid triangles, its leaves formed by SAH (cluster_tree.h).
Bvh buildPlocBvh(const BvhBuildConfig& config, const PrimitiveSet& prims);

}  // namespace bvhlab
