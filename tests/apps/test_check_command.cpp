// `bvhlab check` end to end: one line per check, exit 0 when all pass, 2 on bad input; a crash
// fails its check and the others run; a correct but costly structure passes with a warning; a
// user's animated scene is checked at the frame asked for.
#include "tests/support/cli_run.h"
#include "tests/support/moving_scene.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <regex>

namespace {

using bvhlab::test::Result;
using bvhlab::test::run;
using bvhlab::test::runShell;

// Under AddressSanitizer (tests/sanitize.sh) the third check is a short one: sahbvh's builds at the
// edge, a minute there, run in Registered/CheckSuite.Passes/sahbvh_builds_at_the_edge.
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* kThirdCheck = "watertight";
#else
constexpr const char* kThirdCheck = "builds-at-the-edge";
#endif

TEST(CheckCommand, PassingChecksPrintALineEachAndExitZero) {
    const auto json = bvhlab::test::scratchDir("check") / "check.json";
    const Result r = run("check --accel sahbvh --checks batch,mixed-primitives," + std::string(kThirdCheck) +
                         " --quiet --json " + json.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* check : {"batch", "mixed-primitives", kThirdCheck}) {
        const std::regex line(std::string("(^|\\n)PASS ") + check +
                              " +[0-9]+ scenes +[0-9]+ [a-z]+ +0 failures +[0-9.]+ s");
        EXPECT_TRUE(std::regex_search(r.output, line)) << check << " in\n" << r.output;
    }
    EXPECT_EQ(r.output.find("agreement"), std::string::npos) << "only the checks asked for:\n" << r.output;
    EXPECT_NE(r.output.find("check sahbvh: all checks passed"), std::string::npos) << r.output;
    std::ifstream in(json);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["accel"], "sahbvh");
    EXPECT_TRUE(j["passed"].get<bool>());
    ASSERT_EQ(j["checks"].size(), 3u);
    EXPECT_EQ(j["checks"][0]["check"], "batch");
    EXPECT_GT(j["checks"][0]["cases"].get<int>(), 1000);
}

// --threads, as on every subcommand that traces: the checks' builds and probes run on that many.
TEST(CheckCommand, TakesThreads) {
    const auto json = bvhlab::test::scratchDir("check") / "threads.json";
    const Result r = run("check --accel sahbvh --checks batch --threads 1 --quiet --json " + json.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(json);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["env"]["SetRayTracing::threads"]["value"], "1");
    EXPECT_EQ(j["env"]["SetRayTracing::threads"]["from"], "--threads");
}

