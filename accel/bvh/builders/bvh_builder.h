// The top-down recursion every BVH builder shares (after madmann91/bvh v2's
// top_down_sah_builder): a work stack, the leaf rules, the depth bound and node emission live
// here, once. A builder only says how to split a range of primitives: it partitions the range
// in place and returns the two halves, or declines (the range becomes a leaf).
#pragma once

#include "accel/bvh/builders/bounds_accumulator.h"
#include "accel/bvh/layout/bvh.h"
#include "accel/bvh/layout/quadric_leaves.h"

#include <algorithm>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

namespace bvhlab {

// What runs after the builder on its binary tree.
enum class BvhOptimize {
    None,
    Insertion,  // insertion_optimizer.h (Bittner et al. 2013)
};

enum class MedianSplitBox {
    NodeBox,      // halve the box of the primitives (classic spatial median)
    CentroidBox,  // halve the box of their centres (pbrt's "middle"; never an empty side unless
                  // rounding puts the midpoint on the lowest centre)
};

struct BvhBuildConfig {
    int maxLeaf = 2;             // ranges of this many primitives or fewer always become leaves
    int leafCap = 16;            // largest leaf made when splitting does not pay (SAH termination)
                                 // or cannot separate primitives (coincident centres); >= maxLeaf
    bool sahTermination = true;  // SAH builders: leaf when no split beats testing every primitive
    float cTraversal = 1.0f;     // SAH cost of visiting an inner node, in units of ...
    float cIntersect = 1.0f;     // ... the cost of one ray-triangle test
    int sahBlockShift = 0;       // the SAH builders count a leaf's tests in blocks of 2^shift
                                 // triangles (ceil(n / 2^shift), Embree's sahBlockSize): 2 for
                                 // the wide layouts, whose leaves test eight at once
    int bins = 16;               // binned SAH: bins per axis; more bins approach the sweep, slower
    bool allAxes = false;        // binned SAH: bin all three axes and take the best, not the widest
    bool simd = true;            // SIMD in the hot loops (prep, binning, partition); false = the
                                 // scalar backend of the same code, the same tree
    MedianSplitBox medianSplitBox = MedianSplitBox::CentroidBox;  // tdbvh: which box's longest axis is halved
    float sbvhAlpha = 1e-5f;     // sbvh: spatial splits only where the object split's children
                                 // overlap by more than alpha * A(root)
    float sbvhGrowth = 0.3f;     // sbvh: at most this many new references per triangle
    int plocRadius = 16;         // ploc: each cluster looks for its nearest neighbour among the
                                 // plocRadius clusters on either side in Morton order
    BvhOptimize optimize = BvhOptimize::None;
    int optimizeIterations = 3;  // insertion: at most this many passes over the inner nodes; more
                                 // lower the SAH further, each about as slow as the first
    int threads = 1;             // build threads (TBB; 0 = all hardware threads): the tree does
                                 // not depend on them

    uint32_t effectiveLeafCap() const { return uint32_t(std::max(maxLeaf, leafCap)); }
    // What the SAH charges for testing n primitives: n, or the blocks they fill.
    uint32_t sahTests(uint32_t n) const { return (n + (1u << sahBlockShift) - 1) >> sahBlockShift; }
};

// The SAH leaf test: a split of cost `splitCost` = A_L*N_L + A_R*N_R of n primitives in
// `bounds` pays off when C_trav + C_isect * splitCost / A < C_isect * N.
bool sahPrefersLeaf(const BvhBuildConfig& config, const Bounds3& bounds, uint32_t n, float splitCost);

// Leaf rules every recursion shares: no plane separates primitives whose centres all coincide,
// and near the depth bound only object-median splits (halving the count) are allowed, which
// bounds the depth by depth + ceil(log2 N) <= kBvhMaxDepth - 1.
bool allCentresEqual(const Bounds3& centroidBounds);
bool nearDepthBound(int depth, uint32_t n);

// A node under construction: the primitives refs[begin, end) and their boxes.
struct BuildRange {
    uint32_t begin = 0, end = 0;
    Bounds3 bounds;          // of the primitives' boxes
    Bounds3 centroidBounds;  // of the centres of those boxes
    uint32_t size() const { return end - begin; }
};

// A range partitioned in place into [left.begin, left.end) and [right.begin, right.end).
struct Split {
    BuildRange left, right;
};

// A range whose subtree is left to be built later (by buildBvh's parallel jobs): its node slot
// in the partial tree and its depth.
struct DeferredRange {
    BuildRange range;
    uint32_t node;
    int depth;
};

class TopDownBuilder {
public:
    explicit TopDownBuilder(const BvhBuildConfig& config) : config_(config) {}
    virtual ~TopDownBuilder() = default;

    // Builds the subtree over `root` (a range of `refs`, which it reorders: leaves index into
    // the reordered array) at `depth`: its root at 0, a padding slot, then sibling pairs.
    // Depth stays below kBvhMaxDepth. With `deferred`, ranges of fewer than `deferBelow`
    // primitives are not built but appended there, their node slots left to the caller.
    std::vector<BvhNode, TraversalAllocator<BvhNode>> build(std::span<PrimRef> refs, const BuildRange& root,
                                                            int depth = 0,
                                                            std::vector<DeferredRange>* deferred = nullptr,
                                                            uint32_t deferBelow = 0);

protected:
    // The hook: partition `range` in place and return the halves (both non-empty), or nullopt
    // for a leaf. `mayBeLeaf` says the range is small enough to be one; when it is not, a
    // nullopt answer gets an object-median split instead. Called only for ranges larger than
    // maxLeaf whose centres are not all equal.
    virtual std::optional<Split> trySplit(const BuildRange& range, bool mayBeLeaf) = 0;

