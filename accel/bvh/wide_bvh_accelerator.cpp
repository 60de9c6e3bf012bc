#include "accel/bvh/wide_bvh_accelerator.h"

#include "accel/bvh/traverse/wide_bvh_traversal.h"

#include <chrono>

namespace bvhlab {

std::string_view WideBvhAccelerator::name() const {
    switch (kind_) {
    case BvhKind::SpatialMedian: return "tdbvh4";
    case BvhKind::BinnedSah: return "sahbvh4";
    case BvhKind::SweepSah: return "sweepbvh4";
    }
    return "bvh4";
}

BuildStats WideBvhAccelerator::build(const PrimitiveSet& prims) {
    bvh_ = WideBvh();
    const auto start = std::chrono::steady_clock::now();
    Bvh binary = buildBvh(kind_, config_, prims);
    BuildStats stats;
    const auto collapseStart = std::chrono::steady_clock::now();
    fillTreeStats(binary, config_.cTraversal, config_.cIntersect, stats);  // not timed
    const auto statsEnd = std::chrono::steady_clock::now();
    bvh_ = collapseToWide(std::move(binary));
    const auto end = std::chrono::steady_clock::now();

    stats.buildMs = std::chrono::duration<double, std::milli>((collapseStart - start) + (end - statsEnd)).count();
    stats.primitives = prims.valid.size();
    stats.bytes = bvh_.bytes();
    return stats;
}

bool WideBvhAccelerator::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    return wideBvhFindNearest(bvh_, ray, hit, counters, config_.robust);
}

bool WideBvhAccelerator::isOccluded(const Ray& ray, QueryCounters& counters) const {
    return wideBvhIsOccluded(bvh_, ray, counters, config_.robust);
}

}  // namespace bvhlab
