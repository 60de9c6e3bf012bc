// The commands that run jobs (a structure on a scene, a check) run each in a process of its own:
// a crash, an exception or a time-out (--job-timeout) is a failed row with its reason in every
// table and JSON the command writes, the other jobs run, and the exit code says that some failed
// (3; check: 1, a failed check). A build that runs long says so on stderr.
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"
#include "tests/support/text_count.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>

namespace bvhlab::test {
namespace {

namespace fs = std::filesystem;

// Under AddressSanitizer (tests/sanitize.sh) every process starts and runs several times slower:
// the time-outs that the jobs which must pass run under grow alike.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kSlowdown = 4;
#else
constexpr int kSlowdown = 1;
#endif
// "timed out after N s" of a --job-timeout of `seconds` x kSlowdown.
std::string timedOut(int seconds) { return fmt::format("timed out after {} s", seconds * kSlowdown); }

// A folder with a tiny mesh; commands run in it with their temporary files and scene cache in it
// too, so that a test sees what a run leaves behind.
struct JobWorkspace {
    fs::path dir;
    explicit JobWorkspace(const std::string& name) : dir(scratchDir("failed_jobs") / name) {
        fs::remove_all(dir);
        fs::create_directories(dir / "tmp");
        std::ofstream(dir / "mesh.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nv 0 0 1\n"
                                           "f 1 2 3\nf 2 4 3\nf 1 5 2\nf 3 4 5\n";
    }
    // `bvhlab COMMAND ARGS` in the workspace, with the test plugins at hand; `then` follows in the shell.
    Result run(const std::string& command, const std::string& args, const std::string& then = "") const {
        const std::string plugins = testPlugins();
        return runShell(fmt::format(
            "cd {} && TMPDIR={}/tmp XDG_CACHE_HOME={}/cache {} {} {} --plugin {}/crashing.so "
            "--plugin {}/throwing.so --plugin {}/hanging.so {}",
            dir.string(), dir.string(), dir.string(), bvhlabProgram(), command, args, plugins, plugins, plugins, then));
    }
    std::string read(const std::string& file) const {
        std::ifstream in(dir / file);
        return {std::istreambuf_iterator<char>(in), {}};
    }
    bool tmpIsEmpty() const { return fs::is_empty(dir / "tmp"); }
};

TEST(FailedJobs, BatchGivesAFailedRowPerCrashExceptionAndTimeOutAndTheOtherJobsRows) {
    const JobWorkspace w("batch");
    const Result r =
        w.run("batch", fmt::format("--scenes mesh.obj --accel crashing,throwing,hanging,sahbvh --job-timeout {} "
                                   "-DCamera::width=16 -DCamera::height=12 --out out",
                                   3 * kSlowdown));
    EXPECT_EQ(r.exitCode, 3) << r.output;
    EXPECT_NE(r.output.find("batch: 3 failed jobs in the tables"), std::string::npos) << r.output;
    // mesh.obj has no scene env: said once, by the batch, not again by each job's process.
    EXPECT_EQ(occurrences(r.output, "mesh.obj: no scene env file in"), 1u) << r.output;

    const std::string md = w.read("out/results.md");
    EXPECT_TRUE(std::regex_search(
        md, std::regex(R"(\| mesh \| crashing \| failed: crashed: SIGSEGV \(Segmentation )"
                       R"(fault\) in plugin .*crashing.so, accelerator 'crashing': findNearestBatch\(\) of 192 rays)")))
        << md;
    EXPECT_NE(md.find("| mesh | throwing | failed: plugin "), std::string::npos) << md;
    EXPECT_NE(md.find("accelerator 'throwing': build() threw: no build today |"), std::string::npos) << md;
    EXPECT_NE(md.find("| mesh | hanging | failed: " + timedOut(3) + " |"), std::string::npos) << md;
    // What ran, for the failed jobs too: their structures with their plugins.
    EXPECT_NE(md.find("- `hanging`: "), std::string::npos) << md;
    EXPECT_NE(md.find("plugin hanging.so, CRC-32 "), std::string::npos) << md;
    EXPECT_EQ(md.find("not recorded"), std::string::npos) << md;
    EXPECT_NE(md.find("| mesh | sahbvh | | 4 |"), std::string::npos) << "the good job's rows:\n" << md;
    EXPECT_NE(md.find("Jobs: 4, 3 of them failed"), std::string::npos) << md;

    const std::string csv = w.read("out/results.csv");
    EXPECT_NE(csv.find(",failed\n"), std::string::npos) << csv;
    EXPECT_NE(csv.find("mesh,hanging" + std::string(16, ',') + timedOut(3) + "\n"), std::string::npos) << csv;
    EXPECT_NE(csv.find("mesh,sahbvh,false,4,"), std::string::npos) << csv;

    const nlohmann::json j = nlohmann::json::parse(w.read("out/results.json"));
    EXPECT_EQ(j["failed_jobs"], 3);
    ASSERT_EQ(j["jobs"].size(), 4u);
    EXPECT_EQ(j["jobs"][2]["failed"], timedOut(3));
    EXPECT_FALSE(j["jobs"][3].contains("failed"));
    EXPECT_TRUE(fs::exists(w.dir / "out/images/mesh__sahbvh.png"));
    EXPECT_TRUE(w.tmpIsEmpty()) << "a job's result file is left behind";

    // Merged, the failed jobs are the merge's too.
    const Result merged = w.run("batch", "--merge out --out merged");
    EXPECT_EQ(merged.exitCode, 3) << merged.output;
    EXPECT_NE(w.read("merged/results.md").find("| mesh | hanging | failed: " + timedOut(3) + " |"), std::string::npos);
}

TEST(FailedJobs, CheckFailsACheckThatRunsOutOfTimeAndLeavesNoFile) {
    const JobWorkspace w("check");
    const Result r = w.run("check", "--accel hanging --checks batch,watertight --job-timeout 1 --quiet");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("(^|\\n)FAIL batch .*1 failures .*\\(timed out after 1 s\\)")))
        << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("(^|\\n)FAIL watertight .*\\(timed out after 1 s\\)")))
        << r.output;
    EXPECT_TRUE(w.tmpIsEmpty()) << "a check's result file is left behind";
}

