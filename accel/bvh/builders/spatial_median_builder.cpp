#include "accel/bvh/builders/spatial_median_builder.h"

namespace bvhlab {

std::optional<Split> SpatialMedianBuilder::trySplit(const BuildRange& range, bool /*mayBeLeaf*/) {
    // No cost model: leaves come from the size threshold alone, so every range offered is split.
    const Bounds3& box = median_.splitBox == MedianSplitBox::NodeBox ? range.bounds : range.centroidBounds;
    const int axis = box.largestAxis();
    const float middle = 0.5f * (box.lower[axis] + box.upper[axis]);
    const Split split = partition(range, [axis, middle](const PrimRef& r) { return r.center(axis) < middle; });
    if (split.left.size() == 0 || split.right.size() == 0) {
        return objectMedianSplit(range, range.centroidBounds.largestAxis());
    }
    return split;
}

}  // namespace bvhlab
