// Builder plugins (docs/plugins.md, "A builder"): a plugin that has only a way to build a binary
// BVH adds it with PluginRegistrar::addBuilder (<bvhlab/plugin.h>), and bvhlab supplies the rest:
// leaf arrays, the depth bound, the binary, 4- and 8-wide layouts and their traversals, the
// statistics, parallel jobs and the checks, as the accelerators NAME, NAME4 and NAME8. A builder
// is one of two kinds:
// - a split rule, the hook of bvhlab's top-down recursion (as madmann91/bvh v2's builders are):
//   given a node's primitives, it partitions them in place, and the recursion does the rest;
// - a merge tree, for bottom-up builders: the whole binary tree over single primitives, from
//   which bvhlab forms leaves by SAH (as for its own ploc).
#pragma once

#include <bvhlab/math.h>
#include <bvhlab/prim_ref.h>
#include <bvhlab/settings.h>
#include <bvhlab/view.h>

#include <cstdint>

namespace bvhlab {

// What a builder is told, besides the primitives.
struct BuilderSettings {
    const PluginSettings& keys;  // the builder's own keys
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
    virtual size_t split(View<PrimRef> prims, const Bounds3& bounds, const Bounds3& centroidBounds, bool mayBeLeaf) = 0;
};

// One inner node of a merge tree: its two children. For N primitives, node i < N is prims[i] and
// node N + m is merges[m], whose children are nodes below N + m; the root is the last of the
// N - 1. Every node but the root is the child of exactly one merge.
struct Merge {
    uint32_t left = 0, right = 0;
};

struct PluginBuilder {
    const char* name;            // NAME; NAME4 and NAME8 are added with it
    const char* description;     // of NAME: what the builder does
    View<const PluginKey> keys;  // its own keys
    // Exactly one of the two. A split rule is made with `new` once per build thread, used by
    // that thread only and deleted by bvhlab; a merge tree is asked for once per build (its
    // threads are its own) and writes all prims.size() - 1 merges.
    SplitRule* (*splitRule)(const BuilderSettings& settings) = nullptr;
    void (*mergeTree)(View<const PrimRef> prims, View<Merge> merges, const BuilderSettings& settings) = nullptr;
};

}  // namespace bvhlab
