// Two levels (instancing): a bottom-level structure per instance, built once over the instance's
// primitives in its own object space by any accelerator, under a top-level binary BVH over the
// instances' world boxes. Moving a rigid instance is a new transform and a rebuild of the top
// level over a handful of boxes: no primitive moves, no bottom level is touched.
#pragma once

#include "accel/bvh/builders/bvh_builder.h"
#include "framework/core/accelerator.h"

#include <glm/glm.hpp>

#include <functional>
#include <memory>
#include <vector>

namespace bvhlab {

// One instance: its primitives in object space, its transform into the world, and where its
// primitives are in the index space of the world scene it stands for (hits are reported there).
struct Instance {
    PrimitiveSet prims;
    glm::dmat4 objectToWorld{1.0};   // affine
    uint32_t worldTriangleBase = 0;  // object triangle p is world primitive worldTriangleBase + p
    uint32_t worldSphereBase = 0;    // object sphere j is world primitive worldSphereBase + j
    uint32_t worldConeBase = 0;      // object cone k is world primitive worldConeBase + k

    uint32_t worldPrimitive(uint32_t objectPrim) const;
};

class TwoLevelAccelerator final : public Accelerator {
public:
    using MakeBottom = std::function<std::unique_ptr<Accelerator>()>;

    // `makeBottom` makes each instance's structure; `top` configures the top level's build.
    TwoLevelAccelerator(std::vector<Instance> instances, MakeBottom makeBottom, const BvhBuildConfig& top);

    const char* name() const override { return "twolevel"; }
    // Builds every bottom level over its instance's primitives, then the top level. `prims`, the
    // world's, is not read: the instances stand for it.
    void build(const PrimitiveSet& prims) override;
    // Places instance i by objectToWorld[i] and rebuilds the top level; the bottom levels stay.
    void setTransforms(View<const glm::dmat4> objectToWorld);
    // The instances, the top level's nodes and leaves, the bottoms' primitives and bytes summed.
    void statistics(BuildStatistics& out) const override;
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override;
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override;

    const Accelerator& bottom(size_t i) const { return *bottoms_[i]; }
    size_t instanceCount() const { return instances_.size(); }

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
