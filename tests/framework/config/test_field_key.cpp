// Keys declared by the fields they fill: the type and default come from the field, a list of
// them binds a Config inside larger settings, and reading an env sets the fields.
#include "framework/config/key_bindings.h"

#include <gtest/gtest.h>

using namespace bvhlab;

namespace {

enum class Shape { Round, Square };
constexpr std::string_view kShapeWords[] = {"round", "square"};

struct PartConfig {
    int count = 7;
    uint32_t limit = 1'000'000;
    float scale = 1e-5f;
    bool flag = true;
    Shape shape = Shape::Square;
};

constexpr FieldKey<&PartConfig::count> kCount{"Part::count", 1, 10, "a count"};
constexpr FieldKey<&PartConfig::limit> kLimit{"Part::limit", 0, 2147483647, "a limit"};
constexpr FieldKey<&PartConfig::scale> kScale{"Part::scale", 0, 1, "a scale"};
constexpr FieldKey<&PartConfig::flag> kFlag{"Part::flag", "a switch"};
constexpr FieldKey<&PartConfig::shape> kShape{"Part::shape", kShapeWords, "a shape"};
constexpr std::tuple kPartKeys{&kCount, &kLimit, &kScale, &kFlag, &kShape};

struct Settings {
    PartConfig part;
};

}  // namespace

TEST(FieldKey, TypeAndDefaultAreTheFields) {
    const EnvKey count = kCount.declaration(), limit = kLimit.declaration(), scale = kScale.declaration(),
                 flag = kFlag.declaration(), shape = kShape.declaration();
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
    const KeyBindings<Settings> bindings(kPartKeys, [](Settings& s) -> PartConfig& { return s.part; });
    EnvRegistry registry;
    bindings.registerWith(registry);
    std::vector<std::string> names;
    bindings.appendNames(names);
    EXPECT_EQ(names, (std::vector<std::string>{"Part::count", "Part::limit", "Part::scale", "Part::flag", "Part::shape"}));

    Env env(registry);
    Settings defaults;
    bindings.read(env, defaults);
    EXPECT_EQ(defaults.part.count, PartConfig{}.count);
    EXPECT_EQ(defaults.part.scale, PartConfig{}.scale);
    EXPECT_EQ(defaults.part.shape, Shape::Square);

    env.set(kCount, "3", "test");
    env.set(kLimit, "5", "test");
    env.set(kScale, "0.25", "test");
    env.set(kFlag, "false", "test");
    env.set(kShape, "round", "test");
    Settings read;
    bindings.read(env, read);
    EXPECT_EQ(read.part.count, 3);
    EXPECT_EQ(read.part.limit, 5u);
    EXPECT_EQ(read.part.scale, 0.25f);
    EXPECT_FALSE(read.part.flag);
    EXPECT_EQ(read.part.shape, Shape::Round);
}
