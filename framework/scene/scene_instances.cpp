#include "framework/scene/scene_instances.h"

#include <algorithm>

namespace bvhlab {
namespace {

bool hasFiniteCorners(const Triangle& tri) { return isFinite(tri.v0) && isFinite(tri.v1) && isFinite(tri.v2); }

}  // namespace

SceneInstances::SceneInstances(const AnimatedScene& animated) : animated_(animated) {
    const Scene& scene = animated.scene;
    const PrimitiveSet world = scene.primitives();

    // The static world: the scene's own arrays, its never-moving valid primitives.
    instances_.push_back({.prims = {world.triangles, animated.staticPrimitives(), world.spheres, world.cones},
                          .worldSphereBase = world.sphereBase(),
                          .worldConeBase = world.coneBase()});
    partOf_.push_back(-1);

    objects_.resize(animated.parts.size());
    for (size_t p = 0; p < animated.parts.size(); ++p) {
        const RigidPart& part = animated.parts[p];
        ObjectGeometry& object = objects_[p];
        for (uint32_t i = part.triangles.first; i < part.triangles.end(); ++i) {
            const glm::uvec3 idx = scene.indices[i] - glm::uvec3(part.vertices.first);
            object.triangles.push_back({part.positions[idx.x], part.positions[idx.y], part.positions[idx.z]});
        }
        // Object index space: triangles, then spheres, then cones (PrimitiveSet's).
        const uint32_t triangles = uint32_t(object.triangles.size());
        const uint32_t spheres = uint32_t(part.objectSpheres.size());
        // Every triangle with finite corners, slivers included: whether the world counts a
        // sliver degenerate (its normal underflows in float) changes as the part turns, and a
        // triangle the world builds over must be in its instance too.
        for (uint32_t i = 0; i < triangles; ++i)
            if (hasFiniteCorners(object.triangles[i])) object.valid.push_back(i);
        for (uint32_t j = 0; j < spheres; ++j)
            if (!isDegenerate(part.objectSpheres[j])) object.valid.push_back(triangles + j);
        for (uint32_t k = 0; k < part.objectCones.size(); ++k)
            if (!isDegenerate(part.objectCones[k])) object.valid.push_back(triangles + spheres + k);
        instances_.push_back({.prims = {object.triangles, object.valid, part.objectSpheres, part.objectCones},
                              .worldTriangleBase = part.triangles.first,
                              .worldSphereBase = world.sphereBase() + part.spheres.first,
                              .worldConeBase = world.coneBase() + part.cones.first});
        partOf_.push_back(int(p));
    }

    // The animated triangles in world space, degenerate ones included: their validity changes
    // from frame to frame while a structure's primitive set stays; a degenerate triangle is
    // never hit (its determinant is 0) and its box is a point or a segment.
    for (const AnimatedTriangle& tri : animated.animatedTriangles) animatedTriangles_.push_back(tri.triangle);
    std::sort(animatedTriangles_.begin(), animatedTriangles_.end());
    if (!animatedTriangles_.empty()) {
        deformed_.push_back(uint32_t(instances_.size()));
        instances_.push_back({.prims = {world.triangles, animatedTriangles_}});
        partOf_.push_back(-1);
    }
    transforms();
    for (size_t i = 0; i < instances_.size(); ++i) instances_[i].objectToWorld = transforms_[i];
}

View<const glm::dmat4> SceneInstances::transforms() {
    transforms_.resize(instances_.size());
    for (size_t i = 0; i < instances_.size(); ++i)
        transforms_[i] = partOf_[i] < 0
                             ? glm::dmat4(1.0)
                             : animated_.nodeTransformAt(animated_.parts[size_t(partOf_[i])].node, animated_.time());
    return transforms_;
}

}  // namespace bvhlab
