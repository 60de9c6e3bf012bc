// The env registry and parser: good files, layering, and every kind of bad line.
#include "framework/config/env.h"
#include "framework/core/error.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

using namespace bvhlab;

namespace {

constexpr IntKey kCount{"Set::count", "3", 1, 10, "a count"};
constexpr FloatKey kScale{"Set::scale", "0.5", 0, 2, "a scale"};
constexpr BoolKey kFlag{"Set::flag", "false", "a switch"};
constexpr std::string_view kModes[] = {"fast", "exact"};
constexpr ChoiceKey kMode{"Set::mode", "fast", kModes, "a mode"};
constexpr TextKey kName{"Set::name", "", "a name"};
constexpr PathKey kFile{"Set::file", "", "a file"};
constexpr Vec3Key kPoint{"Set::point", "", "a point"};
constexpr Vec3ListKey kPoints{"Set::points", "", "points"};

EnvRegistry testRegistry() {
    EnvRegistry r;
    r.add(kCount);
    r.add(kScale);
    r.add(kFlag);
    r.add(kMode);
    r.add(kName);
    r.add(kFile);
    r.add(kPoint);
    r.add(kPoints);
    return r;
}

std::filesystem::path writeFile(const std::string& name, const std::string& text) {
    const auto dir = test::scratchDir("env");
    const auto path = dir / name;
    std::ofstream(path) << text;
    return path;
}

// The message of the InputError that `body` throws, or "" if it throws none.
template <typename F>
std::string errorOf(F body) {
    try {
        body();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Env, DefaultsApplyUntilSet) {
    const EnvRegistry r = testRegistry();
    Env env(r);
    EXPECT_EQ(env.get(kCount), 3);
    EXPECT_FLOAT_EQ(env.get(kScale), 0.5f);
    EXPECT_FALSE(env.get(kFlag));
    EXPECT_EQ(env.get(kMode), "fast");
    EXPECT_FALSE(env.get(kPoint).has_value());
    EXPECT_TRUE(env.get(kPoints).empty());
    EXPECT_FALSE(env.isExplicit(kCount));
}

TEST(Env, ParsesFileWithCommentsAndBlankLines) {
    const EnvRegistry r = testRegistry();
    Env env(r);
    env.loadFile(writeFile("good.env",
                           "# comment\n\nSet::count 7   # trailing comment\n"
                           "Set::flag on\nSet::mode exact\nSet::name two words\n"
                           "Set::point 1 2 3\nSet::points 1 2 3, -4 5e-1 6\nSet::file sub/x.obj\n"));
    EXPECT_EQ(env.get(kCount), 7);
    EXPECT_TRUE(env.get(kFlag));
    EXPECT_EQ(env.get(kMode), "exact");
    EXPECT_EQ(env.get(kName), "two words");
    EXPECT_EQ(*env.get(kPoint), Vec3(1, 2, 3));
    ASSERT_EQ(env.get(kPoints).size(), 2u);
    EXPECT_EQ(env.get(kPoints)[1], Vec3(-4, 0.5f, 6));
    EXPECT_TRUE(env.isExplicit(kCount));
    // Relative paths resolve against the env file's folder.
    EXPECT_EQ(env.get(kFile), test::scratchDir("env") / "sub" / "x.obj");
}

TEST(Env, LaterFilesAndOverridesWin) {
    const EnvRegistry r = testRegistry();
    Env env(r);
    env.loadFile(writeFile("a.env", "Set::count 4\nSet::scale 1\n"));
    env.loadFile(writeFile("b.env", "Set::count 5\n"));
    EXPECT_EQ(env.get(kCount), 5);
    EXPECT_FLOAT_EQ(env.get(kScale), 1.0f);
    env.setOverride("Set::count=9");
    EXPECT_EQ(env.get(kCount), 9);
}

TEST(Env, AKeyWithoutAValueKeepsTheEarlierLayersValue) {
    const EnvRegistry r = testRegistry();
    Env env(r);
    env.loadFile(writeFile("scene.env", "Set::name sibenik.obj\nSet::point 1 2 3\n"));
    env.loadFile(writeFile("global.env", "Set::name\nSet::point\nSet::count 4\n"));
    EXPECT_EQ(env.get(kName), "sibenik.obj");
    EXPECT_TRUE(env.get(kPoint).has_value());
    EXPECT_EQ(env.get(kCount), 4);
    EXPECT_NE(errorOf([&] { env.loadFile(writeFile("typo.env", "Set::nmae\n")); }).find("unknown key 'Set::nmae'"),
              std::string::npos);
    env.setOverride("Set::name=");  // -D empties it
    EXPECT_EQ(env.get(kName), "");
}

TEST(Env, UnknownKeyNamesFileLineAndNearestKeys) {
    const EnvRegistry r = testRegistry();
    Env env(r);
    const std::string msg = errorOf([&] { env.loadFile(writeFile("typo.env", "Set::count 2\nSet::cuont 3\n")); });
    EXPECT_NE(msg.find("typo.env:2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Set::cuont"), std::string::npos) << msg;
    EXPECT_NE(msg.find("did you mean Set::count"), std::string::npos) << msg;
}

TEST(Env, BadValuesAreErrorsWithLine) {
    const EnvRegistry r = testRegistry();
    const std::vector<std::string> badLines = {
        "Set::count 11",      "Set::count 0",       "Set::count 2.5",         "Set::count 3x",  "Set::scale nan",
        "Set::scale 3",       "Set::scale abc",     "Set::flag maybe",        "Set::mode slow", "Set::point 1 2",
        "Set::point 1 2 3 4", "Set::point 1 2 inf", "Set::points 1 2 3, 4 5", "justaword",      "Set: 3",
    };
    for (const std::string& line : badLines) {
        Env env(r);
        const std::string msg = errorOf([&] { env.loadFile(writeFile("bad.env", "# first\n" + line + "\n")); });
        EXPECT_NE(msg.find("bad.env:2"), std::string::npos) << line << " -> " << msg;
    }
}

TEST(Env, BadOverrideIsAnError) {
    const EnvRegistry r = testRegistry();
    Env env(r);
    EXPECT_NE(errorOf([&] { env.setOverride("Set::count"); }), "");
    EXPECT_NE(errorOf([&] { env.setOverride("Set::count=99"); }).find("-DSet::count"), std::string::npos);
    EXPECT_NE(errorOf([&] { env.setOverride("Nope::key=1"); }).find("unknown key"), std::string::npos);
}

TEST(Env, MissingFileIsAnError) {
    const EnvRegistry r = testRegistry();
    Env env(r);
    EXPECT_NE(errorOf([&] { env.loadFile("/nonexistent/x.env"); }).find("/nonexistent/x.env"), std::string::npos);
}

TEST(Env, JsonHoldsValueAndOrigin) {
    const EnvRegistry r = testRegistry();
    Env env(r);
    env.setOverride("Set::count=8");
    const nlohmann::json j = env.toJson();
    EXPECT_EQ(j["Set::count"]["value"], "8");
    EXPECT_EQ(j["Set::count"]["from"], "-DSet::count");
    EXPECT_EQ(j["Set::scale"]["from"], "default");
}

// A handle whose name is not registered, or is registered with another type, is a programming
// error, not an input error.
TEST(Env, ReadingThroughAWrongHandleIsALogicError) {
    const EnvRegistry r = testRegistry();
    const Env env(r);
    EXPECT_THROW((void)env.get(IntKey("Set::scale", "0", 0, 1, "")), std::logic_error);
    EXPECT_THROW((void)env.get(BoolKey("Set::nothing", "false", "")), std::logic_error);
    EXPECT_NO_THROW((void)env.get(FloatKey("Set::scale", "0", 0, 1, "")));
}
