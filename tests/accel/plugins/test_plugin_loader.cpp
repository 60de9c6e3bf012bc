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
    EXPECT_EQ(plugin.abi, abiFingerprint(abiFigures()));
    EXPECT_EQ(plugin.additions.acceleratorNames(),
              (std::vector<std::string>{"throwing", "throwing_query", "throwing_factory", "throwing_misread"}));
    ASSERT_EQ(plugin.additions.keys().size(), 2u);
    EXPECT_EQ(plugin.additions.keys()[0].name, "Throwing::unused");
    EXPECT_EQ(plugin.additions.keys()[0].type, KeyType::Int);
    EXPECT_NE(plugin.library, nullptr);
    EXPECT_EQ(findAccelerator("throwing"), nullptr);
}

TEST(PluginLoader, ABuilderAddsItsThreeAccelerators) {
    const OpenedPlugin plugin = openPlugin(testPlugins() + "/builders.so");
    ASSERT_FALSE(plugin.additions.builders.empty());
    EXPECT_EQ(plugin.additions.builders[0].acceleratorNames(), (std::vector<std::string>{"pairs", "pairs4", "pairs8"}));
    EXPECT_TRUE(plugin.additions.builders[0].builder.mergeTree);
    EXPECT_FALSE(plugin.additions.builders[0].builder.splitRule);
}

TEST(PluginLoader, APluginOfAnotherAbiIsRefusedBeforeItsEntryPointRuns) {
    try {
        openPlugin(testPlugins() + "/changed_abi.so");
        ADD_FAILURE() << "changed_abi.so was opened";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("bvhlab ABI " + abiFingerprint(abiFigures())), std::string::npos) << message;
        EXPECT_NE(message.find("sizeof(Ray) is 36 in the plugin, 32 in bvhlab"), std::string::npos) << message;
    }
}

// bvhlab's own figures with one changed, as a plugin of that toolchain or those headers has them.
std::vector<AbiFigure> figuresWith(std::string_view what, uint64_t value) {
    std::vector<AbiFigure> figures(abiFigures().begin(), abiFigures().end());
    for (AbiFigure& f : figures)
        if (f.what == what) f.value = value;
    return figures;
}

TEST(PluginLoader, APluginWithoutUpdateIsAskedToBeRebuilt) {
    // Headers older than Accelerator::update: its figures absent, the later slots one lower.
    std::vector<AbiFigure> older;
    const uint64_t updateSlot = abi::vtableSlot(&Accelerator::update);
    for (AbiFigure f : abiFigures()) {
        const std::string_view what = f.what;
        if (what.ends_with("Accelerator::update")) continue;
        if (what.starts_with("vtable slot of Accelerator::") && f.value > updateSlot) --f.value;
        older.push_back(f);
    }
    const std::string message = abiMismatch(older);
    EXPECT_NE(message.find("vtable slot of Accelerator::update is absent in the plugin"), std::string::npos) << message;
    EXPECT_NE(message.find("rebuild it against this bvhlab's include/bvhlab"), std::string::npos) << message;
}

TEST(PluginLoader, ItsOwnFiguresMatch) { EXPECT_EQ(abiMismatch(abiFigures()), ""); }

TEST(PluginLoader, APluginOfLibcxxIsAskedForLibstdcxx) {
    const std::string message = abiMismatch(figuresWith("standard library", abi::kLibcxx));
    EXPECT_NE(message.find("it was built with libc++; bvhlab uses libstdc++: build it with libstdc++ (without "
                           "-stdlib=libc++)"),
              std::string::npos)
        << message;
    EXPECT_EQ(message.find("headers"), std::string::npos) << message;
}

TEST(PluginLoader, APluginOfTheOtherStringAbiIsAskedForBvhlabs) {
    const std::string message = abiMismatch(figuresWith("standard library ABI", 0));
    EXPECT_NE(message.find("it was built with _GLIBCXX_USE_CXX11_ABI=0, bvhlab with 1: build it with "
                           "-D_GLIBCXX_USE_CXX11_ABI=1"),
              std::string::npos)
        << message;
}

// Figures as headers of an older bvhlab computed them: the compiler's own ABI number instead of
// the toolchain's figures. Those headers are the cause, not the compiler.
TEST(PluginLoader, APluginOfOlderHeadersIsAskedForARebuildNotForAnotherCompiler) {
    std::vector<AbiFigure> figures = {{"__GXX_ABI_VERSION", 1017}};
    for (const AbiFigure& f : abiFigures())
        if (std::string_view(f.what) != "Itanium C++ ABI") figures.push_back(f);
    const std::string message = abiMismatch(figures);
    EXPECT_NE(message.find("it was built against other headers (Itanium C++ ABI is absent in the plugin; "
                           "__GXX_ABI_VERSION is absent in bvhlab): rebuild it"),
              std::string::npos)
        << message;
    EXPECT_EQ(message.find("not compiled for"), std::string::npos) << message;
}

TEST(PluginLoader, AnotherVirtualTableNamesTheFunction) {
    const std::string message = abiMismatch(figuresWith("vtable slot of Accelerator::build", 9));
    EXPECT_NE(message.find("(vtable slot of Accelerator::build is 9 in the plugin, 3 in bvhlab)"), std::string::npos)
        << message;
    const std::string typeMessage = abiMismatch(figuresWith("type of Accelerator::build", 1));
    EXPECT_NE(typeMessage.find("(the type of Accelerator::build differs)"), std::string::npos) << typeMessage;
}

}  // namespace
}  // namespace bvhlab::test
