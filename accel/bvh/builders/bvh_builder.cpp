#include "accel/bvh/builders/bvh_builder.h"

#include "accel/bvh/builders/binned_sah_builder.h"
#include "accel/bvh/builders/build_jobs.h"
#include "accel/bvh/builders/insertion_optimizer.h"
#include "accel/bvh/builders/top_down_recursion.h"

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <stdexcept>

namespace bvhlab {

bool allCentresEqual(const Bounds3& c) { return c.lower.x == c.upper.x && c.lower.y == c.upper.y && c.lower.z == c.upper.z; }

bool nearDepthBound(int depth, uint32_t n) {
    const int ceilLog2 = n <= 1 ? 0 : int(std::bit_width(n - 1));
    return depth + ceilLog2 >= kBvhMaxDepth - 1;
}

bool sahPrefersLeaf(const BvhBuildConfig& config, const Bounds3& bounds, uint32_t n, float splitCost) {
    const float area = bounds.halfArea();
    if (!(area > 0.0f)) return false;  // no meaningful ratio: keep splitting
    const float tests = float(config.sahTests(n));
    return !(config.cTraversal + config.cIntersect * splitCost / area < config.cIntersect * tests);
}

Split TopDownBuilder::splitAtIndex(const BuildRange& range, uint32_t mid) {
    const PrimRef* refs = refs_.data();
    return simd::withFloats4(config_.simd, [&](auto f) {
        using Accumulator = BoundsAccumulator<decltype(f)>;
        return Split{boundsOf<Accumulator>(refs, range.begin, mid), boundsOf<Accumulator>(refs, mid, range.end)};
    });
}

Split TopDownBuilder::objectMedianSplit(const BuildRange& range, int axis) {
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
std::optional<Split> TopDownBuilder::chooseSplit(const BuildRange& range, int depth) {
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

std::vector<BvhNode, TraversalAllocator<BvhNode>> TopDownBuilder::build(std::span<PrimRef> refs,
                                                                        const BuildRange& root, int depth,
                                                                        std::vector<DeferredRange>* deferred,
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

namespace {

// Step one of buildBvh: one PrimRef per valid triangle, and their boxes, in lanes of F.
template <typename F>
BuildRange preparePrimRefsWith(const PrimitiveSet& prims, PrimRef* out) {
    const std::span<const uint32_t> validTriangles = prims.validTriangles();
    const uint32_t n = uint32_t(validTriangles.size());
    const Triangle* triangles = prims.triangles.data();
    const uint32_t* valid = validTriangles.data();
    BoundsAccumulator<F> acc;
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t prim = valid[i];
        const Triangle& t = triangles[prim];
        // Unaligned 4-float loads (lane 3 is ignored); none reads past the triangle, which may
        // end the array.
        const F v0 = F::loadu(&t.v0.x), v1 = F::loadu(&t.v1.x), v2 = F::loadLast3(&t.v2.x);
        PrimRef& ref = out[i];
        min(min(v0, v1), v2).store(ref.lower);
        max(max(v0, v1), v2).store(ref.upper);
        ref.prim = prim;
        ref.pad = 0;
        acc.add(ref);
    }
    return {0, n, acc.bounds(), acc.centroidBounds()};
}

}  // namespace

BuildRange preparePrimRefs(const PrimitiveSet& prims, PrimRef* out, bool simd) {
    return simd::withFloats4(simd, [&](auto f) { return preparePrimRefsWith<decltype(f)>(prims, out); });
}

namespace {

// The nodes over `all` (prepared PrimRefs whose boxes and centres `root` bounds), which it
// reorders into leaf order: the nodes above the jobs, then the jobs' subtrees appended in the
// order they were deferred, so the same tree whatever the thread count and the schedule.
std::vector<BvhNode, TraversalAllocator<BvhNode>> buildNodes(const SplitRuleFactory& makeBuilder,
                                                            const BvhBuildConfig& config, std::span<PrimRef> all,
                                                            const BuildRange& root) {
    std::vector<DeferredRange> jobs;
    std::vector<BvhNode, TraversalAllocator<BvhNode>> nodes =
        makeBuilder(config)->build(all, root, 0, &jobs, kJobPrimitives);
    std::vector<std::vector<BvhNode, TraversalAllocator<BvhNode>>> subtrees(jobs.size());
    onThreads(config.threads, [&] {
        tbb::enumerable_thread_specific<std::unique_ptr<TopDownBuilder>> builders(
            [&] { return makeBuilder(config); });
        tbb::parallel_for(size_t(0), jobs.size(), [&](size_t j) {
            subtrees[j] = builders.local()->build(all, jobs[j].range, jobs[j].depth);
        });
    });
    for (size_t j = 0; j < jobs.size(); ++j) appendSubtree(nodes, jobs[j].node, subtrees[j]);
    return nodes;
}

}  // namespace

void fillLeafArrays(Bvh& bvh, const PrimRef* refs, const PrimitiveSet& prims, int threads) {
    const size_t n = prims.validTriangles().size();
    bvh.primIndices.resize(n);
    for (size_t i = 0; i < n; ++i) bvh.primIndices[i] = refs[i].prim;
    copyLeafTriangles(prims, threads, bvh);
}

void copyLeafTriangles(const PrimitiveSet& prims, int threads, Bvh& bvh) {
    const size_t n = bvh.primIndices.size();
    bvh.leafTriangles.resize(n);
    onThreads(threads, [&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) bvh.leafTriangles[i] = prims.triangles[bvh.primIndices[i]];
        });
    });
}

