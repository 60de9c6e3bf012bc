// A small world of instances for the tests of two levels (ours and Embree's): objects of
// triangles, spheres and cones, placed by rotations, uniform scales and translations, one object
// placed twice, one that can deform in place; the same primitives carried into the world for
// brute force to answer as the instances should.
#pragma once

#include "framework/config/env.h"
#include "framework/core/instanced_accelerator.h"

#include <memory>
#include <string>
#include <vector>

namespace bvhlab::test {

// Primitives in one index space (PrimitiveSet's): every one valid.
struct PrimitiveArrays {
    std::vector<Triangle> triangles;
    std::vector<Sphere> spheres;
    std::vector<Cone> cones;
    std::vector<uint32_t> valid;

    void clear() { *this = {}; }
    void validateAll();  // `valid` lists every primitive
    PrimitiveSet prims() const { return {triangles, valid, spheres, cones}; }
};

// Three instances of two objects: object 0 placed as instances 0 and 2, object 1 as instance 1.
struct InstancedWorld {
    std::vector<PrimitiveArrays> objects;
    std::vector<int> objectOf = {0, 1, 0};
    PrimitiveArrays world;  // every instance's primitives, carried into the world in double

    InstancedWorld();
    // The instances placed by `placed`, their hits named in the world's index space.
    std::vector<Instance> instances(const std::vector<glm::dmat4>& placed) const;
    // Carries the objects as they now are into `world` by `placed`.
    void place(const std::vector<glm::dmat4>& placed);
    // Moves object `object`'s primitives in place, not rigidly (a wave through its vertices and
    // centres), `phase` choosing the wave; counts and validity stay.
    void deform(int object, double phase);
};

// The placements at `time`: a translation, a rotation with a uniform scale, and a rotation.
std::vector<glm::dmat4> placements(double time);

// Rays from a sphere around the world towards random points inside it.
std::vector<Ray> raysInto(const PrimitiveArrays& world, size_t n, uint32_t seed);

// Both queries of `accel` on 2000 rays into `world` answer as brute force over it: a closest
// hit agrees (hitsAgree) and names a primitive the ray meets there; occlusion is the same.
void expectAnswersAsBruteForce(const Accelerator& accel, const PrimitiveArrays& world, uint32_t seed);

// `scene` placed at time 0 and its two levels, built, with `bottom` below (createInstanced).
std::unique_ptr<InstancedAccelerator> builtAtTimeZero(InstancedWorld& scene, const std::string& bottom, const Env& env);

}  // namespace bvhlab::test
