// ploc: Parallel Locally-Ordered Clustering (Meister and Bittner, "Parallel Locally-Ordered
// Clustering for Bounding Volume Hierarchy Construction", IEEE TVCG 24(3), 2018). Bottom-up:
// the primitives sorted by the Morton code of their centres are the first clusters; then, until
// one is left, every cluster finds its nearest neighbour (the smallest box around both) among
// the PlocConfig::radius clusters on either side, mutual nearest neighbours merge into a node at the
// place of the first, and the rest close ranks. Every step is a TBB loop over fixed chunks whose
// results do not depend on the chunking: one tree whatever BuildConfig::threads.
#pragma once

#include "accel/bvh/builders/build_config.h"
#include "accel/bvh/layout/binary_bvh.h"

#include <bvhlab/prim_ref.h>

#include <tuple>

namespace bvhlab {

struct PlocConfig {
    int radius = 16;  // clusters on either side (Morton order) searched for the nearest neighbour:
                      // more finds closer pairs (a lower SAH) at a search that grows with it

    bool operator==(const PlocConfig&) const = default;
};

namespace keys::BVH {
inline constexpr FieldKey<&PlocConfig::radius> plocRadius{
    "BVH::plocRadius", 1, 256,
    "ploc: clusters on either side (Morton order) among which each cluster looks for its nearest neighbour"};
}  // namespace keys::BVH
inline constexpr std::tuple kPlocKeys{&keys::BVH::plocRadius};

// The BinaryBvh of ploc over the valid triangles, its leaves formed by SAH (cluster_tree.h).
BinaryBvh buildPlocBvh(const BuildConfig& config, const PlocConfig& ploc, const PrimitiveSet& prims);

}  // namespace bvhlab
