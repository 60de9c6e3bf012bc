// What an entry point adds, checked in itself (accel/plugins/plugin_additions.h): a key several
// accelerators read is declared once if alike and refused if declared two ways.
#include "accel/plugins/plugin_additions.h"
#include "framework/core/error.h"

#include <gtest/gtest.h>

namespace bvhlab::test {
namespace {

Accelerator* makeNothing(const PluginSettings&) { return nullptr; }

constexpr PluginKey kDepth{"Kd::depth", KeyType::Int, "24", "the deepest leaf", 1, 64};
constexpr PluginKey kDepthOtherDefault{"Kd::depth", KeyType::Int, "16", "the deepest leaf", 1, 64};
constexpr PluginKey kDepthOnly[] = {kDepth};
constexpr PluginKey kDepthOtherwise[] = {kDepthOtherDefault};

TEST(PluginAdditions, AKeySharedByTwoAcceleratorsIsDeclaredOnceIfAlike) {
    RecordingRegistrar registrar;
    registrar.addAccelerator({"kd", "a kd-tree", kDepthOnly, makeNothing});
    registrar.addAccelerator({"kd4", "a 4-wide kd-tree", kDepthOnly, makeNothing});
    EXPECT_NO_THROW(checkAdditions("kd.so", registrar.additions));
    ASSERT_EQ(registrar.additions.keys().size(), 1u);
    EXPECT_EQ(registrar.additions.keys()[0].name, "Kd::depth");
}

TEST(PluginAdditions, AKeyDeclaredTwoWaysIsRefused) {
    RecordingRegistrar registrar;
    registrar.addAccelerator({"kd", "a kd-tree", kDepthOnly, makeNothing});
    registrar.addAccelerator({"kd4", "a 4-wide kd-tree", kDepthOtherwise, makeNothing});
    try {
        checkAdditions("kd.so", registrar.additions);
        FAIL() << "a key declared two ways was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("env key 'Kd::depth' is declared twice, differently"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace bvhlab::test
