// An animated scene as the instances of a two-level structure (framework/core/
// instanced_accelerator.h): the static world as one instance, each rigid part as one with its
// object-space geometry under its transform, and the animated triangles (AFF's `tpa`) as one
// deforming instance in world space, whose triangles setTime rewrites in place. Hits come back
// in the world scene's index space, so two levels answer as one tree over the scene does.
#pragma once

#include "framework/core/instanced_accelerator.h"
#include "framework/scene/animated_scene.h"

#include <vector>

namespace bvhlab {

class SceneInstances {
public:
    // Views `animated` (its scene's arrays and its static primitives), which must outlive this
    // and every structure built over instances().
    explicit SceneInstances(const AnimatedScene& animated);

    // The instances at the scene's current time, for createInstanced; they view this object.
    const std::vector<Instance>& instances() const { return instances_; }
    // After AnimatedScene::setTime: each instance's transform at the scene's time, and the
    // instances whose primitives moved in place: moveInstances' arguments.
    View<const glm::dmat4> transforms();
    View<const uint32_t> deformed() const { return deformed_; }

private:
    // A rigid part's geometry in its object space, in the layout a PrimitiveSet views.
    struct ObjectGeometry {
        std::vector<Triangle> triangles;
        std::vector<uint32_t> valid;
    };

    const AnimatedScene& animated_;
    std::vector<ObjectGeometry> objects_;  // per rigid part
    std::vector<uint32_t> animatedTriangles_;
    std::vector<Instance> instances_;
    std::vector<int> partOf_;  // per instance: its rigid part, or -1 (static or deforming)
    std::vector<glm::dmat4> transforms_;
    std::vector<uint32_t> deformed_;
};

}  // namespace bvhlab
