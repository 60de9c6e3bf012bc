#include "accel/bvh/bvh_accelerator.h"

#include "accel/bvh/traverse/bvh_traversal.h"

#include <chrono>

namespace bvhlab {

std::string_view BvhAccelerator::name() const {
    switch (kind_) {
    case BvhKind::SpatialMedian: return "tdbvh";
    case BvhKind::BinnedSah: return "sahbvh";
    case BvhKind::SweepSah: return "sweepbvh";
    }
    return "bvh";
}

BuildStats BvhAccelerator::build(const PrimitiveSet& prims) {
    // Build time: from the first read of the triangles (PrimRef preparation: boxes and centre
    // bounds) to the finished node array and leaf arrays (primitive indices and the triangles
    // copied in leaf order). The statistics below are not part of it.
    bvh_ = Bvh();
    const auto start = std::chrono::steady_clock::now();
    bvh_ = buildBvh(kind_, config_, prims);
    const auto end = std::chrono::steady_clock::now();

    BuildStats stats;
    stats.buildMs = std::chrono::duration<double, std::milli>(end - start).count();
    stats.primitives = prims.valid.size();
    fillTreeStats(bvh_, config_.cTraversal, config_.cIntersect, stats);
    return stats;
}

bool BvhAccelerator::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    return bvhFindNearest(bvh_, ray, hit, counters, config_.robust);
}

bool BvhAccelerator::isOccluded(const Ray& ray, QueryCounters& counters) const {
    return bvhIsOccluded(bvh_, ray, counters, config_.robust);
}

}  // namespace bvhlab
