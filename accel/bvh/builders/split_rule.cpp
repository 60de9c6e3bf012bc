#include "accel/bvh/builders/split_rule.h"

#include "accel/bvh/builders/top_down_recursion.h"

#include <algorithm>
#include <bit>

namespace bvhlab {

bool allCentresEqual(const Bounds3& c) {
    return c.lower.x == c.upper.x && c.lower.y == c.upper.y && c.lower.z == c.upper.z;
}

bool nearDepthBound(int depth, uint32_t n) {
    const int ceilLog2 = n <= 1 ? 0 : int(std::bit_width(n - 1));
    return depth + ceilLog2 >= kBvhMaxDepth - 1;
}

Split BvhSplitRule::splitAtIndex(const BuildRange& range, uint32_t mid) {
    const PrimRef* refs = refs_.data();
    return simd::withFloats4(config_.simd, [&](auto f) {
        using Accumulator = BoundsAccumulator<decltype(f)>;
        return Split{boundsOf<Accumulator>(refs, range.begin, mid), boundsOf<Accumulator>(refs, mid, range.end)};
    });
}

Split BvhSplitRule::objectMedianSplit(const BuildRange& range, int axis) {
    PrimRef* begin = refs_.data() + range.begin;
    const uint32_t mid = range.begin + range.size() / 2;
    std::nth_element(begin, refs_.data() + mid, refs_.data() + range.end, [axis](const PrimRef& a, const PrimRef& b) {
        const float ca = a.center(axis), cb = b.center(axis);
        return ca < cb || (ca == cb && a.prim < b.prim);
    });
    return splitAtIndex(range, mid);
}

// The leaf rules, in order: small ranges are leaves; coincident centres cannot be separated
// by any plane (a leaf, or halves by index when too many); near the depth bound only
// object-median splits (halving the count) are allowed, which bounds the depth by
// depth + ceil(log2 N) <= kBvhMaxDepth - 1; otherwise the builder decides.
std::optional<Split> BvhSplitRule::chooseSplit(const BuildRange& range, int depth) {
    const uint32_t n = range.size();
    const bool mayBeLeaf = n <= config_.effectiveLeafCap();
    if (n <= uint32_t(config_.maxLeaf)) return std::nullopt;
    if (allCentresEqual(range.centroidBounds)) {
        if (mayBeLeaf) return std::nullopt;
        return splitAtIndex(range, range.begin + n / 2);
    }
    if (nearDepthBound(depth, n)) return objectMedianSplit(range, range.centroidBounds.largestAxis());
    if (std::optional<Split> split = trySplit(range, mayBeLeaf)) return split;
    if (mayBeLeaf) return std::nullopt;
    return objectMedianSplit(range, range.centroidBounds.largestAxis());
}

std::vector<BvhNode, TraversalAllocator<BvhNode>> BvhSplitRule::build(std::span<PrimRef> refs, const BuildRange& root,
                                                                      int depth, std::vector<DeferredRange>* deferred,
                                                                      uint32_t deferBelow) {
    refs_ = refs;
    // The root, the padding slot that aligns the sibling pairs, and at most N - 1 pairs.
    return buildTopDown(
        root, depth, 2 * size_t(root.size()),
        [&](const BuildRange& range, uint32_t node, int rangeDepth) {
            if (!deferred || range.size() >= deferBelow) return false;
            deferred->push_back({range, node, rangeDepth});
            return true;
        },
        [&](const BuildRange& range, int rangeDepth) { return chooseSplit(range, rangeDepth); },
        [](const BuildRange& range, BvhNode& node) {
            node.index = range.begin;
            node.count = range.size();
        });
}

}  // namespace bvhlab
