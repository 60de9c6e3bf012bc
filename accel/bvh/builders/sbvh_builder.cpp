#include "accel/bvh/builders/sbvh_builder.h"

#include "accel/bvh/builders/build_steps.h"
#include "accel/bvh/builders/reference_split.h"
#include "accel/bvh/builders/top_down_recursion.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>

namespace bvhlab {

namespace {

// Where partition sends a reference (a bit per child).
enum RefSide : int { kLeft = 1, kRight = 2, kBoth = 3 };

}  // namespace

SbvhBuilder::SbvhBuilder(const BuildConfig& config, const BinnedSahConfig& binned, const SbvhConfig& sbvh,
                         std::span<const Triangle> triangles, float rootArea)
    : config_(config),
      triangles_(triangles),
      minOverlap_(sbvh.alpha * rootArea),
      objectBinning_(config, binned),
      spatialBinning_(config, binned.bins) {}

std::vector<PrimRef> SbvhBuilder::takeVector() {
    if (pool_.empty()) return {};
    std::vector<PrimRef> v = std::move(pool_.back());
    pool_.pop_back();
    v.clear();
    return v;
}

template <typename Side>
SbvhSplit SbvhBuilder::partition(SbvhRange& range, Side side) {
    return simd::withFloats4(config_.simd, [&](auto f) {
        BoundsAccumulator<decltype(f)> leftAcc, rightAcc;
        std::vector<PrimRef>& refs = range.refs;
        const size_t n = refs.size();
        std::vector<PrimRef> right = takeVector();
        right.reserve(n);
        size_t kept = 0;  // refs[0, kept) are the left child's; kept <= i, so nothing unread is overwritten
        for (size_t i = 0; i < n; ++i) {
            PrimRef l = refs[i], r = refs[i];
            const int s = side(refs[i], l, r);
            if (s & kRight) {
                right.push_back(r);
                rightAcc.add(r);
            }
            if (s & kLeft) {
                refs[kept++] = l;
                leftAcc.add(l);
            }
        }
        refs.resize(kept);
        // What the cut references used of the budget; the rest is shared by reference count.
        const size_t total = kept + right.size();
        assert(total - n <= range.budget);
        const uint32_t rest = uint32_t(range.budget - (total - n));
        const uint32_t leftBudget = total == 0 ? 0 : uint32_t(uint64_t(rest) * kept / total);
        SbvhRange rightRange{std::move(right), rightAcc.bounds(), rightAcc.centroidBounds(), rest - leftBudget};
        SbvhRange leftRange{std::move(refs), leftAcc.bounds(), leftAcc.centroidBounds(), leftBudget};
        return SbvhSplit{std::move(leftRange), std::move(rightRange)};
    });
}

SbvhSplit SbvhBuilder::splitAtIndex(SbvhRange& range, uint32_t mid) {
    return partition(range,
                     [i = 0u, mid](const PrimRef&, PrimRef&, PrimRef&) mutable { return i++ < mid ? kLeft : kRight; });
}

SbvhSplit SbvhBuilder::objectMedianSplit(SbvhRange& range, int axis) {
    const uint32_t mid = range.size() / 2;
    std::nth_element(range.refs.begin(), range.refs.begin() + mid, range.refs.end(),
                     [axis](const PrimRef& a, const PrimRef& b) {
                         const float ca = a.center(axis), cb = b.center(axis);
                         return ca < cb || (ca == cb && a.prim < b.prim);
                     });
    return splitAtIndex(range, mid);
}

// BvhSplitRule's leaf rules (split_rule.cpp), over a range of references.
std::optional<SbvhSplit> SbvhBuilder::chooseSplit(SbvhRange& range, int depth) {
    const uint32_t n = range.size();
    const bool mayBeLeaf = n <= config_.effectiveLeafCap();
    if (n <= uint32_t(config_.maxLeaf)) return std::nullopt;
    if (allCentresEqual(range.centroidBounds)) {
        if (mayBeLeaf) return std::nullopt;
        return splitAtIndex(range, n / 2);
    }
    if (nearDepthBound(depth, n)) return objectMedianSplit(range, range.centroidBounds.largestAxis());
    if (auto split = trySplit(range, mayBeLeaf)) return split;
    if (mayBeLeaf) return std::nullopt;
    return objectMedianSplit(range, range.centroidBounds.largestAxis());
}

std::optional<SbvhSplit> SbvhBuilder::trySplit(SbvhRange& range, bool mayBeLeaf) {
    const uint32_t n = range.size();
    const std::optional<ObjectPlane> object =
        objectBinning_.bestPlane(range.refs.data(), {0, n, range.bounds, range.centroidBounds});
    if (!object) return std::nullopt;
    float bestCost = object->cost;

    // Spatial splits only where the object split leaves its children overlapping (lambda >
    // alpha * A(root)): elsewhere they rarely win and cost a binning.
    std::optional<SpatialPlane> spatial;
    if (range.budget > 0) {
        const float overlap =
            intersectionOf(objectBinning_.leftBounds(*object), objectBinning_.rightBounds(*object)).halfArea();
        if (overlap > minOverlap_)
            spatial = spatialBinning_.bestPlane(range.refs, range.bounds, triangles_, range.budget);
        if (spatial && spatial->cost < bestCost) {
            bestCost = spatial->cost;
        } else {
            spatial.reset();
        }
    }
    if (mayBeLeaf && config_.sahTermination && sahPrefersLeaf(config_, range.bounds, n, bestCost)) return std::nullopt;

    const auto objectSide = [plane = *object](const PrimRef& ref, PrimRef&, PrimRef&) {
        return plane.isLeft(ref) ? kLeft : kRight;
    };
    if (!spatial) return partition(range, objectSide);

    // The spatial split with reference unsplitting: a cut reference goes whole to
    // one side when that costs less than the cut, judged against the binning's boxes and counts.
    const SpatialPlane& p = *spatial;
    const float areaLeft = p.left.halfArea(), areaRight = p.right.halfArea();
    const float testsLeft = float(config_.sahTests(p.leftCount)), testsRight = float(config_.sahTests(p.rightCount));
    const float cutCost = areaLeft * testsLeft + areaRight * testsRight;
    const float testsLeftOneLess = float(config_.sahTests(p.leftCount - 1));
    const float testsRightOneLess = float(config_.sahTests(p.rightCount - 1));
    auto split = partition(range, [&](const PrimRef& ref, PrimRef& left, PrimRef& right) {
        if (p.binOf(ref.upper[p.axis]) < p.plane) return kLeft;
        if (p.binOf(ref.lower[p.axis]) >= p.plane) return kRight;
        const Bounds3 box = ref.box();
        const auto [leftBox, rightBox] = splitReference(triangles_[ref.prim], box, p.axis, p.position);
        if (leftBox.isEmpty()) return kRight;
        if (rightBox.isEmpty()) return kLeft;
        const float allLeft = unionOf(p.left, box).halfArea() * testsLeft + areaRight * testsRightOneLess;
        const float allRight = areaLeft * testsLeftOneLess + unionOf(p.right, box).halfArea() * testsRight;
        if (allLeft <= cutCost && allLeft <= allRight) return kLeft;
        if (allRight <= cutCost) return kRight;
        left = PrimRef::of(leftBox, ref.prim);
        right = PrimRef::of(rightBox, ref.prim);
        return kBoth;
    });
    if (split.left.size() != 0 && split.right.size() != 0) return split;
    // Every reference went whole to one side (none was cut, so they are the range's own, in
    // order): the object split instead.
    range = std::move(split.left.size() != 0 ? split.left : split.right);
    return partition(range, objectSide);
}

BvhNodes SbvhBuilder::build(SbvhRange root, int depth, std::vector<Deferred>* deferred, uint32_t deferBelow) {
    // The root, the padding slot that aligns the sibling pairs, and at most R - 1 pairs over at
    // most R = N + budget references.
    const size_t maxNodes = 2 * (size_t(root.size()) + root.budget);
    return buildTopDown(
        std::move(root), depth, maxNodes,
        [&](SbvhRange& range, uint32_t node, int rangeDepth) {
            if (!deferred || range.size() >= deferBelow) return false;
            deferred->push_back({std::move(range), node, rangeDepth});
            return true;
        },
        [&](SbvhRange& range, int rangeDepth) { return chooseSplit(range, rangeDepth); },
        [&](SbvhRange& range, BvhNode& node) {
            node.index = uint32_t(leafPrims_.size());
            node.count = range.size();
            for (const PrimRef& ref : range.refs) leafPrims_.push_back(ref.prim);
            pool_.push_back(std::move(range.refs));
        });
}

BinaryBvh buildSbvh(const BuildConfig& config, const BinnedSahConfig& binned, const SbvhConfig& sbvh,
                    const PrimitiveSet& prims) {
    const size_t n = prims.validTriangles().size();
    SbvhRange root;
    root.refs.resize(n);
    const BuildRange all = preparePrimRefs(prims, root.refs.data(), config.simd);
    root.bounds = all.bounds;
    root.centroidBounds = all.centroidBounds;
    root.budget = uint32_t(double(sbvh.growth) * double(n));
    const float rootArea = root.bounds.halfArea();

    // The nodes above the jobs, then the jobs' subtrees and leaf entries appended in the order
    // they were deferred (build_jobs.h): one tree whatever the thread count.
    SbvhBuilder top(config, binned, sbvh, prims.triangles, rootArea);
    std::vector<SbvhBuilder::Deferred> jobs;
    BinaryBvh bvh;
    bvh.nodes = top.build(std::move(root), 0, &jobs, kJobPrimitives);
    struct Subtree {
        BvhNodes nodes;
        std::vector<uint32_t> leafPrims;
    };
    std::vector<Subtree> subtrees(jobs.size());
    onThreads(config.threads, [&] {
        tbb::parallel_for(size_t(0), jobs.size(), [&](size_t j) {
            SbvhBuilder builder(config, binned, sbvh, prims.triangles, rootArea);
            subtrees[j].nodes = builder.build(std::move(jobs[j].range), jobs[j].depth);
            subtrees[j].leafPrims = std::move(builder.leafPrims());
        });
    });
    std::vector<uint32_t>& leafPrims = top.leafPrims();
    for (size_t j = 0; j < jobs.size(); ++j) {
        appendSubtree(bvh.nodes, jobs[j].node, subtrees[j].nodes, uint32_t(leafPrims.size()));
        leafPrims.insert(leafPrims.end(), subtrees[j].leafPrims.begin(), subtrees[j].leafPrims.end());
    }
    bvh.primIndices = std::move(leafPrims);
    copyLeafTriangles(prims, config.threads, bvh);
    return bvh;
}

}  // namespace bvhlab
