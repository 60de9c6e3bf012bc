// Insertion-based optimisation of a finished binary BVH (Bittner, Hapala, Havran, "Fast
// Insertion-Based Optimization of Bounding Volume Hierarchies", CGF 32(1) 2013): inner nodes
// that waste area are taken out and their two children reinserted where they raise the SAH
// least. A post-pass after any builder (BVH::optimize=insertion): the builder's leaves stay
// whole, only inner nodes move.
#pragma once

#include "accel/bvh/layout/binary_bvh.h"
#include "framework/config/field_key.h"

#include <tuple>

namespace bvhlab {

struct InsertionConfig {
    int iterations = 3;  // at most this many passes over the inner nodes; more lower the SAH
                         // further, each about as slow as the first

    bool operator==(const InsertionConfig&) const = default;
};

namespace keys::BVH {
inline constexpr FieldKey<&InsertionConfig::iterations> optimizeIterations{
    "BVH::optimizeIterations", 1, 100,
    "insertion: at most this many passes over all inner nodes, fewer once a pass lowers the inner nodes' area by "
    "under 1 %"};
}  // namespace keys::BVH
inline constexpr std::tuple kInsertionKeys{&keys::BVH::optimizeIterations};

// Optimises `bvh` in place by at most `passes` passes (fewer when one gains under 1 %): the
// nodes are emitted again depth-first, the leaf arrays reordered to the new leaf order. With
// the leaves fixed, the SAH changes only through the inner nodes' areas, whatever C_trav,
// C_isect or the leaves' block charge; a pass that would raise it is undone. Sequential: the
// same tree whatever the thread count.
void optimizeByInsertion(BinaryBvh& bvh, int passes);

}  // namespace bvhlab
