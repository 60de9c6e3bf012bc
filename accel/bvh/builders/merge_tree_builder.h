// A binary tree given as merges, as a bottom-up builder makes it (a plugin's:
// <bvhlab/builder.h>): node i < N is the i-th prepared primitive, node N + m joins children[2m] and
// children[2m + 1], both below it; the last node is the root. The tree becomes a ClusterTree
// whose leaves are formed by SAH and whose depth is bounded as ploc's (cluster_tree.h).
#pragma once

#include "accel/bvh/builders/build_config.h"
#include "accel/bvh/layout/binary_bvh.h"

#include <bvhlab/prim_ref.h>

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace bvhlab {

// The merges over the primitives in the order given: 2 (N - 1) child indices.
using MergeFunction = std::function<std::vector<uint32_t>(std::span<const PrimRef>)>;

// Throws std::runtime_error naming `builder` when the merges are not a binary tree over exactly
// those primitives (their count, a child not below its parent, a node used twice or never).
BinaryBvh buildFromMerges(const std::string& builder, const BuildConfig& config, const PrimitiveSet& prims,
                          const MergeFunction& merge);

}  // namespace bvhlab
