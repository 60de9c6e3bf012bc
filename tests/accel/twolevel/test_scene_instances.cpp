// An animated scene as instances (framework/scene/scene_instances.h) under two levels: at every
// frame, with its rigid parts placed anew and its animated triangles deformed in place, the two
// levels answer as brute force over the world scene at that frame does, in the world's indices.
#include "accel/registry.h"
#include "accel/verify/oracle.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/verify_keys.h"
#include "framework/scene/scene_instances.h"
#include "tests/support/scene_files.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <random>
#include <string>

namespace bvhlab::test {
namespace {

// `n` random small triangles around `centre`, as AFF polygons.
std::string randomPolygons(int n, float cx, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> at(-2.0f, 2.0f), jitter(-0.5f, 0.5f);
    std::string out;
    for (int i = 0; i < n; ++i) {
        const float x = cx + at(rng), y = at(rng), z = at(rng);
        out += fmt::format("p 3\n{} {} {}\n{} {} {}\n{} {} {}\n", x, y, z, x + jitter(rng), y + jitter(rng), z, x,
                           y + jitter(rng), z + jitter(rng));
    }
    return out;
}

// A static block, a spinning and travelling part (nested under a static transform, with a
// sphere), and animated triangles that fly apart, over 5 frames.
std::string sceneText() {
    std::string text = "v\nfrom 0 0 30\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 32 32\n";
    text += "f 1 1 1 1 0 0 0 1\n" + randomPolygons(150, -6.0f, 1);
    text += "x spin\n{\nxs 1 1 1  0 0 1 0  3 0 0\n{\n" + randomPolygons(120, 0.0f, 2) + "s 1 1 1 0.7\n}\n}\n";
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> at(-2.0f, 2.0f);
    for (int i = 0; i < 40; ++i) {
        text += "tpa 2\n";
        for (float key : {0.0f, 4.0f}) {
            const float spread = key == 0.0f ? 1.0f : 3.0f, x = 6.0f + at(rng) * spread, y = at(rng) * spread;
            text += fmt::format(" {}\n {} {} 0 0 0 1\n {} {} 0 0 0 1\n {} {} 1 0 0 1\n", key, x, y, x + 0.6f, y, x,
                                y + 0.6f);
        }
    }
    text += "a 0 4 5\nk spin\n{\n transl 4\n -1 0 0 0 0 0 0\n 0 0 0 0 0 0 0\n 4 0 3 1 0 0 0\n 5 0 3 1 0 0 0\n";
    text += " rot 4\n -1 0 0 1 0 0 0 0\n 0 0 0 1 0 0 0 0\n 4 0 0 1 170 0 0 0\n 5 0 0 1 170 0 0 0\n}\n";
    return text;
}

void expectAnswersAsBruteForceAt(const std::string& bottom) {
    TempDir dir;
    AnimatedScene animated = loadAnimatedScene(dir.write("moving.aff", sceneText()));
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
