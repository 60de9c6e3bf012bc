// An animated scene as instances (framework/scene/scene_instances.h) under two levels: at every
// frame, with its rigid parts placed anew and its animated triangles deformed in place, the two
// levels answer as brute force over the world scene at that frame does, in the world's indices.
#include "accel/registry.h"
#include "accel/verify/oracle.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/verify_keys.h"
#include "framework/scene/scene_instances.h"
#include "tests/support/moving_scene.h"
#include "tests/support/scene_files.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

namespace bvhlab::test {
namespace {

void expectAnswersAsBruteForceAt(const std::string& bottom) {
    TempDir dir;
    AnimatedScene animated = loadAnimatedScene(dir.write("moving.aff", movingSceneText()));
    SceneInstances instances(animated);
    ASSERT_EQ(instances.instances().size(), 3u);  // static, the part, the animated triangles
    ASSERT_EQ(instances.deformed().size(), 1u);
    const Env env(verify::verifyKeys());
    std::unique_ptr<InstancedAccelerator> twoLevel = createInstanced(instances.instances(), bottom, env);
    twoLevel->build({});

    for (int frame = 0; frame < animated.frameCount; ++frame) {
        SCOPED_TRACE(fmt::format("{} at frame {}", bottom, frame));
        animated.setTime(animated.frameTime(frame));
        if (frame > 0) twoLevel->moveInstances(instances.transforms(), instances.deformed());
        std::unique_ptr<Accelerator> naive = createAccelerator("naive", env);
        naive->build(animated.scene.primitives());
        size_t hits = 0;
        for (const Ray& ray : verify::raysTowardTriangles(animated.scene, 400, uint64_t(frame) + 1)) {
            QueryCounters counters;
            Hit got, expected;
            const bool found = twoLevel->findNearest(ray, got, counters);
            ASSERT_EQ(found, naive->findNearest(ray, expected, counters)) << verify::describe(ray);
            if (found) {
                EXPECT_TRUE(verify::agree(got, expected)) << verify::describe(got) << verify::describe(expected);
            }
            EXPECT_EQ(twoLevel->isOccluded(ray, counters), found);
            hits += found;
        }
        EXPECT_GT(hits, 300u);
    }
}

TEST(SceneInstances, TwoLevelsAnswerAsBruteForceAtEveryFrame) { expectAnswersAsBruteForceAt("sahbvh8"); }

TEST(SceneInstances, AnyStructureServesAsTheBottomLevel) { expectAnswersAsBruteForceAt("sahbvh"); }

TEST(SceneInstances, EmbreesInstancesAnswerAsBruteForceAtEveryFrame) { expectAnswersAsBruteForceAt("embree"); }

}  // namespace
}  // namespace bvhlab::test
