// sahbvh4: the binned-SAH tree of sahbvh, collapsed into 4-wide nodes (wide_bvh.h) and
// traversed four child boxes at a time. Same builder, same leaves, same env keys as sahbvh:
// only the traversal's step differs, so the two measure what the node width buys.
#pragma once

#include "accel/bvh/build/bvh_builder.h"
#include "accel/bvh/layout/wide_bvh.h"
#include "framework/core/accelerator.h"

namespace bvhlab {

class WideBvhAccelerator final : public Accelerator {
public:
    WideBvhAccelerator(BvhKind kind, const BvhBuildConfig& config) : kind_(kind), config_(config) {}

    std::string_view name() const override;
    // Build time includes the collapse. #Nodes, #Leaves, depth and SAH are the binary tree's
    // (the same formula as every builder's); memory is the wide tree's.
    BuildStats build(const PrimitiveSet& prims) override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;


private:
    BvhKind kind_;
    BvhBuildConfig config_;
    WideBvh bvh_;
};

}  // namespace bvhlab
