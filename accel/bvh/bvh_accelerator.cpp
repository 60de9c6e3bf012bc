#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/builders/build_threads.h"

#include "accel/bvh/layout/end_point_overlap.h"
#include "accel/bvh/layout/refit.h"
#include "accel/bvh/traverse/binary_bvh_traversal.h"

#include <fmt/format.h>

#include <bit>
#include <stdexcept>
#include <type_traits>

namespace bvhlab {

namespace {

template <typename Layout>
struct LayoutWidth {
    static constexpr int value = 2;
};
template <int N>
struct LayoutWidth<WideBvh<N>> {
    static constexpr int value = N;
};

// Adds the work counted from `before` to `after` to a ray's cost: a batch's quadric part, after
// the kernel's batch call gave the triangles' part.
void addWorkBetween(RayCost& cost, const QueryCounters& before, const QueryCounters& after) {
    const RayCost work = Accelerator::costBetween(before, after);
    cost.intersectionTests += work.intersectionTests;
    cost.traversalSteps += work.traversalSteps;
}

}  // namespace

template <typename Layout>
BvhAccelerator<Layout>::BvhAccelerator(BuilderRecord builder, const BvhBuildConfig& build,
                                       const TraversalConfig& traversal, const BvhStatsConfig& stats,
                                       const BvhUpdateConfig& update)
    : builder_(std::move(builder)),
      build_(build),
      traversal_(traversal),
      kernels_(traversalKernels<Layout>(traversal)),
      stats_(stats),
      update_(update),
      name_(builder_.name) {
    if constexpr (LayoutWidth<Layout>::value > 2) {
        name_ += std::to_string(LayoutWidth<Layout>::value);
        // The leaves test a block of triangles at a time: the SAH charges them so.
        build_.shared.sahBlockShift = std::countr_zero(unsigned(TriangleBlock::kLanes));
    }
}

template <typename Layout>
void BvhAccelerator<Layout>::build(const PrimitiveSet& prims) {
    // T_B: from the first read of the primitives (PrimRef preparation: boxes and centre bounds)
    // to the finished node arrays and leaf arrays (primitive indices and the primitives copied
    // in leaf order), including a collapse and the quadric tree.
    tree_ = Layout();
    binary_ = BinaryBvh();
    binaryStale_ = false;
    statistics_.reset();
    prims_ = prims;
    quadrics_ = QuadricBvh();
    triangles_ = prims.validTriangles().size();
    BinaryBvh binary = buildBvh(builder_, build_, prims);
    if constexpr (std::is_same_v<Layout, BinaryBvh>) {
        tree_ = std::move(binary);
    } else {
        const CollapseCosts costs{build_.shared.cTraversal, build_.shared.cIntersect, build_.shared.effectiveLeafCap()};
        onThreads(build_.shared.threads, [&] { tree_ = collapseToWide<LayoutWidth<Layout>::value>(binary, costs); });
        binary_ = std::move(binary);
    }
    if (prims.hasQuadrics()) {
        BvhBuildConfig config = build_;
        config.shared.sahBlockShift = 0;  // quadrics are tested one at a time
        quadrics_ = buildQuadricBvh(builder_, config, prims);
    }
}

template <typename Layout>
bool BvhAccelerator<Layout>::update(const PrimitiveSet& prims) {
    if (update_.mode == BvhUpdate::Rebuild) return false;
    if (prims.triangles.size() != prims_.triangles.size() || prims.spheres.size() != prims_.spheres.size() ||
        prims.cones.size() != prims_.cones.size() || prims.valid.size() != prims_.valid.size())
        throw std::invalid_argument(
            fmt::format("{}: an update over {} primitives ({} valid); the structure was built over {} ({} valid)",
                        name_, prims.triangles.size() + prims.spheres.size() + prims.cones.size(), prims.valid.size(),
                        prims_.triangles.size() + prims_.spheres.size() + prims_.cones.size(), prims_.valid.size()));
    prims_ = prims;
    statistics_.reset();
    onThreads(build_.shared.threads, [&] {
        if constexpr (std::is_same_v<Layout, BinaryBvh>) {
            refitBinary(tree_, prims);
            if (update_.mode == BvhUpdate::Insertion) optimizeByInsertion(tree_, build_.insertion.iterations);
        } else if (update_.mode == BvhUpdate::Insertion) {
            refitBinary(binary_, prims);
            optimizeByInsertion(binary_, build_.insertion.iterations);
            const CollapseCosts costs{build_.shared.cTraversal, build_.shared.cIntersect,
                                      build_.shared.effectiveLeafCap()};
            tree_ = collapseToWide<LayoutWidth<Layout>::value>(binary_, costs);
            binaryStale_ = false;
        } else {
            refitWide(tree_, prims);
            binaryStale_ = true;
        }
        if (!quadrics_.empty()) refitQuadrics(quadrics_, prims);
    });
    return true;
}

template <typename Layout>
BuildStats BvhAccelerator<Layout>::buildStats() const {
    if (statistics_) return *statistics_;
    if (binaryStale_ || binary_.leafTriangles.size() != binary_.primIndices.size()) {
        onThreads(build_.shared.threads, [&] { refitBinary(binary_, prims_); });
        binaryStale_ = false;
    }
    const BinaryBvh& binary = binaryTree();
    BuildStats stats;
    fillTreeStats(binary, build_.shared.cTraversal, build_.shared.cIntersect, stats);
    stats.leafBound = build_.shared.effectiveLeafCap();  // every builder's leaves, and the collapse's
    if (!binary.empty() && binary.leafTriangles.size() <= stats_.epoMaxTriangles)
        stats.epo = endPointOverlap(binary.nodes, binary.leafTriangles, build_.shared.cTraversal,
                                    build_.shared.cIntersect, build_.shared.threads);
    stats.primitives = triangles_;
    stats.bytes = tree_.bytes();
    if (!quadrics_.empty()) {
        BuildStats quadricStats;
        fillTreeStats(quadrics_, build_.shared.cTraversal, build_.shared.cIntersect, quadricStats);
        quadricStats.primitives = quadrics_.primIndices.size();
        const Bounds3 triangleRoot = binary.empty() ? Bounds3() : binary.nodes[0].box();
        combineTreeStats(stats, triangleRoot, quadricStats, quadrics_.nodes[0].box());
    }
    stats.figures.push_back({"kernel_bits", double(isaVectorBits(kernels_.isa)),
                             fmt::format("vector width of the traversal kernels that ran: {} (BVH::isa={})",
                                         isaName(kernels_.isa), isaName(traversal_.isa))});
    statistics_ = stats;
    decltype(binary_.leafTriangles)().swap(binary_.leafTriangles);
    return stats;
}

template <typename Layout>
const BinaryBvh& BvhAccelerator<Layout>::binaryTree() const {
    if constexpr (std::is_same_v<Layout, BinaryBvh>)
        return tree_;
    else
        return binary_;
}

// The triangles' tree first, then the quadrics' up to the closest hit found so far. One query
// for the counters, the work of both. The quadric part is a call of its own, out of line, so
// that the triangle-only path stays a triangle traversal and nothing more: inlined into it, the
// quadric tree's traversal cost triangle-only scenes 7-14 % per query, measured.
template <typename Layout>
bool BvhAccelerator<Layout>::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    const bool found = kernels_.forCounters(counters).findNearest(tree_, ray, hit, counters);
    if (quadrics_.empty()) [[likely]]
        return found;
    return findNearestQuadric(ray, found, hit, counters);
}