    bool sahPrefersLeaf(const BuildRange& range, float splitCost) const {
        return bvhlab::sahPrefersLeaf(config_, range.bounds, range.size(), splitCost);
    }

    // Moves the primitives for which isLeft(ref) holds to the front; computes both halves' boxes
    // in the same pass (SIMD backend per config). Halves may be empty.
    template <typename IsLeft>
    Split partition(const BuildRange& range, IsLeft isLeft);
    // Splits at refs index `mid` as they lie, computing both halves' boxes.
    Split splitAtIndex(const BuildRange& range, uint32_t mid);
    // Median by centre along `axis` (ties by primitive index): halves of equal size.
    Split objectMedianSplit(const BuildRange& range, int axis);

    template <typename Accumulator>
    static BuildRange boundsOf(const PrimRef* refs, uint32_t begin, uint32_t end);

    BvhBuildConfig config_;
    std::span<PrimRef> refs_;

private:
    std::optional<Split> chooseSplit(const BuildRange& range, int depth);
};

template <typename Accumulator>
BuildRange TopDownBuilder::boundsOf(const PrimRef* refs, uint32_t begin, uint32_t end) {
    Accumulator acc;
    for (uint32_t i = begin; i < end; ++i) acc.add(refs[i]);
    return {begin, end, acc.bounds(), acc.centroidBounds()};
}

template <typename IsLeft>
Split TopDownBuilder::partition(const BuildRange& range, IsLeft isLeft) {
    // Hoare partition from both ends; every primitive is classified once and added to the
    // box of the side it ends up on.
    auto run = [&](auto leftAcc, auto rightAcc) {
        PrimRef* refs = refs_.data();
        uint32_t l = range.begin, r = range.end;
        for (;;) {
            while (l < r && isLeft(refs[l])) leftAcc.add(refs[l++]);
            while (l < r && !isLeft(refs[r - 1])) rightAcc.add(refs[--r]);
            if (l == r) break;
            // refs[l] belongs right and refs[r - 1] left.
            std::swap(refs[l], refs[r - 1]);
            leftAcc.add(refs[l++]);
            rightAcc.add(refs[--r]);
        }
        return Split{{range.begin, l, leftAcc.bounds(), leftAcc.centroidBounds()},
                     {l, range.end, rightAcc.bounds(), rightAcc.centroidBounds()}};
    };
    return simd::withFloats4(config_.simd, [&](auto f) {
        using Accumulator = BoundsAccumulator<decltype(f)>;
        return run(Accumulator{}, Accumulator{});
    });
}

// A builder: how the binary tree is made, by a split rule under the shared recursion
// (TopDownBuilder) or by a whole tree of its own (sbvh's growing ranges, ploc's clustering).
// accel/bvh/builder_table.cpp names ours; a plugin's comes from <bvhlab/builder.h>.
using SplitRuleFactory = std::function<std::unique_ptr<TopDownBuilder>(const BvhBuildConfig&)>;
struct BvhBuilder {
    std::string name;  // "sahbvh": the binary accelerator's name
    // Exactly one of the two. splitRule is called once per build thread.
    SplitRuleFactory splitRule;
    // The triangles' tree; spheres and cones then get binned SAH (no triangle to clip, and few).
    std::function<Bvh(const BvhBuildConfig&, const PrimitiveSet&)> wholeTree;
    // A plugin's: after its split rule, the triangles' PrimRefs are checked to be the ones it was
    // given, reordered; spheres and cones get binned SAH (unchecked, a rule could lose one).
    bool fromPlugin = false;
};

// The whole build: PrimRefs from the valid triangles (SIMD or scalar), the builder's recursion
// or its own tree, then the leaf arrays (primitive indices and triangles in leaf order), then
// the optimisation the config asks for.
Bvh buildBvh(const BvhBuilder& builder, const BvhBuildConfig& config, const PrimitiveSet& prims);

// buildBvh over the valid spheres and cones (their boxes), with their shapes in leaf order.
QuadricBvh buildQuadricBvh(const BvhBuilder& builder, const BvhBuildConfig& config, const PrimitiveSet& prims);

// The steps of buildBvh that the builders with their own recursion (sbvh, ploc) share:
// one PrimRef per valid triangle into `out` (its size), and the range over them;
BuildRange preparePrimRefs(const PrimitiveSet& prims, PrimRef* out, bool simd);
// the leaf arrays from PrimRefs in leaf order;
void fillLeafArrays(Bvh& bvh, const PrimRef* refs, const PrimitiveSet& prims, int threads);
// bvh.leafTriangles from the triangles bvh.primIndices name, in parallel.
void copyLeafTriangles(const PrimitiveSet& prims, int threads, Bvh& bvh);

}  // namespace bvhlab
