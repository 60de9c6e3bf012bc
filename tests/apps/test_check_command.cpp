// `bvhlab check` end to end: one line per check, exit 0 when all pass, 2 on bad input.
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <regex>

namespace {

using bvhlab::test::Result;
using bvhlab::test::run;

TEST(CheckCommand, PassingChecksPrintALineEachAndExitZero) {
    const auto json = bvhlab::test::scratchDir("check") / "check.json";
    const Result r = run("check --accel sahbvh --checks batch,mixed-primitives,builds-at-the-edge --quiet --json " +
                         json.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* check : {"batch", "mixed-primitives", "builds-at-the-edge"}) {
        const std::regex line(std::string("(^|\\n)PASS ") + check + " +[0-9]+ scenes +[0-9]+ [a-z]+ +0 failures +[0-9.]+ s");
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

}  // namespace