namespace {

// A plugin's split rule may reorder the PrimRefs, nothing else: each valid triangle once, with
// the box it was given.
void checkPrimRefsOf(const BvhBuilder& builder, const PrimRef* refs, const PrimitiveSet& prims) {
    const std::span<const uint32_t> valid = prims.validTriangles();
    std::vector<uint8_t> seen(prims.triangles.size(), 0);
    for (const uint32_t prim : valid) seen[prim] = 1;
    for (size_t i = 0; i < valid.size(); ++i) {
        const PrimRef& ref = refs[i];
        const bool known = ref.prim < seen.size() && seen[ref.prim] == 1;
        if (known) seen[ref.prim] = 2;
        Bounds3 box;
        if (known)
            for (const Vec3& v : {prims.triangles[ref.prim].v0, prims.triangles[ref.prim].v1, prims.triangles[ref.prim].v2})
                box.extend(v);
        if (!known || ref.box().lower != box.lower || ref.box().upper != box.upper)
            throw std::runtime_error(fmt::format("builder '{}' changed the primitives it was to reorder (at index {}: "
                                                 "primitive {}{})",
                                                 builder.name, i, ref.prim, known ? ", another box" : ", not one of them once"));
    }
}

// The builder's tree, before any optimisation.
Bvh buildBinary(const BvhBuilder& builder, const BvhBuildConfig& config, const PrimitiveSet& prims) {
    if (builder.wholeTree) return builder.wholeTree(config, prims);
    const size_t n = prims.validTriangles().size();
    // Uninitialised storage: every PrimRef is written by preparePrimRefs.
    const std::unique_ptr<PrimRef[]> refs = std::make_unique_for_overwrite<PrimRef[]>(n);
    const BuildRange root = preparePrimRefs(prims, refs.get(), config.simd);
    Bvh bvh;
    bvh.nodes = buildNodes(builder.splitRule, config, std::span<PrimRef>(refs.get(), n), root);
    if (builder.fromPlugin) checkPrimRefsOf(builder, refs.get(), prims);
    fillLeafArrays(bvh, refs.get(), prims, config.threads);
    return bvh;
}

}  // namespace

Bvh buildBvh(const BvhBuilder& builder, const BvhBuildConfig& config, const PrimitiveSet& prims) {
    Bvh bvh = buildBinary(builder, config, prims);
    if (config.optimize == BvhOptimize::Insertion) optimizeByInsertion(bvh, config.optimizeIterations);
    return bvh;
}

QuadricBvh buildQuadricBvh(const BvhBuilder& builder, const BvhBuildConfig& config, const PrimitiveSet& prims) {
    // Few primitives as a rule (the SPD scenes have thousands, not millions): plain loops. The
    // builders of whole trees are for the millions of triangles (ploc) or clip them (sbvh); their
    // spheres and cones get binned SAH, as a plugin's do.
    const SplitRuleFactory binnedSah = [](const BvhBuildConfig& c) { return std::make_unique<BinnedSahBuilder>(c); };
    const std::span<const uint32_t> valid = prims.validQuadrics();
    std::vector<PrimRef> refs(valid.size());
    BoundsAccumulator<simd::Scalar<4>> acc;
    for (size_t i = 0; i < valid.size(); ++i) {
        refs[i] = PrimRef::of(boundsOf(prims.quadric(valid[i])), valid[i]);
        acc.add(refs[i]);
    }
    QuadricBvh bvh;
    bvh.nodes = buildNodes(builder.splitRule && !builder.fromPlugin ? builder.splitRule : binnedSah, config, refs,
                           {0, uint32_t(refs.size()), acc.bounds(), acc.centroidBounds()});
    for (const PrimRef& ref : refs) {
        bvh.primIndices.push_back(ref.prim);
        bvh.leafShapes.push_back(prims.quadric(ref.prim));
    }
    return bvh;
}

}  // namespace bvhlab
