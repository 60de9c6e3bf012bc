// A rerun of a batch keeps each finished job whose result key is this run's and runs the rest
// (apps/batch/batch_resume.h): an interrupted batch runs only the jobs it lacks, a job of a scene
// that stopped before its heat maps runs again, a rebuilt plugin's jobs run again and the others'
// are kept, and --fresh runs all.
#include "tests/support/batch_results.h"
#include "tests/support/batch_scenes.h"
#include "tests/support/cli_run.h"
#include "tests/support/scan_plugin.h"
#include "tests/support/test_paths.h"
#include "tests/support/text_count.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

using namespace bvhlab;
using test::batchArgs;
using test::makeScenes;
using test::readJson;
using test::Result;
using test::run;

namespace fs = std::filesystem;

TEST(BatchResume, AnInterruptedBatchRunsOnlyTheJobsItLacks) {
    const fs::path dir = makeScenes("resume");
    const fs::path out = dir / "out";
    Result r = run(batchArgs(dir, "out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(
        0 < test::occurrences(r.output, "batch: 0 jobs kept from an earlier run (same result key); 4 to run: 4 new"))
        << r.output;
    const std::string started = readJson(out / "jobs" / "first__sahbvh.json")["run"]["started"];

    // As if the run had stopped in its last job.
    fs::remove(out / "jobs" / "second__sahbvh.json");
    r = run(batchArgs(dir, "out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(
        0 < test::occurrences(r.output, "batch: 3 jobs kept from an earlier run (same result key); 1 to run: 1 new"))
        << r.output;
    EXPECT_TRUE(0 < test::occurrences(r.output, "[job 1/1] second sahbvh: rendering with shadows")) << r.output;
    EXPECT_FALSE(0 < test::occurrences(r.output, "first naive")) << r.output;
    EXPECT_EQ(test::occurrences(r.output, "scene first:"), 0u) << "a scene with nothing to run is not loaded\n"
                                                               << r.output;
    // The scene's new heat maps are drawn at its kept jobs' scale.
    EXPECT_TRUE(0 < test::occurrences(r.output, "(that of the scene's jobs kept from an earlier run: naive)"))
        << r.output;
    EXPECT_EQ(readJson(out / "jobs" / "first__sahbvh.json")["run"]["started"], started);
    EXPECT_TRUE(0 < test::occurrences(readJson(out / "results.json").dump(), "second__sahbvh"));
    EXPECT_TRUE(0 < test::occurrences(r.output, "| second | sahbvh |")) << r.output;

    // A job whose scene stopped before its heat maps were drawn runs again.
    nlohmann::json job = readJson(out / "jobs" / "first__naive.json");
    for (const char* render : {"no_shadows", "shadows"}) job["runs"][render].erase("heatmap");
    std::ofstream(out / "jobs" / "first__naive.json") << job.dump(2);
    r = run(batchArgs(dir, "out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(0 < test::occurrences(r.output,
                                      "3 jobs kept from an earlier run (same result key); 1 to run: 1 because its heat "
                                      "maps were not drawn"))
        << r.output;

    r = run(batchArgs(dir, "out") + " --fresh");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(0 < test::occurrences(
                        r.output, "0 jobs kept from an earlier run (same result key); 4 to run: 4 because of --fresh"))
        << r.output;
}

TEST(BatchResume, ARebuiltPluginsJobsRunAgain) {
    const fs::path dir = makeScenes("resume_plugin");
    const fs::path plugin = test::installScan(dir, 1);
    const std::string args = "batch --scenes " + (dir / "scenes.list").string() + " --accel scan,sahbvh --plugin " +
                             plugin.string() + " -DScene::cacheDir= --out " + (dir / "out").string();
    Result r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(0 < test::occurrences(r.output, "batch: 4 jobs kept from an earlier run (same result key); 0 to run"))
        << r.output;

    test::installScan(dir, 2);
    r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(0 < test::occurrences(r.output,
                                      "batch: 2 jobs kept from an earlier run (same result key); 2 to run: 2 because "
                                      "plugin crc32: "))
        << r.output;
    EXPECT_TRUE(0 < test::occurrences(r.output, "[job 2/2] second scan")) << r.output;
}
