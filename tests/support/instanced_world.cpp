#include "tests/support/instanced_world.h"

#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "tests/support/bvh_checks.h"
#include "tests/support/random_geometry.h"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <random>

namespace bvhlab::test {

namespace {

// An object: `triangles` random ones, a few spheres and cones among them.
PrimitiveArrays randomObject(size_t triangles, uint32_t seed, float extent, float size) {
    PrimitiveArrays object;
    object.triangles = randomSoup(triangles, seed, extent, size).triangles;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(0.0f, extent), radius(0.1f * size, 0.5f * size);
    for (int k = 0; k < 6; ++k) object.spheres.push_back({{pos(rng), pos(rng), pos(rng)}, radius(rng)});
    for (int k = 0; k < 4; ++k) {
        const Vec3 base(pos(rng), pos(rng), pos(rng));
        object.cones.push_back({base, radius(rng), base + Vec3(randomUnit(rng)) * size, radius(rng)});
    }
    object.validateAll();
    return object;
}

// The factor of a uniform scale in `m`: the length of its first column.
double scaleOf(const glm::dmat4& m) { return glm::length(DVec3(m[0])); }

}  // namespace

void PrimitiveArrays::validateAll() {
    valid.clear();
    const size_t n = triangles.size() + spheres.size() + cones.size();
    for (size_t i = 0; i < n; ++i) valid.push_back(uint32_t(i));
}

InstancedWorld::InstancedWorld() : objects{randomObject(300, 1, 4.0f, 0.8f), randomObject(200, 2, 3.0f, 1.0f)} {}

std::vector<Instance> InstancedWorld::instances(const std::vector<glm::dmat4>& placed) const {
    size_t triangles = 0, spheres = 0;
    for (int object : objectOf) {
        triangles += objects[object].triangles.size();
        spheres += objects[object].spheres.size();
    }
    std::vector<Instance> out;
    uint32_t triangleBase = 0, sphereBase = uint32_t(triangles), coneBase = uint32_t(triangles + spheres);
    for (size_t i = 0; i < objectOf.size(); ++i) {
        const PrimitiveArrays& object = objects[objectOf[i]];
        out.push_back({object.prims(), placed[i], triangleBase, sphereBase, coneBase});
        triangleBase += uint32_t(object.triangles.size());
        sphereBase += uint32_t(object.spheres.size());
        coneBase += uint32_t(object.cones.size());
    }
    return out;
}

void InstancedWorld::place(const std::vector<glm::dmat4>& placed) {
    world.clear();
    for (size_t i = 0; i < objectOf.size(); ++i) {
        const PrimitiveArrays& object = objects[objectOf[i]];
        const glm::dmat4& m = placed[i];
        auto carry = [&](const Vec3& v) { return Vec3(m * glm::dvec4(DVec3(v), 1.0)); };
        const float scale = float(scaleOf(m));
        for (const Triangle& t : object.triangles) world.triangles.push_back({carry(t.v0), carry(t.v1), carry(t.v2)});
        for (const Sphere& s : object.spheres) world.spheres.push_back({carry(s.centre), scale * s.radius});
        for (const Cone& c : object.cones)
            world.cones.push_back({carry(c.base), scale * c.baseRadius, carry(c.apex), scale * c.apexRadius});
    }
    world.validateAll();
}

void InstancedWorld::deform(int object, double phase) {
    auto wave = [&](const Vec3& v) {
        return v + 0.3f * Vec3(float(std::sin(2.0 * v.y + phase)), float(std::cos(2.0 * v.z + phase)),
                               float(std::sin(2.0 * v.x - phase)));
    };
    PrimitiveArrays& o = objects[object];
    for (Triangle& t : o.triangles) t = {wave(t.v0), wave(t.v1), wave(t.v2)};
    for (Sphere& s : o.spheres) s.centre = wave(s.centre);
    for (Cone& c : o.cones) {
        c.base = wave(c.base);
        c.apex = wave(c.apex);
    }
}

std::vector<glm::dmat4> placements(double time) {
    const glm::dmat4 identity(1.0);
    return {
        glm::translate(identity, {time, 0.0, 0.0}),
        glm::scale(glm::rotate(glm::translate(identity, {5.0, 1.0, -2.0}), 0.7 + time, DVec3(1.0, 2.0, 0.5)),
                   {1.5, 1.5, 1.5}),
        glm::rotate(glm::translate(identity, {-3.0, 4.0 + time, 1.0}), 2.0, DVec3(0.0, 0.0, 1.0)),
    };
}

std::vector<Ray> raysInto(const PrimitiveArrays& world, size_t n, uint32_t seed) {
    Bounds3 box;
    for (const Triangle& t : world.triangles) box.extend(t.bounds());
    for (const Sphere& s : world.spheres) box.extend(s.bounds());
    for (const Cone& c : world.cones) box.extend(c.bounds());
    const DVec3 centre(box.center());
    const double radius = glm::length(DVec3(box.diagonal()));
    std::mt19937 rng(seed);
    std::vector<Ray> rays;
    for (size_t i = 0; i < n; ++i) {
        const DVec3 from = centre + randomUnit(rng) * radius;
        const DVec3 to = centre + randomPointWithin(rng, radius * 0.4);
        rays.push_back({Vec3(from), Vec3(to - from), 0.0f, kInfinity});
    }
    return rays;
}

void expectAnswersAsBruteForce(const Accelerator& accel, const PrimitiveArrays& world, uint32_t seed) {
    const Env env(verify::verifyKeys());
    const std::unique_ptr<Accelerator> naive = createAccelerator("naive", env);
    naive->build(world.prims());
    const std::unique_ptr<Accelerator> alone = createAccelerator("naive", env);
    size_t hits = 0;
    for (const Ray& ray : raysInto(world, 2000, seed)) {
        QueryCounters counters;
        Hit expected, got;
        const bool expectedFound = naive->findNearest(ray, expected, counters);
        ASSERT_EQ(accel.findNearest(ray, got, counters), expectedFound);
        ASSERT_TRUE(hitsAgree(got, expected)) << got.t << " " << expected.t;
        if (expectedFound) {
            // The hit names a world primitive the ray meets there, at the same barycentrics: ties
            // aside (coincident primitives), the same as brute force's, whose t rounds otherwise.
            ASSERT_LT(got.primitive, world.valid.size());
            const uint32_t named[] = {got.primitive};
            PrimitiveSet one = world.prims();
            one.valid = named;
            alone->build(one);
            Hit there;
            ASSERT_TRUE(alone->findNearest(ray, there, counters)) << got.primitive;
            EXPECT_TRUE(hitsAgree(got, there)) << got.t << " " << there.t;
            EXPECT_NEAR(got.u, there.u, 1e-3f);
            EXPECT_NEAR(got.v, there.v, 1e-3f);
        }
        hits += expectedFound;
        EXPECT_EQ(accel.isOccluded(ray, counters), naive->isOccluded(ray, counters));
    }
    EXPECT_GT(hits, 200u);
}

std::unique_ptr<InstancedAccelerator> builtAtTimeZero(InstancedWorld& scene, const std::string& bottom,
                                                      const Env& env) {
    scene.place(placements(0.0));
    std::unique_ptr<InstancedAccelerator> twoLevel = createInstanced(scene.instances(placements(0.0)), bottom, env);
    twoLevel->build({});
    return twoLevel;
}

}  // namespace bvhlab::test
