#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/builders/build_threads.h"

#include "accel/bvh/layout/end_point_overlap.h"
#include "accel/bvh/traverse/binary_bvh_traversal.h"

#include <fmt/format.h>

#include <bit>
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

}  // namespace

template <typename Layout>
BvhAccelerator<Layout>::BvhAccelerator(BuilderRecord builder, const BvhBuildConfig& build,
                                       const TraversalConfig& traversal, const BvhStatsConfig& stats)
    : builder_(std::move(builder)),
      build_(build),
      traversal_(traversal),
      kernels_(traversalKernels<Layout>(traversal)),
      stats_(stats),
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
    statistics_.reset();
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
BuildStats BvhAccelerator<Layout>::buildStats() const {
    if (statistics_) return *statistics_;
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
    binary_ = BinaryBvh();
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
    if (quadrics_.empty()) [[likely]]
        return kernels_.forCounters(counters, !costs.empty())
            .findNearestBatch(tree_, rays, hits, counters, costs, traversal_, coherence);
    Accelerator::findNearestBatch(rays, hits, counters, costs, coherence);
}

template <typename Layout>
void BvhAccelerator<Layout>::isOccludedBatch(View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters,
                                             View<RayCost> costs, RayCoherence coherence) const {
    if (quadrics_.empty()) [[likely]]
        return kernels_.forCounters(counters, !costs.empty())
            .isOccludedBatch(tree_, rays, occluded, counters, costs, traversal_, coherence);
    Accelerator::isOccludedBatch(rays, occluded, counters, costs, coherence);
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