TEST(FailedJobs, BenchWritesItsJsonWithAFailedRow) {
    const JobWorkspace w("bench");
    const Result r = w.run("bench",
                           "--scenes mesh.obj --accel crashing --builds 1 --passes 1 --threads 1 --queries single "
                           "--out bench.json");
    EXPECT_EQ(r.exitCode, 3) << r.output;
    EXPECT_NE(r.output.find("mesh             failed: crashed: SIGSEGV (Segmentation fault) in plugin "),
              std::string::npos)
        << r.output;
    const nlohmann::json j = nlohmann::json::parse(w.read("bench.json"));
    EXPECT_EQ(j["failed_jobs"], 1);
    ASSERT_EQ(j["rows"].size(), 1u);
    EXPECT_EQ(j["rows"][0]["scene"], "mesh");
    EXPECT_NE(j["rows"][0]["failed"].get<std::string>().find("accelerator 'crashing'"), std::string::npos) << j.dump(2);
}

TEST(FailedJobs, StressEndsAHangingBuildAfterItsTimeAndGivesFailedRows) {
    const JobWorkspace w("stress");
    const Result r =
        w.run("stress", fmt::format("--accel crashing,hanging,sahbvh --parts acne,builders --acne-pixels 8 "
                                    "--builder-prims 1000 --builder-max-seconds {} --job-timeout {} --threads 1 "
                                    "--out stress.json",
                                    2 * kSlowdown, 3 * kSlowdown));
    EXPECT_EQ(r.exitCode, 3) << r.output;
    EXPECT_NE(r.output.find("hanging: failed: " + timedOut(3) + "\n"), std::string::npos) << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("crashing: failed: crashed: SIGSEGV .*accelerator 'crashing'")))
        << r.output;
    EXPECT_TRUE(std::regex_search(
        r.output, std::regex(fmt::format("hanging +failed: the build did not end within {} s", 2 * kSlowdown))))
        << r.output;
    const nlohmann::json j = nlohmann::json::parse(w.read("stress.json"));
    EXPECT_EQ(j["failed_jobs"], 3);  // crashing in both parts, hanging's acne
    size_t sahbvhRows = 0, failedRows = 0;
    for (const char* part : {"acne", "builders"})
        for (const nlohmann::json& row : j[part]) {
            sahbvhRows += row["accel"] == "sahbvh";
            failedRows += row.contains("failed");
        }
    EXPECT_EQ(sahbvhRows, 6u + 3u) << "every case of the good structure ran";
    EXPECT_EQ(failedRows, 4u);  // and hanging's first build at the edge
    EXPECT_TRUE(w.tmpIsEmpty()) << "a job's result file is left behind";
}

