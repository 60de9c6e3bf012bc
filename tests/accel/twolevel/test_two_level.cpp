// Two levels (accel/twolevel/two_level_accelerator.h): instances placed by rotations, scales and
// translations answer rays as brute force over the same triangles put into the world does,
// before and after they move; hits name the world's primitives; both levels' work is counted.
#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "framework/core/error.h"
#include "tests/support/bvh_checks.h"
#include "tests/support/random_geometry.h"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <random>

namespace bvhlab::test {
namespace {

// Three instances of two soups: one placed twice.
struct InstancedWorld {
    std::vector<Soup> objects = {randomSoup(300, 1, 4.0f, 0.8f), randomSoup(200, 2, 3.0f, 1.0f)};
    std::vector<int> objectOf = {0, 1, 0};
    Soup world;  // every instance's triangles, carried into the world in double

    std::vector<Instance> instances(const std::vector<glm::dmat4>& placed) const {
        std::vector<Instance> out;
        uint32_t base = 0;
        for (size_t i = 0; i < objectOf.size(); ++i) {
            const Soup& object = objects[objectOf[i]];
            out.push_back({object.prims(), placed[i], base, 0, 0});
            base += uint32_t(object.triangles.size());
        }
        return out;
    }
    void place(const std::vector<glm::dmat4>& placed) {
        world = {};
        for (size_t i = 0; i < objectOf.size(); ++i)
            for (const Triangle& t : objects[objectOf[i]].triangles) {
                auto carry = [&](const Vec3& v) { return Vec3(placed[i] * glm::dvec4(DVec3(v), 1.0)); };
                world.add({carry(t.v0), carry(t.v1), carry(t.v2)});
            }
    }
};

std::vector<glm::dmat4> placements(double time) {
    const glm::dmat4 identity(1.0);
    return {
        glm::translate(identity, {time, 0.0, 0.0}),
        glm::scale(glm::rotate(glm::translate(identity, {5.0, 1.0, -2.0}), 0.7 + time, DVec3(1.0, 2.0, 0.5)),
                   {1.5, 1.5, 1.5}),
        glm::rotate(glm::translate(identity, {-3.0, 4.0 + time, 1.0}), 2.0, DVec3(0.0, 0.0, 1.0)),
    };
}

// Rays from a sphere around the scene towards random points inside it.
std::vector<Ray> raysInto(const Soup& world, size_t n, uint32_t seed) {
    Bounds3 box;
    for (const Triangle& t : world.triangles) box.extend(t.bounds());
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

void expectAnswersAsBruteForce(const Accelerator& twoLevel, const Soup& world, uint32_t seed) {
    const std::unique_ptr<Accelerator> naive = createAccelerator("naive", Env(verify::verifyKeys()));
    naive->build(world.prims());
    size_t hits = 0;
    for (const Ray& ray : raysInto(world, 2000, seed)) {
        QueryCounters counters;
        Hit expected, got;
        const bool expectedFound = naive->findNearest(ray, expected, counters);
        ASSERT_EQ(twoLevel.findNearest(ray, got, counters), expectedFound);
        ASSERT_TRUE(hitsAgree(got, expected)) << got.t << " " << expected.t;
        if (expectedFound && got.t == expected.t) {
            EXPECT_EQ(got.primitive, expected.primitive);
        }
        hits += expectedFound;
        EXPECT_EQ(twoLevel.isOccluded(ray, counters), naive->isOccluded(ray, counters));
    }
    EXPECT_GT(hits, 200u);
}

// The scene placed at time 0 and its two levels, built, with `bottom` under the top level.
std::unique_ptr<InstancedAccelerator> builtAtTimeZero(InstancedWorld& scene, const std::string& bottom) {
    scene.place(placements(0.0));
    std::unique_ptr<InstancedAccelerator> twoLevel =
        createInstanced(scene.instances(placements(0.0)), bottom, Env(verify::verifyKeys()));
    twoLevel->build({});
    return twoLevel;
}

TEST(TwoLevel, AnswersAsBruteForceOverThePlacedTrianglesBeforeAndAfterAMove) {
    InstancedWorld scene;
    const std::unique_ptr<InstancedAccelerator> twoLevel = builtAtTimeZero(scene, "sahbvh8");
    expectAnswersAsBruteForce(*twoLevel, scene.world, 7);

    const std::vector<glm::dmat4> moved = placements(1.25);
    scene.place(moved);
    twoLevel->moveInstances(moved, {});
    expectAnswersAsBruteForce(*twoLevel, scene.world, 8);
}

TEST(TwoLevel, CountsBothLevelsAndOneQueryPerRay) {
    InstancedWorld scene;
    const std::unique_ptr<InstancedAccelerator> twoLevel = builtAtTimeZero(scene, "naive");
    QueryCounters counters;
    size_t found = 0;
    const std::vector<Ray> rays = raysInto(scene.world, 100, 3);
    for (const Ray& ray : rays) {
        Hit hit;
        found += twoLevel->findNearest(ray, hit, counters);
    }
    EXPECT_EQ(counters.queries, rays.size());
    EXPECT_GT(found, 0u);
    // Brute force tests every triangle of each instance it reaches: whole objects only.
    EXPECT_GT(counters.intersectionTests, 0u);
    EXPECT_GT(counters.traversalSteps, counters.queries);  // the top level's nodes and the bottoms' one each
}

TEST(TwoLevel, AnUnknownBottomStructureIsRefusedByName) {
    const Env env(verify::verifyKeys());
    EXPECT_THROW(createInstanced({}, "nosuch", env), InputError);
}

}  // namespace
}  // namespace bvhlab::test
