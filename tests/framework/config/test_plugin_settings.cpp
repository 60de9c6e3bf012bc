// A plugin's keys on bvhlab's side (framework/config/plugin_settings.h): declarations checked as
// they are registered, values read by name and type, and a key the plugin did not declare or
// reads with another type refused naming it.
#include "framework/config/common_keys.h"
#include "framework/config/plugin_settings.h"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace bvhlab;

namespace {

constexpr const char* kShapes[] = {"box", "ball"};
constexpr PluginKey kDepth{"Kd::depth", KeyType::Int, "24", "the deepest leaf", 1, 64};
constexpr PluginKey kCost{"Kd::cost", KeyType::Float, "1.5", "a leaf's cost", 0, 10};
constexpr PluginKey kShape{"Kd::shape", KeyType::Choice, "box", "the shape of a cell", 0, 0, kShapes};
constexpr PluginKey kOrigin{"Kd::origin", KeyType::Vec3, "", "where the tree starts"};
constexpr PluginKey kSeeds{"Kd::seeds", KeyType::Vec3List, "0 0 0, 1 2 3", "seed points"};
constexpr PluginKey kOther{"Other::flag", KeyType::Bool, "true", "another plugin's key"};

// A message of `call`'s std::invalid_argument, or "" when it threw none.
template <typename Call>
std::string refusal(Call&& call) {
    try {
        call();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

EnvRegistry registryOf(std::initializer_list<PluginKey> keys) {
    EnvRegistry registry;
    for (const PluginKey& key : keys) registry.add(declarationOf(key));
    return registry;
}

TEST(PluginSettings, DeclarationsBecomeTheRegistrysKeys) {
    const EnvKey shape = declarationOf(kShape);
    EXPECT_EQ(shape.name, "Kd::shape");
    EXPECT_EQ(shape.type, KeyType::Choice);
    EXPECT_EQ(shape.defaultValue, "box");
    EXPECT_EQ(shape.choices, (std::vector<std::string>{"box", "ball"}));
    const EnvKey depth = declarationOf(kDepth);
    EXPECT_EQ(depth.min, 1);
    EXPECT_EQ(depth.max, 64);
}

TEST(PluginSettings, AMalformedDeclarationIsRefusedNamingTheKey) {
    EXPECT_EQ(refusal([] {
                  declarationOf({"depth", KeyType::Int, "1", "no section", 0, 9});
              }),
              "env key 'depth' is not 'Section::key'");
    EXPECT_EQ(refusal([] {
                  declarationOf({nullptr, KeyType::Int, "1", "no name"});
              }),
              "env key '' is not 'Section::key'");
    EXPECT_EQ(refusal([] { declarationOf({"Kd::x", KeyType(99), "1", "?"}); }), "env key 'Kd::x': unknown type 99");
    EXPECT_EQ(refusal([] {
                  declarationOf({"Kd::x", KeyType::Int, nullptr, "?"});
              }),
              "env key 'Kd::x': no default value (\"\" for none)");
    EXPECT_EQ(refusal([] {
                  declarationOf({"Kd::x", KeyType::Float, "1", "?", 2, 1});
              }),
              "env key 'Kd::x': its range 2 to 1 is not in order");
    EXPECT_EQ(refusal([] {
                  declarationOf({"Kd::x", KeyType::Choice, "a", "?"});
              }),
              "env key 'Kd::x': a Choice key without choices");
}

TEST(PluginSettings, ReadsTheDeclaredKeysByNameAndType) {
    const EnvRegistry registry = registryOf({kDepth, kCost, kShape, kOrigin, kSeeds});
    Env env(registry);
    env.setOverride("Kd::depth=30");
    const EnvPluginSettings settings(env, {"Kd::depth", "Kd::cost", "Kd::shape", "Kd::origin", "Kd::seeds"},
                                     "accelerator 'kd'");
    EXPECT_EQ(settings.getInt("Kd::depth"), 30);
    EXPECT_TRUE(settings.isExplicit("Kd::depth"));
    EXPECT_FLOAT_EQ(settings.getFloat("Kd::cost"), 1.5f);
    EXPECT_FALSE(settings.isExplicit("Kd::cost"));
    EXPECT_STREQ(settings.getText("Kd::shape"), "box");
    Vec3 origin(7.0f);
    EXPECT_FALSE(settings.getVec3("Kd::origin", origin));
    EXPECT_EQ(origin, Vec3(7.0f));
    const View<const Vec3> seeds = settings.getVec3List("Kd::seeds");
    ASSERT_EQ(seeds.size(), 2u);
    EXPECT_EQ(seeds[1], Vec3(1, 2, 3));
}

TEST(PluginSettings, AKeyNotDeclaredOrReadWithAnotherTypeIsRefusedNamingIt) {
    const EnvRegistry registry = registryOf({kDepth, kOther});
    const Env env(registry);
    const EnvPluginSettings settings(env, {"Kd::depth"}, "accelerator 'kd'");
    EXPECT_EQ(refusal([&] { settings.getFloat("Kd::depth"); }),
              "accelerator 'kd' read the Int key 'Kd::depth' with getFloat: read it with getInt");
    EXPECT_EQ(refusal([&] { settings.getText("Kd::depth"); }),
              "accelerator 'kd' read the Int key 'Kd::depth' with getText: read it with getInt");
    // Another plugin's key, though registered, is not this one's.
    EXPECT_EQ(refusal([&] { settings.getBool("Other::flag"); }),
              "accelerator 'kd' read the key 'Other::flag', which it did not declare (its keys: Kd::depth)");
    EXPECT_EQ(refusal([&] { settings.getBool(nullptr); }),
              "accelerator 'kd' read the key '', which it did not declare (its keys: Kd::depth)");
}

TEST(PluginSettings, EveryStructureMayReadTheRunsThreadCount) {
    EnvRegistry registry = registryOf({kDepth});
    registerCommonKeys(registry);
    Env env(registry);
    env.setOverride(std::string(kThreadsKey) + "=3");
    const EnvPluginSettings settings(env, {"Kd::depth"}, "accelerator 'kd'");
    EXPECT_EQ(settings.getInt(kThreadsKey), 3);
}

TEST(PluginKeyList, GivesBackTheDeclarationsItIsMadeOf) {
    const std::vector<EnvKey> keys = {declarationOf(kDepth), declarationOf(kShape)};
    const PluginKeyList list(keys);
    ASSERT_EQ(list.view().size(), 2u);
    for (size_t i = 0; i < keys.size(); ++i) {
        const EnvKey back = declarationOf(list.view()[i]);
        EXPECT_EQ(back.name, keys[i].name);
        EXPECT_EQ(back.type, keys[i].type);
        EXPECT_EQ(back.defaultValue, keys[i].defaultValue);
        EXPECT_EQ(back.description, keys[i].description);
        EXPECT_EQ(back.min, keys[i].min);
        EXPECT_EQ(back.max, keys[i].max);
        EXPECT_EQ(back.choices, keys[i].choices);
    }
}

}  // namespace