// A structure given with keys is checked by the rules of its name: sahbvh8's batches are packets.
TEST(CheckCommand, AStructureWithKeysIsCheckedAsItsName) {
    const Result r = run("check --accel sahbvh8:BVH::bins=8 --checks batch --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("check sahbvh8:BVH::bins=8: all checks passed"), std::string::npos) << r.output;
}

TEST(CheckCommand, UnknownAcceleratorOrCheckExitsTwoListingTheKnownOnes) {
    Result r = run("check --accel nosuch");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("unknown accelerator 'nosuch'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("sahbvh"), std::string::npos) << r.output;

    r = run("check --accel sahbvh --checks agreement,nosuch");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("unknown check 'nosuch'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("builds-at-the-edge"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("PASS"), std::string::npos) << "no check runs on bad input:\n" << r.output;

    r = run("check --accel sahbvh -DBVH::nosuchkey=1 --checks batch");
    EXPECT_EQ(r.exitCode, 2) << r.output;
}

// --scene: a scene file beside the generated scenes, an animated one at Scene::frame, read again in
// the child process of each check that takes scenes; named with its frame in --json.
TEST(CheckCommand, ChecksAUsersAnimatedSceneAtAFrame) {
    const auto dir = bvhlab::test::scratchDir("check_scene");
    const auto scene = dir / "moving.aff", json = dir / "scene.json";
    std::ofstream(scene) << bvhlab::test::movingSceneText();
    const Result r = run("check --accel sahbvh --scene " + scene.string() +
                         " -DScene::frame=2 --checks batch --quiet --json " + json.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("(^|\\n)PASS batch +2 scenes"))) << r.output;
    std::ifstream in(json);
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_EQ(j["scenes"].size(), 1u) << j.dump();
    EXPECT_EQ(j["scenes"][0]["name"], "moving.aff at frame 2");
    EXPECT_EQ(j["scenes"][0]["file"], scene.string());
    EXPECT_EQ(j["scenes"][0]["frame"], 2);
    EXPECT_EQ(j["scenes"][0]["update_to_frame"], 3);
    EXPECT_EQ(j["scenes"][0]["spheres_and_cones_left_out"], 1);
}

TEST(CheckCommand, AMissingOrMalformedSceneOrAFramePastTheLastExitsTwoNamingIt) {
    const auto dir = bvhlab::test::scratchDir("check_scene");
    std::ofstream(dir / "moving.aff") << bvhlab::test::movingSceneText();
    std::ofstream(dir / "malformed.aff") << "v\nfrom 0 0 1\nnot a viewpoint\n";
    const std::string missing = (dir / "missing.obj").string();
    for (const auto& [arguments, message] :
         {std::pair<std::string, std::string>{"--scene " + missing, "--scene " + missing + ": no such file"},
          {"--scene " + (dir / "malformed.aff").string(), (dir / "malformed.aff").string() + ":3: "},
          {"--scene " + (dir / "moving.aff").string() + " -DScene::frame=5",
           "Scene::frame 5 (from -DScene::frame): moving.aff has 5 frames, 0 to 4"}}) {
        const Result r = run("check --accel sahbvh --checks batch --quiet " + arguments);
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("error: " + message), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("PASS"), std::string::npos) << "no check runs on bad input:\n" << r.output;
    }
}

const std::string kPlugins = bvhlab::test::testPlugins();

TEST(CheckCommand, ACrashFailsItsCheckNamingThePluginTheCallAndTheRayAndTheOtherChecksRun) {
    const std::string plugin = kPlugins + "/crashing.so";
    Result r = run("check --plugin " + plugin + " --accel crashing --checks agreement,watertight --quiet");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    // Not anchored at a line's start: a sanitizer's report of the crash (the sanitizer pass) is on
    // the child's stderr, which may run into the line this prints.
    EXPECT_TRUE(std::regex_search(r.output, std::regex("FAIL agreement .*1 failures .*\\(crashed\\)"))) << r.output;
    EXPECT_NE(r.output.find("    agreement: SIGSEGV (Segmentation fault) in plugin " + plugin +
                            ", accelerator 'crashing': findNearest() of the ray org=("),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("FAIL watertight .*\\(crashed\\)"))) << r.output;
    EXPECT_NE(r.output.find("check crashing: FAILED"), std::string::npos) << r.output;

    // A stack overflow in build(), with the primitives it was given.
    r = runShell("ulimit -s 8192; " + bvhlab::test::bvhlabProgram() + " check --plugin " + plugin +
                 " --accel crashing_build --checks batch --quiet");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_TRUE(
        std::regex_search(r.output, std::regex("batch: SIGSEGV \\(Segmentation fault\\) in plugin .*crashing.so, "
                                               "accelerator 'crashing_build': build\\(\\) over [0-9]+ primitives")))
        << r.output;
}

TEST(CheckCommand, AnExceptionFailsItsCheckNamingThePluginAndTheOtherChecksRun) {
    const Result r =
        run("check --plugin " + kPlugins + "/throwing.so --accel throwing_query --checks batch,watertight --quiet");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("    batch: plugin " + kPlugins +
                            "/throwing.so, accelerator 'throwing_query': findNearest() threw: "
                            "no queries today"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("(^|\\n)FAIL watertight .*\\(threw\\)"))) << r.output;
}

TEST(CheckCommand, ACorrectStructureThatWorksFarHarderThanSahbvhPassesWithACostWarning) {
    // `interleaved` deals each node's primitives out to its children in turn: every box spans the scene.
    Result r = run("check --plugin " + kPlugins + "/builders.so --accel interleaved --checks batch,cost --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("(^|\\n)PASS batch "))) << r.output;
    EXPECT_TRUE(std::regex_search(
        r.output, std::regex("(^|\\n)WARN cost .*0 failures .*sahbvh's.*past 10x: right answers at an absurd cost")))
        << r.output;
    EXPECT_NE(r.output.find("check interleaved: all checks passed, with a warning (cost)"), std::string::npos)
        << r.output;

    r = run("check --accel sahbvh8 --checks cost --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("(^|\\n)PASS cost .*sahbvh's"))) << r.output;
    EXPECT_NE(r.output.find("check sahbvh8: all checks passed\n"), std::string::npos) << r.output;

    r = run("check --accel embree --checks cost --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("(^|\\n)SKIP cost .*no counters"))) << r.output;
}

}  // namespace
