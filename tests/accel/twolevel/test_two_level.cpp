// Two levels (accel/twolevel/two_level_accelerator.h): instances placed by rotations, scales and
// translations answer rays as brute force over the same primitives put into the world does,
// before and after they move, and after an instance deformed in place; hits name the world's
// primitives; both levels' work is counted; a move of other instances is refused.
#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "framework/core/error.h"
#include "tests/support/instanced_world.h"

#include <gtest/gtest.h>

namespace bvhlab::test {
namespace {

TEST(TwoLevel, AnswersAsBruteForceOverThePlacedPrimitivesBeforeAndAfterAMove) {
    InstancedWorld scene;
    const std::unique_ptr<InstancedAccelerator> twoLevel = builtAtTimeZero(scene, "sahbvh8", Env(verify::verifyKeys()));
    expectAnswersAsBruteForce(*twoLevel, scene.world, 7);

    const std::vector<glm::dmat4> moved = placements(1.25);
    scene.place(moved);
    twoLevel->moveInstances(moved, {});
    expectAnswersAsBruteForce(*twoLevel, scene.world, 8);
}

TEST(TwoLevel, AnswersAsBruteForceAfterAnInstanceDeformedInPlace) {
    InstancedWorld scene;
    const std::unique_ptr<InstancedAccelerator> twoLevel = builtAtTimeZero(scene, "sahbvh8", Env(verify::verifyKeys()));
    // Object 1 is instance 1 alone; its bottom level is updated, the others are only placed.
    scene.deform(1, 0.5);
    const std::vector<glm::dmat4> moved = placements(0.5);
    scene.place(moved);
    const uint32_t deformed[] = {1};
    twoLevel->moveInstances(moved, deformed);
    expectAnswersAsBruteForce(*twoLevel, scene.world, 9);
}

TEST(TwoLevel, CountsBothLevelsAndOneQueryPerRay) {
    InstancedWorld scene;
    const std::unique_ptr<InstancedAccelerator> twoLevel = builtAtTimeZero(scene, "naive", Env(verify::verifyKeys()));
    QueryCounters counters;
    size_t found = 0;
    const std::vector<Ray> rays = raysInto(scene.world, 100, 3);
    for (const Ray& ray : rays) {
        Hit hit;
        found += twoLevel->findNearest(ray, hit, counters);
    }
    EXPECT_EQ(counters.queries, rays.size());
    EXPECT_GT(found, 0u);
    // Brute force tests every primitive of each instance it reaches: whole objects only.
    EXPECT_GT(counters.intersectionTests, 0u);
    EXPECT_GT(counters.traversalSteps, counters.queries);  // the top level's nodes and the bottoms' one each
}

// Transforms of another count, or a deformed instance that is not there, are refused before
// anything moves: the structure answers as before.
TEST(TwoLevel, AMoveOfOtherInstancesIsRefusedAndChangesNothing) {
    InstancedWorld scene;
    const std::unique_ptr<InstancedAccelerator> twoLevel = builtAtTimeZero(scene, "sahbvh", Env(verify::verifyKeys()));
    std::vector<glm::dmat4> moved = placements(1.0);
    const std::vector<glm::dmat4> fewer(moved.begin(), moved.end() - 1);
    EXPECT_THROW(twoLevel->moveInstances(fewer, {}), std::invalid_argument);
    const uint32_t missing[] = {uint32_t(moved.size())};
    EXPECT_THROW(twoLevel->moveInstances(moved, missing), std::invalid_argument);
    expectAnswersAsBruteForce(*twoLevel, scene.world, 12);
}

TEST(TwoLevel, AnUnknownBottomStructureIsRefusedByName) {
    const Env env(verify::verifyKeys());
    EXPECT_THROW(createInstanced({}, "nosuch", env), InputError);
}

}  // namespace
}  // namespace bvhlab::test
