#include "accel/bvh/builders/binned_sah_builder.h"

namespace bvhlab {

std::optional<Split> BinnedSahBuilder::trySplit(const BuildRange& range, bool mayBeLeaf) {
    const std::optional<ObjectPlane> best = binning_.bestPlane(refs_.data(), range);
    if (!best) return std::nullopt;
    if (mayBeLeaf && config_.sahTermination && sahPrefersLeaf(range, best->cost)) return std::nullopt;
    return partition(range, [plane = *best](const PrimRef& r) { return plane.isLeft(r); });
}

}  // namespace bvhlab
