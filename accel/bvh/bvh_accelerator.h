// The BVH accelerators behind our interface: one class, one node layout and one traversal,
// parameterised by the builder (tdbvh, sahbvh, sweepbvh).
#pragma once

#include "accel/bvh/build/bvh_builder.h"
#include "framework/core/accelerator.h"

namespace bvhlab {

class BvhAccelerator final : public Accelerator {
public:
    BvhAccelerator(BvhKind kind, const BvhBuildConfig& config) : kind_(kind), config_(config) {}

    std::string_view name() const override;
    BuildStats build(const PrimitiveSet& prims) override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;

    const Bvh& bvh() const { return bvh_; }
    const BvhBuildConfig& config() const { return config_; }

private:
    BvhKind kind_;
    BvhBuildConfig config_;
    Bvh bvh_;
};

}  // namespace bvhlab
