// Two levels (instancing), ours: a bottom-level structure per instance, built once over the
// instance's primitives in its own object space by any accelerator, under a top-level binary BVH
// over the instances' world boxes. Moving a rigid instance is a new transform and a rebuild of
// the top level over a handful of boxes: no primitive moves, no bottom level is touched.
#pragma once

#include "accel/bvh/builders/bvh_builder.h"
#include "framework/core/instanced_accelerator.h"

#include <functional>
#include <memory>
#include <vector>

namespace bvhlab {

class TwoLevelAccelerator final : public InstancedAccelerator {
public:
    using MakeBottom = std::function<std::unique_ptr<Accelerator>()>;

    // `makeBottom` makes each instance's structure; `top` configures the top level's build.
    TwoLevelAccelerator(std::vector<Instance> instances, MakeBottom makeBottom, const BvhBuildConfig& top);

    const char* name() const override { return "twolevel"; }
    void build(const PrimitiveSet& prims) override;
    size_t instanceCount() const override { return instances_.size(); }
    // The instances, the top level's nodes and leaves, the bottoms' primitives and bytes summed.
    void statistics(BuildStatistics& out) const override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;

    const Accelerator& bottom(size_t i) const { return *bottoms_[i]; }

protected:
    void move(View<const glm::dmat4> objectToWorld, View<const uint32_t> deformed) override;

private:
    // An instance as the queries use it: the world-to-object transform in float, applied to a
    // ray's origin and direction without normalising, so that t is the same in both spaces.
    struct Placement {
        glm::mat4x3 worldToObject;
    };
    void placeInstance(size_t i);
    void buildTop();
    Ray toObject(const Ray& ray, size_t i) const;
    // The top level's walk along `ray`, whose tmax the caller may shrink as it finds hits:
    // `visit(instance)` for each instance of each leaf the ray reaches, until it returns true.
    // Counts the nodes it visits and one query however many instances answer (each counts one).
    template <typename Visit>
    void walk(const Ray& ray, QueryCounters& counters, Visit&& visit) const;

    std::vector<Instance> instances_;
    MakeBottom makeBottom_;
    BvhBuildConfig topConfig_;
    std::vector<std::unique_ptr<Accelerator>> bottoms_;
    std::vector<Bounds3> objectBoxes_;  // of each instance's valid primitives
    std::vector<Bounds3> worldBoxes_;
    std::vector<Placement> placements_;
    std::vector<BvhNode, TraversalAllocator<BvhNode>> topNodes_;
    std::vector<uint32_t> topInstances_;  // leaf order
};

}  // namespace bvhlab