template <typename Layout>
bool BvhAccelerator<Layout>::isOccluded(const Ray& ray, QueryCounters& counters) const {
    if (kernels_.forCounters(counters).isOccluded(tree_, ray, counters)) return true;
    if (quadrics_.empty()) [[likely]]
        return false;
    return isOccludedQuadric(ray, counters);
}

template <typename Layout>
void BvhAccelerator<Layout>::findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters,
                                              View<RayCost> costs, RayCoherence coherence) const {
    kernels_.forCounters(counters, !costs.empty())
        .findNearestBatch(tree_, rays, hits, counters, costs, traversal_, coherence);
    if (quadrics_.empty()) [[likely]]
        return;
    // The quadric tree's part ray by ray, up to each ray's triangle hit, as findNearest does.
    for (size_t i = 0; i < rays.size(); ++i) {
        const QueryCounters before = counters;
        findNearestQuadric(rays[i], hits[i].found(), hits[i], counters);
        if (!costs.empty()) addWorkBetween(costs[i], before, counters);
    }
}

template <typename Layout>
void BvhAccelerator<Layout>::isOccludedBatch(View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters,
                                             View<RayCost> costs, RayCoherence coherence) const {
    kernels_.forCounters(counters, !costs.empty())
        .isOccludedBatch(tree_, rays, occluded, counters, costs, traversal_, coherence);
    if (quadrics_.empty()) [[likely]]
        return;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (occluded[i]) continue;
        const QueryCounters before = counters;
        occluded[i] = isOccludedQuadric(rays[i], counters) ? 1 : 0;
        if (!costs.empty()) addWorkBetween(costs[i], before, counters);
    }
}

template <typename Layout>
bool BvhAccelerator<Layout>::findNearestQuadric(const Ray& ray, bool found, Hit& hit, QueryCounters& counters) const {
    Ray rest = ray;
    if (found) rest.tmax = hit.t;
    QueryCounters work;
    found |= bvhlab::findNearest(quadrics_, rest, hit, work, traversal_);
    counters.addWork(work);
    return found;
}

template <typename Layout>
bool BvhAccelerator<Layout>::isOccludedQuadric(const Ray& ray, QueryCounters& counters) const {
    QueryCounters work;
    const bool occluded = bvhlab::isOccluded(quadrics_, ray, work, traversal_);
    counters.addWork(work);
    return occluded;
}

template class BvhAccelerator<BinaryBvh>;
template class BvhAccelerator<WideBvh<4>>;
template class BvhAccelerator<WideBvh<8>>;

}  // namespace bvhlab