TEST(FailedJobs, SpdGivesAFailedRowAndTheOtherStructuresRows) {
    const JobWorkspace w("spd");
    std::ofstream(w.dir / "balls.nff") << "v\nfrom 0 -6 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 8 8\n"
                                          "l 4 -3 6\nf 1 0.75 0.33 0.8 0 100000 0 1\n"
                                          "p 3\n4 4 -0.5\n-4 4 -0.5\n0 -4 -0.5\ns 0 0 0.5 1\n";
    std::ofstream(w.dir / "havran_stats_grids.txt")
        << "Invariants\n balls gears lattice mount\nPrimaryRay[-] 64 64 64 64\n";
    std::ofstream(w.dir / "havran_stats_octrees.txt") << "BALLS\n N_IT 19.0\n N_TS 11.0\n";
    const Result r = w.run("spd", "balls.nff --accel crashing,sahbvh -DSpd::reference=. --out spd --quiet");
    EXPECT_EQ(r.exitCode, 3) << r.output;
    const std::string md = w.read("spd/spd.md");
    EXPECT_NE(md.find("| crashing | failed: crashed: SIGSEGV (Segmentation fault) in plugin "), std::string::npos)
        << md;
    EXPECT_TRUE(std::regex_search(md, std::regex(R"(\| sahbvh \| [0-9.]+ \| [0-9.]+ \|)"))) << md;
    EXPECT_NE(md.find("| PrimaryRay | 81 | 64 |"), std::string::npos) << "the invariants of the structure that ran:\n"
                                                                      << md;
    const nlohmann::json j = nlohmann::json::parse(w.read("spd/spd.json"));
    EXPECT_EQ(j["failed_jobs"], 1);
    EXPECT_TRUE(j["scenes"][0]["accels"][0].contains("failed"));
    EXPECT_EQ(j["scenes"][0]["accels"][1]["accel"], "sahbvh");
}

// tradeoff: each configuration of a scene is a job; a failed one is a row of its own in the CSV
// and Markdown, left out of every figure, and measured again by the next run.
// The line of `text` that starts with `start`, without its end.
std::string lineOf(const std::string& text, const std::string& start) {
    const size_t at = text.find("\n" + start);
    return at == std::string::npos ? "" : text.substr(at + 1, text.find('\n', at + 1) - at - 1);
}

// How many commas follow the accel column in every row of a CSV file (its header's less the two
// before it): a failed row has only them between its accel and its reason.
size_t commasAfterAccel(const std::string& csv) {
    return size_t(std::count(csv.begin(), csv.begin() + csv.find('\n'), ',') - 2);
}

// `bvhlab plot DIR` draws the configurations measured and passes over the failed ones (where
// Debian's matplotlib is at hand).
void expectPlotsOf(const JobWorkspace& w, const std::string& folder) {
    if (std::system("/usr/bin/python3 -c 'import matplotlib' 2>/dev/null") != 0) return;
    const Result plot = runShell(fmt::format("cd {} && {} plot {}", w.dir.string(), bvhlabProgram(), folder));
    EXPECT_EQ(plot.exitCode, 0) << plot.output;
}

