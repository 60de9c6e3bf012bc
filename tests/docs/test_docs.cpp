// docs/env-keys.md lists exactly the registered keys and accelerators (regenerate it with
// `bvhlab keys > docs/env-keys.md`), and env/global.env uses only known keys.
#include "accel/bvh/bvh_env.h"
#include "accel/registry.h"
#include "apps/common/program_keys.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace bvhlab;

TEST(Docs, EnvKeyListMatchesRegistry) {
    std::ifstream in(std::string(BVHLAB_SOURCE_DIR) + "/docs/env-keys.md");
    ASSERT_TRUE(in) << "docs/env-keys.md is missing";
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), envKeysMarkdown()) << "run: build/bvhlab keys > docs/env-keys.md";
}

TEST(Docs, GlobalEnvLoads) {
    Env env(programKeys());
    EXPECT_NO_THROW(env.loadFile(std::string(BVHLAB_SOURCE_DIR) + "/env/global.env"));
}

// Each key's declared default is a value it accepts (a default out of its own range would be
// used silently, since defaults are not parsed from a file).
TEST(Docs, EveryDeclaredDefaultIsValid) {
    for (const auto& [name, key] : programKeys().keys()) {
        Env env(programKeys());
        EXPECT_NO_THROW(env.set(name, key.defaultValue, "default")) << name << " = '" << key.defaultValue << "'";
    }
}

// BvhBuildConfig's member defaults (used by code that builds without an env) are the keys'.
TEST(Docs, BvhConfigDefaultsAreTheKeysDefaults) {
    const BvhBuildConfig fromKeys = bvhConfigFromEnv(Env(programKeys()));
    const BvhBuildConfig members;
    EXPECT_EQ(fromKeys.maxLeaf, members.maxLeaf);
    EXPECT_EQ(fromKeys.leafCap, members.leafCap);
    EXPECT_EQ(fromKeys.bins, members.bins);
    EXPECT_EQ(fromKeys.allAxes, members.allAxes);
    EXPECT_EQ(fromKeys.sahTermination, members.sahTermination);
    EXPECT_EQ(fromKeys.cTraversal, members.cTraversal);
    EXPECT_EQ(fromKeys.cIntersect, members.cIntersect);
    EXPECT_EQ(fromKeys.simd, members.simd);
    EXPECT_EQ(fromKeys.medianSplitBox, members.medianSplitBox);
    EXPECT_EQ(fromKeys.sbvhAlpha, members.sbvhAlpha);
    EXPECT_EQ(fromKeys.sbvhGrowth, members.sbvhGrowth);
}
