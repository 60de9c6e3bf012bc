// `bvhlab batch --slurm N` without a cluster: a stand-in sbatch on PATH records its arguments and
// answers job ids; the scripts it was given are then run by bash as Slurm runs them (each shard
// with its SLURM_ARRAY_TASK_ID, then the merge). The merged tables are one run's; a shard that did
// not finish fails the merge, which names its log and merges nothing; a requeued shard keeps the
// jobs it finished; without sbatch nothing is written. test_slurm_cluster.cpp submits to a real Slurm.
#include "tests/support/batch_results.h"
#include "tests/support/batch_scenes.h"
#include "tests/support/cli_run.h"
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

using namespace bvhlab;
using test::batchArgs;
using test::csvWithoutTimings;
using test::jsonRowsWithoutTimings;
using test::makeScenes;
using test::readText;
using test::Result;

namespace fs = std::filesystem;

namespace {

// DIR/NAME/sbatch: appends its arguments to DIR/NAME/calls.txt and prints the job ids 101, 102,
// ... as `sbatch --parsable` does (with a cluster name); `failing` instead refuses as sbatch
// refuses an unknown partition.
fs::path standInSbatch(const fs::path& dir, const std::string& name, bool failing = false) {
    const fs::path folder = dir / name;
    fs::create_directories(folder);
    std::ofstream(folder / "sbatch")
        << "#!/bin/sh\n"
        << (failing ? "echo 'sbatch: error: invalid partition specified: nosuch' >&2\nexit 1\n"
                    : "echo \"$*\" >> \"$(dirname \"$0\")/calls.txt\"\n"
                      "echo \"$((100 + $(wc -l < \"$(dirname \"$0\")/calls.txt\")));bvhlabtest\"\n");
    fs::permissions(folder / "sbatch", fs::perms::owner_all);
    return folder;
}

// `bvhlab ARGS` with `path` as PATH.
Result runWithPath(const std::string& path, const std::string& args) {
    return test::runShell("PATH=" + path + " " + test::bvhlabProgram() + " " + args);
}

// A written script run as Slurm runs it: by bash, a shard with its array task id.
Result runAsSlurm(const fs::path& script, int arrayTask = -1) {
    return test::runShell((arrayTask >= 0 ? "SLURM_ARRAY_TASK_ID=" + std::to_string(arrayTask) + " " : "") + "bash " +
                          script.string());
}

}  // namespace

TEST(BatchSlurm, SubmitsTheShardsAndAfterThemTheMergeOfOneRunsTables) {
    const fs::path dir = makeScenes("slurm_submit");
    const fs::path sbatch = standInSbatch(dir, "bin"), out = dir / "out";
    const Result r = runWithPath(sbatch.string() + ":/usr/bin:/bin",
                                 batchArgs(dir, "out") + " --slurm 3 --slurm-args '--partition=short --time=00:10:00'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const std::string& what : std::vector<std::string>{
             "3 shards as array job 101 (101_0 .. 101_2), the merge as job 102", "squeue -j 101,102",
             (out / "slurm" / "merge.log").string(), (out / "results.md").string()})
        EXPECT_NE(r.output.find(what), std::string::npos) << what << "\n" << r.output;
    const fs::path shards = out / "slurm" / "shards.sbatch", merge = out / "slurm" / "merge.sbatch";
    EXPECT_EQ(readText(sbatch / "calls.txt"),
              "--parsable --partition=short --time=00:10:00 " + shards.string() + "\n" +
                  "--parsable --partition=short --time=00:10:00 --dependency=afterany:101 " + merge.string() + "\n");
    const std::string script = readText(shards);
    for (const char* what : {"#SBATCH --array=0-2\n", "#SBATCH --cpus-per-task=1\n", "--accel naive,sahbvh",
                             "--shard \"$shard/3\" --out \"$out/shards/$shard\""})
        EXPECT_NE(script.find(what), std::string::npos) << what << "\n" << script;
    // The folders are the batch's before any shard runs; nothing ran here.
    for (const char* folder : {"", "shards/0", "shards/1", "shards/2"})
        EXPECT_TRUE(fs::exists(out / folder / "batch.json")) << folder;
    EXPECT_TRUE(fs::is_empty(out / "jobs"));

    for (int task = 0; task < 3; ++task) {
        const Result shard = runAsSlurm(shards, task);
        ASSERT_EQ(shard.exitCode, 0) << shard.output;
        EXPECT_TRUE(fs::exists(out / "slurm" / ("shard-" + std::to_string(task) + ".done")));
    }
    const Result merged = runAsSlurm(merge);
    ASSERT_EQ(merged.exitCode, 0) << merged.output;
    const Result whole = test::run(batchArgs(dir, "whole"));
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    EXPECT_EQ(csvWithoutTimings(out / "results.csv"), csvWithoutTimings(dir / "whole" / "results.csv"));
    EXPECT_EQ(jsonRowsWithoutTimings(out / "results.json"), jsonRowsWithoutTimings(dir / "whole" / "results.json"));
    EXPECT_NE(readText(out / "results.md").find("Jobs: 4 ("), std::string::npos);
}

