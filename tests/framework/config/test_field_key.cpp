// Keys declared by the fields they fill: the type and default come from the field, a list of
// them binds a Config inside larger settings, and reading an env (as a structure reads its keys)
// sets the fields.
#include "framework/config/key_bindings.h"
#include "framework/config/plugin_settings.h"

#include <gtest/gtest.h>

using namespace bvhlab;

namespace {

enum class PartShape { Round, Square };
constexpr std::string_view kPartShapeWords[] = {"round", "square"};

struct PartConfig {
    int count = 7;
    uint32_t limit = 1'000'000;
    float scale = 1e-5f;
    bool flag = true;
    PartShape shape = PartShape::Square;
};

constexpr FieldKey<&PartConfig::count> kPartCount{"Part::count", 1, 10, "a count"};
constexpr FieldKey<&PartConfig::limit> kPartLimit{"Part::limit", 0, 2147483647, "a limit"};
constexpr FieldKey<&PartConfig::scale> kPartScale{"Part::scale", 0, 1, "a scale"};
constexpr FieldKey<&PartConfig::flag> kPartFlag{"Part::flag", "a switch"};
constexpr FieldKey<&PartConfig::shape> kPartShape{"Part::shape", kPartShapeWords, "a shape"};
constexpr std::tuple kPartKeys{&kPartCount, &kPartLimit, &kPartScale, &kPartFlag, &kPartShape};

struct PartSettings {
    PartConfig part;
};

}  // namespace

TEST(FieldKey, TypeAndDefaultAreTheFields) {
    const EnvKey count = kPartCount.declaration(), limit = kPartLimit.declaration(), scale = kPartScale.declaration(),
                 flag = kPartFlag.declaration(), shape = kPartShape.declaration();
    EXPECT_EQ(count.type, KeyType::Int);
    EXPECT_EQ(count.defaultValue, "7");
    EXPECT_EQ(count.max, 10.0);
    EXPECT_EQ(limit.type, KeyType::Int);
    EXPECT_EQ(limit.defaultValue, "1000000");
    EXPECT_EQ(scale.type, KeyType::Float);
    EXPECT_EQ(scale.defaultValue, "1e-5");
    EXPECT_EQ(flag.type, KeyType::Bool);
    EXPECT_EQ(flag.defaultValue, "true");
    EXPECT_EQ(shape.type, KeyType::Choice);
    EXPECT_EQ(shape.defaultValue, "square");
    EXPECT_EQ(shape.choices, (std::vector<std::string>{"round", "square"}));
}

TEST(FieldKey, ShortestTextReadsBack) {
    EXPECT_EQ(shortestText(1.0f), "1");
    EXPECT_EQ(shortestText(0.3f), "0.3");
    EXPECT_EQ(shortestText(1e-5f), "1e-5");
    EXPECT_EQ(shortestText(1e20f), "1e+20");
}

TEST(FieldKey, BindingsReadAnEnvIntoThePart) {
    const KeyBindings<PartSettings> bindings(kPartKeys, [](PartSettings& s) -> PartConfig& { return s.part; });
    EnvRegistry registry;
    std::vector<EnvKey> declared;
    bindings.appendDeclarations(declared);
    std::vector<std::string> names;
    for (const EnvKey& key : declared) {
        registry.add(key);
        names.push_back(key.name);
    }
    EXPECT_EQ(names,
              (std::vector<std::string>{"Part::count", "Part::limit", "Part::scale", "Part::flag", "Part::shape"}));

    Env env(registry);
    const EnvPluginSettings keys(env, names, "the part");
    PartSettings defaults;
    bindings.read(keys, defaults);
    EXPECT_EQ(defaults.part.count, PartConfig{}.count);
    EXPECT_EQ(defaults.part.scale, PartConfig{}.scale);
    EXPECT_EQ(defaults.part.shape, PartShape::Square);

    env.set(kPartCount, "3", "test");
    env.set(kPartLimit, "5", "test");
    env.set(kPartScale, "0.25", "test");
    env.set(kPartFlag, "false", "test");
    env.set(kPartShape, "round", "test");
    PartSettings read;
    bindings.read(keys, read);
    EXPECT_EQ(read.part.count, 3);
    EXPECT_EQ(read.part.limit, 5u);
    EXPECT_EQ(read.part.scale, 0.25f);
    EXPECT_FALSE(read.part.flag);
    EXPECT_EQ(read.part.shape, PartShape::Round);
}
