// The policies that keep a structure at an animation's time (apps/animate/update_policy.h): at
// every frame each answers as brute force over the scene at that frame; refit refits, rebuild
// rebuilds, adaptive rebuilds when its SAH grew past the factor or its K frames are up, two
// levels move; a structure without an update cannot refit and says so.
#include "accel/registry.h"
#include "accel/verify/oracle.h"
#include "accel/verify/ray_generators.h"
#include "apps/animate/update_policy.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/program_keys.h"
#include "tests/support/moving_scene.h"
#include "tests/support/scene_files.h"

#include <gtest/gtest.h>

namespace bvhlab::test {
namespace {

struct MovingScene {
    TempDir dir;
    AnimatedScene animated = loadAnimatedScene(dir.write("moving.aff", movingSceneText()));
};

Env policyEnv(const std::string& policy, const std::vector<std::string>& overrides = {}) {
    Env env(programKeys());
    env.set("Animate::policy", policy, "test");
    for (const std::string& assignment : overrides) env.setOverride(assignment, "test");
    return env;
}

// Every frame's actions; each frame's answers checked against brute force.
std::vector<std::string> runFrames(MovingScene& scene, const std::string& accel, const Env& env) {
    AnimatedScene& animated = scene.animated;
    animated.setTime(animated.frameTime(0));
    AnimatedStructure structure(animated, accel, env);
    std::vector<std::string> actions;
    for (int frame = 0; frame < animated.frameCount; ++frame) {
        SCOPED_TRACE(fmt::format("{} {} at frame {}", accel, env.get(keys::Animate::policy), frame));
        const bool validChanged = frame > 0 && animated.setTime(animated.frameTime(frame));
        const FrameUpdate update = frame == 0 ? structure.start() : structure.advance(validChanged);
        actions.push_back(toString(update.action));
        EXPECT_GE(update.stats.buildMs, 0.0);
        std::unique_ptr<Accelerator> naive = createAccelerator("naive", Env(programKeys()));
        naive->build(animated.scene.primitives());
        size_t hits = 0;
        for (const Ray& ray : verify::raysTowardTriangles(animated.scene, 300, uint64_t(frame) + 7)) {
            QueryCounters counters;
            Hit got, expected;
            const bool found = structure.accelerator().findNearest(ray, got, counters);
            EXPECT_EQ(found, naive->findNearest(ray, expected, counters)) << verify::describe(ray);
            if (found) {
                EXPECT_TRUE(verify::agree(got, expected)) << verify::describe(got) << verify::describe(expected);
            }
            hits += found;
        }
        EXPECT_GT(hits, 200u);
    }
    return actions;
}

using Actions = std::vector<std::string>;

TEST(UpdatePolicy, RebuildRebuildsEveryFrame) {
    MovingScene scene;
    EXPECT_EQ(runFrames(scene, "sahbvh8", policyEnv("rebuild")),
              (Actions{"build", "rebuild", "rebuild", "rebuild", "rebuild"}));
}

TEST(UpdatePolicy, RefitRefitsOursAndEmbrees) {
    for (const auto& [accel, overrides] : {std::pair<std::string, std::vector<std::string>>{"sahbvh", {}},
                                           {"sahbvh8", {}},
                                           {"sahbvh", {"BVH::update=insertion"}},
                                           {"embree", {"Embree::quality=refit"}}}) {
        MovingScene scene;
        EXPECT_EQ(runFrames(scene, accel, policyEnv("refit", overrides)),
                  (Actions{"build", "refit", "refit", "refit", "refit"}))
            << accel;
    }
}

TEST(UpdatePolicy, AdaptiveRebuildsWhenItsSahGrewOrItsFramesAreUp) {
    MovingScene scene;
    // The animated triangles fly apart: the refitted tree's SAH grows past any factor near 1.
    const Actions bySah = runFrames(scene, "sahbvh", policyEnv("adaptive", {"Animate::sahGrowth=1.0001"}));
    EXPECT_EQ(bySah[1], "refit");
    EXPECT_NE(std::find(bySah.begin() + 2, bySah.end(), "rebuild"), bySah.end());
    EXPECT_EQ(runFrames(scene, "sahbvh", policyEnv("adaptive", {"Animate::sahGrowth=1e6", "Animate::rebuildEvery=2"})),
              (Actions{"build", "refit", "rebuild", "refit", "rebuild"}));
    EXPECT_EQ(runFrames(scene, "sahbvh", policyEnv("adaptive", {"Animate::sahGrowth=1e6"})),
              (Actions{"build", "refit", "refit", "refit", "refit"}));
}

TEST(UpdatePolicy, TwoLevelsMoveTheirInstances) {
    for (const std::string accel : {"sahbvh8", "embree"}) {
        MovingScene scene;
        EXPECT_EQ(runFrames(scene, accel, policyEnv("twolevel")), (Actions{"build", "move", "move", "move", "move"}))
            << accel;
    }
}

TEST(UpdatePolicy, AStructureWithoutAnUpdateCannotRefit) {
    MovingScene scene;
    AnimatedStructure structure(scene.animated, "embree", policyEnv("refit", {"Embree::quality=low"}));
    EXPECT_THROW(structure.start(), NoUpdateError);
    EXPECT_THROW(parseUpdatePolicy("sometimes"), InputError);
}

}  // namespace
}  // namespace bvhlab::test
