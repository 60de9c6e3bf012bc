// A split rule of bvhlab's BVH builders and the top-down recursion every split rule shares (after
// madmann91/bvh v2's top_down_sah_builder): a work stack, the leaf rules, the depth bound and node
// emission live here, once. A split rule only says how to split a range of primitives: it
// partitions the range in place and returns the two halves, or declines (the range becomes a
// leaf). A plugin's SplitRule (<bvhlab/builder.h>) is the same hook behind the public API, run as
// one of these (accel/plugins/plugin_builder.cpp).
#pragma once

#include "accel/bvh/builders/bounds_accumulator.h"
#include "accel/bvh/builders/build_config.h"
#include "accel/bvh/layout/binary_bvh.h"

#include <optional>
#include <span>
#include <vector>

namespace bvhlab {

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

class BvhSplitRule {
public:
    explicit BvhSplitRule(const BuildConfig& config) : config_(config) {}
    virtual ~BvhSplitRule() = default;

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

    BuildConfig config_;
    std::span<PrimRef> refs_;

private:
    std::optional<Split> chooseSplit(const BuildRange& range, int depth);
};

template <typename Accumulator>
BuildRange BvhSplitRule::boundsOf(const PrimRef* refs, uint32_t begin, uint32_t end) {
    Accumulator acc;
    for (uint32_t i = begin; i < end; ++i) acc.add(refs[i]);
    return {begin, end, acc.bounds(), acc.centroidBounds()};
}

template <typename IsLeft>
Split BvhSplitRule::partition(const BuildRange& range, IsLeft isLeft) {
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

}  // namespace bvhlab
