// docs/env-keys.md lists exactly the registered keys and accelerators (regenerate it with
// `bvhlab keys > docs/env-keys.md`), and env/global.env uses only known keys.
#include "accel/registry.h"

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
    Env env;
    EXPECT_NO_THROW(env.loadFile(std::string(BVHLAB_SOURCE_DIR) + "/env/global.env"));
}
