// The builder table as the registry shows it: each BVH accelerator registered with its env keys.
#include "accel/bvh/bvh_accelerator.h"
#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "tests/support/bvh_checks.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace bvhlab {
namespace {

TEST(Bvh, RegisteredWithTheirEnvKeys) {
    const EnvRegistry& registry = verify::verifyKeys();
    for (const char* name : {"tdbvh", "sahbvh", "sahbvh4", "sahbvh8", "sweepbvh", "ploc", "ploc8"}) {
        const auto& infos = acceleratorInfos();
        const auto it =
            std::find_if(infos.begin(), infos.end(), [&](const AcceleratorInfo& i) { return i.name == name; });
        ASSERT_NE(it, infos.end()) << name;
        for (const std::string& key : it->envKeys) EXPECT_NE(registry.find(key), nullptr) << key;
    }
    Env env(verify::verifyKeys());
    env.set(keys::BVH::bins, "8", "test");
    env.set(keys::BVH::maxLeaf, "3", "test");
    env.set(keys::BVH::tdbvhSplit, "nodebox", "test");
    env.set(keys::BVH::optimize, "insertion", "test");
    env.set(keys::BVH::optimizeIterations, "5", "test");
    const BvhBuildConfig config = bvhSettingsFromEnv(env).build;
    EXPECT_EQ(config.optimize, BvhOptimize::Insertion);
    EXPECT_EQ(config.insertion.iterations, 5);
    EXPECT_EQ(config.binnedSah.bins, 8);
    EXPECT_EQ(config.shared.maxLeaf, 3);
    EXPECT_EQ(config.spatialMedian.splitBox, MedianSplitBox::NodeBox);
    const auto accel = createAccelerator("sahbvh", env);
    EXPECT_STREQ(accel->name(), "sahbvh");
    EXPECT_TRUE(accel->hasCounters());
}

}  // namespace
}  // namespace bvhlab
