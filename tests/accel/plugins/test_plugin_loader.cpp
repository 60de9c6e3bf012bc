// Opening a plugin file (accel/plugins/plugin_loader.h): what its entry point adds comes back,
// checked, and nothing of it is registered; a plugin of another ABI is refused naming both.
#include "accel/plugins/plugin_loader.h"
#include "accel/registry.h"
#include "framework/core/error.h"
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>

namespace bvhlab::test {
namespace {

TEST(PluginLoader, ReturnsWhatThePluginAddsAndRegistersNothing) {
    const OpenedPlugin plugin = openPlugin(testPlugins() + "/throwing.so");
    EXPECT_EQ(plugin.abi, abiFingerprint(kAbi));
    EXPECT_EQ(plugin.acceleratorNames(),
              (std::vector<std::string>{"throwing", "throwing_query", "throwing_factory", "throwing_misread"}));
    ASSERT_EQ(plugin.keys().size(), 2u);
    EXPECT_EQ(plugin.keys()[0].name, "Throwing::unused");
    EXPECT_EQ(plugin.keys()[0].type, KeyType::Int);
    EXPECT_NE(plugin.library, nullptr);
    EXPECT_EQ(findAccelerator("throwing"), nullptr);
}

TEST(PluginLoader, ABuilderAddsItsThreeAccelerators) {
    const OpenedPlugin plugin = openPlugin(testPlugins() + "/builders.so");
    ASSERT_FALSE(plugin.builders.empty());
    EXPECT_EQ(plugin.builders[0].acceleratorNames(), (std::vector<std::string>{"pairs", "pairs4", "pairs8"}));
    EXPECT_TRUE(plugin.builders[0].builder.mergeTree);
    EXPECT_FALSE(plugin.builders[0].builder.splitRule);
}

TEST(PluginLoader, APluginOfAnotherAbiIsRefusedBeforeItsEntryPointRuns) {
    try {
        openPlugin(testPlugins() + "/changed_abi.so");
        ADD_FAILURE() << "changed_abi.so was opened";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("bvhlab ABI " + abiFingerprint(kAbi)), std::string::npos) << message;
        EXPECT_NE(message.find("sizeof(Ray): plugin 36, bvhlab 32"), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace bvhlab::test
