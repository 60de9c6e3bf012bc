// `bvhlab batch --slurm` on a real Slurm: three small scenes x two accelerators at 200 x 200 as
// an array of three shards and the merge after them, whose tables must equal one run's in every
// column but the timings; and a shard cancelled while it runs (scancel) fails the merge, which
// names that shard's log. ctest's SlurmCluster test runs these inside
// tests/slurm/with_local_slurm.sh (a private munged, slurmctld and slurmd, stopped after); the
// test binary alone skips them. Each job's id and state are printed for the log.
#include "tests/support/batch_results.h"
#include "tests/support/batch_scenes.h"
#include "tests/support/cli_run.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <thread>

using namespace bvhlab;
using test::csvWithoutTimings;
using test::jsonRowsWithoutTimings;
using test::makeSolidScenes;
using test::readText;
using test::Result;
using test::run;

namespace fs = std::filesystem;

namespace {

class SlurmCluster : public ::testing::Test {
protected:
    void SetUp() override {
        if (!std::getenv("BVHLAB_LOCAL_SLURM"))
            GTEST_SKIP() << "no Slurm cluster: ctest's SlurmCluster test runs these inside "
                            "tests/slurm/with_local_slurm.sh";
    }
};

struct Submitted {
    std::string shards, merge;  // job ids
};

// Submits with `bvhlab ARGS --slurm 3` and reads the job ids it prints.
Submitted submit(const std::string& args) {
    const Result r = run(args + " --slurm 3");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    fmt::print("{}", r.output);
    std::smatch m;
    const std::regex ids(R"(as array job (\d+) .*, the merge as job (\d+))");
    if (!std::regex_search(r.output, m, ids)) {
        ADD_FAILURE() << "no job ids in:\n" << r.output;
        return {};
    }
    return {m[1], m[2]};
}

// JobState of each of `jobs` as scontrol knows them (an array's tasks as ARRAY_TASK).
std::map<std::string, std::string> jobStates(const std::vector<std::string>& jobs) {
    std::map<std::string, std::string> states;
    static const std::regex record(R"(JobId=(\d+) (?:ArrayJobId=(\d+) ArrayTaskId=(\S+) )?.*JobState=(\w+))");
    for (const std::string& job : jobs) {
        std::stringstream lines(test::runShell("scontrol show job --oneliner " + job).output);
        for (std::string line; std::getline(lines, line);) {
            std::smatch m;
            if (std::regex_search(line, m, record))
                states[m[2].matched ? m[2].str() + "_" + m[3].str() : m[1].str()] = m[4];
        }
    }
    return states;
}

bool finished(const std::string& state) {
    return state != "PENDING" && state != "RUNNING" && state != "CONFIGURING" && state != "COMPLETING" &&
           state != "SUSPENDED" && !state.empty();
}

// Waits (at most `seconds`) until the merge job has ended; prints and returns every job's state.
std::map<std::string, std::string> waitForMerge(const Submitted& jobs, int seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    std::map<std::string, std::string> states = jobStates({jobs.shards, jobs.merge});
    while (!finished(states[jobs.merge]) && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(250));
        states = jobStates({jobs.shards, jobs.merge});
    }
    for (const auto& [id, state] : states)
        fmt::print("slurm job {} ({}): {}\n", id,
                   id == jobs.merge ? "merge" : "shard " + id.substr(id.find('_') + 1) + "/3", state);
    return states;
}

// `bvhlab batch` over makeSolidScenes' folder at 200 x 200, its own scene cache, into DIR/OUT.
std::string solidBatchArgs(const fs::path& dir, const std::string& accels, const std::string& out) {
    return "batch --scenes " + (dir / "scenes.list").string() + " --accel " + accels +
           " -DCamera::width=200 -DCamera::height=200 -DScene::cacheDir=" + (dir / "cache").string() + " --out " +
           (dir / out).string();
}

TEST_F(SlurmCluster, ThreeShardsAndTheirMergeGiveTheTablesOfOneRun) {
    const fs::path dir = makeSolidScenes("slurm_cluster");
    const Submitted jobs = submit(solidBatchArgs(dir, "sahbvh,embree", "cluster"));
    ASSERT_FALSE(jobs.merge.empty());
    std::map<std::string, std::string> states = waitForMerge(jobs, 120);
    for (const std::string task : {"_0", "_1", "_2"}) EXPECT_EQ(states[jobs.shards + task], "COMPLETED") << task;
    ASSERT_EQ(states[jobs.merge], "COMPLETED") << readText(dir / "cluster" / "slurm" / "merge.log");

    const Result whole = run(solidBatchArgs(dir, "sahbvh,embree", "whole"));
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    const auto csv = csvWithoutTimings(dir / "cluster" / "results.csv");
    EXPECT_EQ(csv.size(), 1u + 3 * 2 * 2);  // header, two rows per scene x accelerator
    EXPECT_EQ(csv, csvWithoutTimings(dir / "whole" / "results.csv"));
    EXPECT_EQ(jsonRowsWithoutTimings(dir / "cluster" / "results.json"),
              jsonRowsWithoutTimings(dir / "whole" / "results.json"));
    EXPECT_NE(readText(dir / "cluster" / "results.md").find("Jobs: 6 ("), std::string::npos);
    // Each shard ran two of the six jobs, into its own folder.
    for (int shard = 0; shard < 3; ++shard)
        EXPECT_NE(readText(dir / "cluster" / "slurm" / fmt::format("shard-{}.log", shard))
                      .find(fmt::format("shard {}/3 runs 2 of them", shard)),
                  std::string::npos)
            << shard;
}

TEST_F(SlurmCluster, ACancelledShardFailsTheMergeNamingItsLog) {
    // Shard 1 gets the naive render of 61k-triangle spheres (jobs 1 and 4 of spheres, torus,
    // boxes x sahbvh, naive): it runs for a while, long enough to be cancelled while it runs.
    const fs::path dir = makeSolidScenes("slurm_cancel", 5);
    const Submitted jobs = submit(solidBatchArgs(dir, "sahbvh,naive", "cluster"));
    ASSERT_FALSE(jobs.merge.empty());
    const std::string victim = jobs.shards + "_1";
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (jobStates({victim})[victim] != "RUNNING" && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ASSERT_EQ(jobStates({victim})[victim], "RUNNING");
    ASSERT_EQ(test::runShell("scancel " + victim).exitCode, 0);

    std::map<std::string, std::string> states = waitForMerge(jobs, 120);
    EXPECT_EQ(states[jobs.shards + "_0"], "COMPLETED");
    EXPECT_EQ(states[victim], "CANCELLED");
    EXPECT_EQ(states[jobs.shards + "_2"], "COMPLETED");
    EXPECT_EQ(states[jobs.merge], "FAILED");
    const fs::path slurm = dir / "cluster" / "slurm";
    const std::string log = readText(slurm / "merge.log");
    fmt::print("merge.log:\n{}", log);
    EXPECT_NE(log.find("error: shard 1/3 did not finish (it failed, was cancelled or never started): see its log " +
                       (slurm / "shard-1.log").string()),
              std::string::npos)
        << log;
    EXPECT_EQ(log.find("shard 0/3"), std::string::npos) << log;
    EXPECT_NE(readText(slurm / "shard-1.log").find("CANCELLED"), std::string::npos);  // slurmstepd says so
    EXPECT_FALSE(fs::exists(dir / "cluster" / "results.md"));
}

}  // namespace
