// tdbvh: the spatial-median BVH (nanoGolem's TDBVH, the report's starting point). Each range
// is split at the middle of the longest axis of its box: the box of the primitives
// (MedianSplitBox::NodeBox) or of their centres (CentroidBox, the default); a primitive goes left
// when its centre lies below the middle. When one side would be empty, the range is split at
// the object median along the widest axis of the centres instead.
#pragma once

#include "accel/bvh/builders/split_rule.h"

#include <string_view>
#include <tuple>

namespace bvhlab {

enum class MedianSplitBox {
    CentroidBox,  // halve the box of their centres (pbrt's "middle"; never an empty side unless
                  // rounding puts the midpoint on the lowest centre)
    NodeBox,      // halve the box of the primitives (classic spatial median)
};
inline constexpr std::string_view kMedianSplitBoxWords[] = {"centroidbox", "nodebox"};

struct SpatialMedianConfig {
    MedianSplitBox splitBox = MedianSplitBox::CentroidBox;  // which box's longest axis is halved

    bool operator==(const SpatialMedianConfig&) const = default;
};

namespace keys::BVH {
inline constexpr FieldKey<&SpatialMedianConfig::splitBox> tdbvhSplit{
    "BVH::tdbvhSplit", kMedianSplitBoxWords,
    "tdbvh: halve the longest axis of the box of the centres, or of the node's box"};
}  // namespace keys::BVH
inline constexpr std::tuple kSpatialMedianKeys{&keys::BVH::tdbvhSplit};

class SpatialMedianBuilder final : public BvhSplitRule {
public:
    SpatialMedianBuilder(const BuildConfig& config, const SpatialMedianConfig& median)
        : BvhSplitRule(config), median_(median) {}

protected:
    std::optional<Split> trySplit(const BuildRange& range, bool mayBeLeaf) override;

private:
    SpatialMedianConfig median_;
};

}  // namespace bvhlab
