// Two levels (instancing), as an interface: a bottom-level structure per instance, built once in
// the instance's object space, under a top level over the instances' world boxes. An animation
// asks two things of it per frame: rigid instances placed anew (a new transform, no primitive
// touched) and deforming instances, whose primitives moved in place, brought up to date. Ours
// is accel/twolevel/two_level_accelerator.h (any registered structure below); Embree's
// instances are accel/embree/embree_instances.h.
#pragma once

#include "framework/core/accelerator.h"

#include <fmt/format.h>
#include <glm/glm.hpp>

#include <stdexcept>

namespace bvhlab {

// One instance: its primitives in object space, its transform into the world, and where its
// primitives are in the index space of the world scene it stands for (hits are reported there).
// The arrays `prims` views must outlive the structure; a deforming instance's are rewritten in
// place between frames (same counts).
struct Instance {
    PrimitiveSet prims;
    glm::dmat4 objectToWorld{1.0};   // affine
    uint32_t worldTriangleBase = 0;  // object triangle p is world primitive worldTriangleBase + p
    uint32_t worldSphereBase = 0;    // object sphere j is world primitive worldSphereBase + j
    uint32_t worldConeBase = 0;      // object cone k is world primitive worldConeBase + k

    uint32_t worldPrimitive(uint32_t objectPrim) const {
        switch (prims.kind(objectPrim)) {
            case PrimitiveKind::Triangle:
                return worldTriangleBase + objectPrim;
            case PrimitiveKind::Sphere:
                return worldSphereBase + (objectPrim - prims.sphereBase());
            case PrimitiveKind::Cone:
                break;
        }
        return worldConeBase + (objectPrim - prims.coneBase());
    }
};

class InstancedAccelerator : public Accelerator {
public:
    // build() builds every bottom level over its instance's primitives, then the top level;
    // the world's PrimitiveSet it is given is not read: the instances stand for it.

    // Places instance i at objectToWorld[i] (one per instance), brings the bottom level of each
    // instance in `deformed` up to its moved primitives (an update where that structure has
    // one, else a rebuild), then rebuilds the top level once. Transforms of another count or a
    // deformed instance that is not there throw std::invalid_argument before anything moves.
    void moveInstances(View<const glm::dmat4> objectToWorld, View<const uint32_t> deformed) {
        if (objectToWorld.size() != instanceCount())
            throw std::invalid_argument(
                fmt::format("{}: {} transforms for {} instances", name(), objectToWorld.size(), instanceCount()));
        for (uint32_t i : deformed)
            if (i >= instanceCount())
                throw std::invalid_argument(
                    fmt::format("{}: deformed instance {} of {} instances", name(), i, instanceCount()));
        move(objectToWorld, deformed);
    }
    virtual size_t instanceCount() const = 0;

protected:
    // moveInstances, its arguments checked.
    virtual void move(View<const glm::dmat4> objectToWorld, View<const uint32_t> deformed) = 0;
};

}  // namespace bvhlab
