// Builder plugins (docs/plugins.md, "A builder"): a plugin that has only a way to build a binary
// BVH adds it with PluginRegistrar::addBuilder, and bvhlab supplies the rest: leaf arrays, the
// depth bound, the binary, 4- and 8-wide layouts and their traversals, the statistics, parallel
// jobs and the checks, as the accelerators NAME, NAME4 and NAME8. A builder is one of two kinds:
// - a split rule, the hook of bvhlab's top-down recursion (as madmann91/bvh v2's builders are):
//   given a node's primitives, it partitions them in place, and the recursion does the rest;
// - a merge tree, for bottom-up builders: the whole binary tree over single primitives, from
//   which bvhlab forms leaves by SAH (as for its own ploc).
#pragma once

#include "framework/config/env.h"
#include "framework/core/prim_ref.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace bvhlab {

// What a builder is told, besides the primitives.
struct BuilderSettings {
    const Env& env;  // every key of the run: the plugin's own and bvhlab's
    // The traversal tests a leaf's primitives this many at a time (1 in NAME, 8 in NAME4 and
    // NAME8): an SAH charges a leaf of n primitives ceil(n / leafBlock) tests.
    uint32_t leafBlock = 1;
    // The run's SAH constants (BVH::cTraversal, BVH::cIntersect), which bvhlab's own SAH builders
    // and the reported SAH cost use: the cost of visiting an inner node and of one primitive
    // test, in the same unit (only their ratio matters to a split). cTraversal >= 0,
    // cIntersect > 0.
    float cTraversal = 1.0f;
    float cIntersect = 1.0f;
};

class SplitRule {
public:
    virtual ~SplitRule() = default;
    // Reorders `prims`, a node's primitives, so that those of the left child come first, and
    // returns how many they are. 0 or prims.size() declines: the node becomes a leaf when
    // `mayBeLeaf`, else it is split at the object median. `bounds` is the box of their boxes,
    // `centroidBounds` the box of their centres. Called only for nodes of more than
    // BVH::maxLeaf primitives whose centres are not all equal (near the depth bound the
    // recursion splits at the median itself). Only the order of `prims` may change.
    virtual size_t split(std::span<PrimRef> prims, const Bounds3& bounds, const Bounds3& centroidBounds,
                         bool mayBeLeaf) = 0;
};

// One inner node of a merge tree: its two children. For N primitives, node i < N is prims[i] and
// node N + m is merges[m], whose children are nodes below N + m; the root is the last of the
// N - 1. Every node but the root is the child of exactly one merge.
struct Merge {
    uint32_t left = 0, right = 0;
};

struct PluginBuilder {
    std::string name;         // NAME; NAME4 and NAME8 are added with it
    std::string description;  // of NAME: what the builder does
    std::vector<EnvKey> keys;  // its own keys, declared as an accelerator's are
    // Exactly one of the two. A split rule is made once per build thread and used by that
    // thread only; a merge tree is asked for once per build (its threads are its own).
    std::function<std::unique_ptr<SplitRule>(const BuilderSettings&)> splitRule;
    std::function<std::vector<Merge>(std::span<const PrimRef> prims, const BuilderSettings&)> mergeTree;
};

}  // namespace bvhlab