TEST(FailedJobs, TradeoffGivesFailedRowsAndMeasuresThemAgainOnTheNextRun) {
    const JobWorkspace w("tradeoff");
    const std::string args =
        "--quick --scenes mesh.obj --accel crashing,hanging,sahbvh --bins 4 --size 8 --ray-size 8 "
        "--max-spp 2 --reference-spp 2 --builds 1 --passes 1 --out out --job-timeout " +
        std::to_string(2 * kSlowdown);
    const Result r = w.run("tradeoff", args);
    EXPECT_EQ(r.exitCode, 3) << r.output;
    EXPECT_NE(r.output.find("tradeoff: 2 of 4 configurations measured failed"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("  mesh hanging: failed: " + timedOut(2) + "\n"), std::string::npos) << r.output;

    const std::string md = w.read("out/tradeoff.md");
    EXPECT_TRUE(std::regex_search(md, std::regex(R"(\| mesh \| crashing \| failed: crashed: SIGSEGV \(Segmentation )"
                                                 R"(fault\) in plugin .*crashing.so, accelerator 'crashing': )")))
        << md;
    EXPECT_NE(md.find("| mesh | hanging | failed: " + timedOut(2) + " | n/a | n/a | n/a | n/a | n/a | n/a |\n"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| mesh | sahbvh-K4 | "), std::string::npos) << md;
    EXPECT_NE(md.find("| embree | 1 | "), std::string::npos) << "the summary counts the scenes measured:\n" << md;
    EXPECT_EQ(md.find("\n| hanging | "), std::string::npos) << "a failed configuration has no summary row:\n" << md;

    const std::string csv = w.read("out/tradeoff.csv");
    EXPECT_NE(csv.find(",pixels_differing_1spp,failed\n"), std::string::npos) << csv;
    EXPECT_EQ(lineOf(csv, "mesh,hanging,hanging,"),
              "mesh,hanging,hanging" + std::string(commasAfterAccel(csv), ',') + timedOut(2))
        << csv;
    EXPECT_NE(lineOf(csv, "mesh,crashing,crashing,").find(",\"crashed: SIGSEGV"), std::string::npos) << csv;
    EXPECT_NE(csv.find("mesh,sahbvh-K4,sahbvh,4,4,1,"), std::string::npos) << csv;
    const nlohmann::json stored = nlohmann::json::parse(w.read("out/mesh/hanging.json"));
    EXPECT_EQ(stored["failed"], timedOut(2));
    EXPECT_TRUE(w.tmpIsEmpty()) << "a job's result file is left behind";
    expectPlotsOf(w, "out");

    // The next run keeps what was measured and measures the failed ones again.
    const Result again = w.run("tradeoff", args);
    EXPECT_EQ(again.exitCode, 3) << again.output;
    EXPECT_NE(again.output.find("2 configurations measured, 2 kept from an earlier run"), std::string::npos)
        << again.output;
    EXPECT_NE(again.output.find("  mesh hanging: failed: " + timedOut(2) + "\n"), std::string::npos) << again.output;
}

TEST(FailedJobs, TradeoffBuildersGivesFailedRowsBesideTheParetoFrontAndCorrelations) {
    const JobWorkspace w("builders");
    // Forty overlapping triangles: trees whose EPO is not 0, which the rank correlations need.
    std::ofstream soup(w.dir / "soup.obj");
    for (int t = 0; t < 40; ++t)
        soup << fmt::format("v {} {} {}\nv {} {} {}\nv {} {} {}\n", t % 7 * 0.6, t % 5 * 0.7, t % 3 * 0.9,
                            t % 7 * 0.6 + 1.1, t % 5 * 0.7 + 0.3, t % 3 * 0.9 - 0.4, t % 7 * 0.6 - 0.2,
                            t % 5 * 0.7 + 1.2, t % 3 * 0.9 + 0.5);
    for (int t = 0; t < 40; ++t) soup << fmt::format("f {} {} {}\n", 3 * t + 1, 3 * t + 2, 3 * t + 3);
    soup.close();
    const Result r =
        w.run("tradeoff", fmt::format("--builders --quick --scenes soup.obj --accel crashing,hanging,sahbvh,sweepbvh "
                                      "--ray-size 8 --builds 1 --passes 1 --job-timeout {} --out out",
                                      2 * kSlowdown));
    EXPECT_EQ(r.exitCode, 3) << r.output;
    EXPECT_NE(r.output.find("tradeoff: 2 of 8 configurations measured failed"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("  soup hanging: failed: " + timedOut(2) + "\n"), std::string::npos) << r.output;

    const std::string md = w.read("out/builders.md");
    EXPECT_NE(md.find("| soup | hanging | failed: " + timedOut(2) + " | | | | | | | | | |\n"), std::string::npos) << md;
    EXPECT_NE(md.find("| soup | crashing | failed: crashed: SIGSEGV"), std::string::npos) << md;
    EXPECT_NE(md.find("| soup | embree-medium | "), std::string::npos) << md;
    EXPECT_TRUE(std::regex_search(md, std::regex(R"(\| soup \| binary \| 3 \| [-+][0-9.]+ / )")))
        << "the rank correlation of the three builders measured:\n"
        << md;

    const std::string csv = w.read("out/builders.csv");
    EXPECT_NE(csv.find(",pareto_incoherent,failed\n"), std::string::npos) << csv;
    EXPECT_EQ(lineOf(csv, "soup,hanging,hanging,"),
              "soup,hanging,hanging" + std::string(commasAfterAccel(csv), ',') + timedOut(2))
        << csv;
    EXPECT_EQ(w.read("out/builders_summary.csv").find("hanging"), std::string::npos) << "no summary of a failed one";
    expectPlotsOf(w, "out");
}

TEST(FailedJobs, ABuildThatRunsLongSaysSo) {
    const JobWorkspace w("render");
    // render has no time-out: a user sees the build running, and ends it.
    const Result r = w.run("render", "--scene mesh.obj -DASDS::type=hanging --out out/render",
                           fmt::format("& pid=$!; sleep {}; kill -9 $pid; wait $pid; true", 2 + 2 * kSlowdown));
    EXPECT_NE(r.output.find("hanging on mesh: still building after 2s"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace bvhlab::test
