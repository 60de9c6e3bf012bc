// tdbvh: the spatial-median BVH (nanoGolem's TDBVH, the report's starting point). Each range
// is split at the middle of the longest axis of its box: the box of the primitives
// (MedianSplitBox::NodeBox) or of their centres (CentroidBox, the default); a primitive goes left
// when its centre lies below the middle. When one side would be empty, the range is split at
// the object median along the widest axis of the centres instead.
#pragma once

#include "accel/bvh/builders/bvh_builder.h"

namespace bvhlab {

class SpatialMedianBuilder final : public TopDownBuilder {
public:
    using TopDownBuilder::TopDownBuilder;

protected:
    std::optional<Split> trySplit(const BuildRange& range, bool mayBeLeaf) override;
};

}  // namespace bvhlab