TEST(BatchSlurm, TheShardsLoadThePluginsTheBatchWasGiven) {
    const fs::path dir = makeScenes("slurm_plugin");
    const fs::path sbatch = standInSbatch(dir, "bin"), out = dir / "out", plugin = dir / "mine" / "grid.so";
    fs::create_directories(plugin.parent_path());
    fs::copy_file(fs::path(test::bvhlabProgram()).parent_path() / "plugins" / "grid.so", plugin);
    const Result r = runWithPath(sbatch.string() + ":/usr/bin:/bin",
                                 "batch --scenes " + (dir / "scenes.list").string() + " --accel grid:Grid::density=2 " +
                                     "--plugin " + plugin.string() + " -DScene::cacheDir=" + (dir / "cache").string() +
                                     " --out " + out.string() + " --slurm 1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string script = readText(out / "slurm" / "shards.sbatch");
    EXPECT_NE(script.find("--plugin " + plugin.string()), std::string::npos) << script;
    const Result shard = runAsSlurm(out / "slurm" / "shards.sbatch", 0);
    ASSERT_EQ(shard.exitCode, 0) << shard.output;
    EXPECT_NE(readText(out / "shards" / "0" / "batch.json").find("grid:Grid::density=2"), std::string::npos);
}

TEST(BatchSlurm, AShardThatDidNotFinishFailsTheMergeNamingItsLog) {
    const fs::path dir = makeScenes("slurm_unfinished");
    const fs::path sbatch = standInSbatch(dir, "bin"), out = dir / "out";
    ASSERT_EQ(runWithPath(sbatch.string() + ":/usr/bin:/bin", batchArgs(dir, "out") + " --slurm 3").exitCode, 0);
    // Shard 1 ran once before; this time it is cancelled before it ends (it never gets to .done).
    ASSERT_EQ(runAsSlurm(out / "slurm" / "shards.sbatch", 1).exitCode, 0);
    for (int task : {0, 2}) ASSERT_EQ(runAsSlurm(out / "slurm" / "shards.sbatch", task).exitCode, 0);
    fs::remove(out / "slurm" / "shard-1.done");

    const Result merged = runAsSlurm(out / "slurm" / "merge.sbatch");
    EXPECT_EQ(merged.exitCode, 1) << merged.output;
    EXPECT_NE(merged.output.find("error: shard 1/3 did not finish (it failed, was cancelled or never started): see "
                                 "its log " +
                                 (out / "slurm" / "shard-1.log").string()),
              std::string::npos)
        << merged.output;
    EXPECT_NE(merged.output.find("1 of 3 shards did not finish: nothing merged"), std::string::npos) << merged.output;
    EXPECT_EQ(merged.output.find("shard 0/3"), std::string::npos) << merged.output;
    EXPECT_FALSE(fs::exists(out / "results.md"));
    EXPECT_TRUE(fs::is_empty(out / "jobs"));
}

// A shard that Slurm requeues (preempted, or its node failed) runs its command again, which keeps
// the jobs it finished and runs the rest; its log goes on.
TEST(BatchSlurm, ARequeuedShardKeepsTheJobsItFinished) {
    const fs::path dir = makeScenes("slurm_requeued");
    const fs::path sbatch = standInSbatch(dir, "bin"), out = dir / "out";
    ASSERT_EQ(runWithPath(sbatch.string() + ":/usr/bin:/bin", batchArgs(dir, "out") + " --slurm 2").exitCode, 0);
    const fs::path script = out / "slurm" / "shards.sbatch";
    for (const char* what : {"#SBATCH --requeue\n", "#SBATCH --open-mode=append\n"})
        EXPECT_NE(readText(script).find(what), std::string::npos) << what;
    ASSERT_EQ(runAsSlurm(script, 0).exitCode, 0);
    // Preempted in its second job (jobs 0 and 2 are shard 0's: first naive, second naive).
    fs::remove(out / "shards" / "0" / "jobs" / "second__naive.json");
    const Result requeued = runAsSlurm(script, 0);
    ASSERT_EQ(requeued.exitCode, 0) << requeued.output;
    EXPECT_NE(requeued.output.find("batch: 1 jobs kept from an earlier run (same result key); 1 to run: 1 new"),
              std::string::npos)
        << requeued.output;
    EXPECT_NE(requeued.output.find("[job 1/1] second naive"), std::string::npos) << requeued.output;
    EXPECT_TRUE(fs::exists(out / "slurm" / "shard-0.done"));
}

TEST(BatchSlurm, WithoutSbatchOnPathItSaysSoAndWritesNothing) {
    const fs::path dir = makeScenes("slurm_nosbatch");
    const fs::path empty = dir / "empty";
    fs::create_directories(empty);
    const Result r = runWithPath(empty.string(), batchArgs(dir, "out") + " --slurm 2");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_EQ(r.output, "error: --slurm: sbatch is not on PATH (" + empty.string() +
                            "): run this where jobs are submitted to the cluster (a Slurm login node), or put "
                            "Slurm's bin folder on PATH\n");
    EXPECT_FALSE(fs::exists(dir / "out" / "batch.json"));
    EXPECT_FALSE(fs::exists(dir / "out" / "slurm"));
}

TEST(BatchSlurm, BadSlurmArgumentsAreErrors) {
    const fs::path dir = makeScenes("slurm_bad");
    const std::string path = standInSbatch(dir, "bin").string() + ":/usr/bin:/bin";
    for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
             {" --slurm 5", "--slurm 5: the batch has 4 jobs, so at most 4 shards"},
             {" --slurm 2 --shard 0/2", "--slurm and --shard do not go together"},
             {" --slurm 0", "--slurm"},
             {" --slurm-args --partition=short", "--slurm-args requires --slurm"}}) {
        const Result r = runWithPath(path, batchArgs(dir, "out") + args);
        EXPECT_NE(r.exitCode, 0) << args;
        EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "bin" / "calls.txt"));  // nothing submitted

    // sbatch refuses: its message, then ours naming the command.
    const Result refused = runWithPath(standInSbatch(dir, "refusing", true).string() + ":/usr/bin:/bin",
                                       batchArgs(dir, "out") + " --slurm 2 --slurm-args --partition=nosuch");
    EXPECT_EQ(refused.exitCode, 1) << refused.output;
    EXPECT_NE(refused.output.find("sbatch: error: invalid partition specified: nosuch\nerror: `"), std::string::npos)
        << refused.output;
    EXPECT_NE(refused.output.find("--parsable --partition=nosuch"), std::string::npos) << refused.output;
    EXPECT_NE(refused.output.find("failed (exit code 1; sbatch's message is above)"), std::string::npos)
        << refused.output;
}
