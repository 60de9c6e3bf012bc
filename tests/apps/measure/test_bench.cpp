// `bvhlab bench` with one plugin's structure: its rows and what it is (its own settings, its
// plugin) lead the table, the reference rows are shown when asked; a rerun keeps each scene whose
// result key is the same as a whole (apps/measure/bench_resume.h), measures a scene it lacks, and
// measures again after the plugin is rebuilt.
#include "tests/support/batch_scenes.h"
#include "tests/support/cli_run.h"
#include "tests/support/scan_plugin.h"
#include "tests/support/text_count.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

using namespace bvhlab;
using test::Result;
using test::run;

namespace fs = std::filesystem;

namespace {

nlohmann::json readBench(const fs::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
}

size_t rowsOf(const nlohmann::json& bench, const std::string& sceneId) {
    size_t n = 0;
    for (const nlohmann::json& row : bench["rows"]) n += row["scene_id"] == sceneId;
    return n;
}

}  // namespace

TEST(Bench, APluginsRowsLeadAndRerunsKeepWholeScenes) {
    const fs::path dir = test::makeScenes("bench");
    test::installScan(dir, 1);
    const fs::path out = dir / "bench.json";
    const std::string args = "bench --scenes " + (dir / "first.env").string() + " " + (dir / "second.env").string() +
                             " --accel scan --plugin " + (dir / "plugins" / "scan.so").string() +
                             " --queries single --threads 1 --builds 1 --passes 1 --out " + out.string();
    Result r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("bench: 0 scenes kept from an earlier run (same result key); 2 to measure: 2 new"),
              std::string::npos)
        << r.output;
    // The table: scan's rows, what scan is, and where the reference rows are.
    EXPECT_EQ(test::occurrences(r.output, "  1 scan "), 2u) << r.output;  // a row per scene
    EXPECT_EQ(r.output.find("  1 nothing-guarded"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("  scan: Scan::passes=1; plugin scan.so, CRC-32 "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("the reference rows (embree, embree-robust, nothing, nothing-guarded, embree-bare) are in "
                            "the JSON; --reference-rows shows them here"),
              std::string::npos)
        << r.output;
    const nlohmann::json first = readBench(out);
    ASSERT_EQ(first["scenes"].size(), 2u);
    EXPECT_EQ(rowsOf(first, "first"), 6u);
    EXPECT_EQ(first["rows"][0]["structure"]["keys"]["Scan::passes"], "1");
    EXPECT_EQ(first["rows"][0]["structure"]["plugin"]["file"], "scan.so");

    // The same again: every scene kept; with --reference-rows the table shows them all.
    r = run(args + " --reference-rows");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("bench: 2 scenes kept from an earlier run (same result key); 0 to measure"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("  1 nothing-guarded"), std::string::npos) << r.output;
    EXPECT_EQ(readBench(out)["rows"], first["rows"]);

    // As if the run had stopped after the first scene: only the second is measured.
    nlohmann::json partial = first;
    partial["scenes"].erase(1);
    std::ofstream(out) << partial.dump();
    r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("bench: 1 scenes kept from an earlier run (same result key); 1 to measure: 1 new"),
              std::string::npos)
        << r.output;
    const nlohmann::json resumed = readBench(out);
    EXPECT_EQ(rowsOf(resumed, "first"), 6u);
    EXPECT_EQ(rowsOf(resumed, "second"), 6u);

    // A rebuilt plugin: every scene again, and why.
    test::installScan(dir, 2);
    r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("bench: 0 scenes kept from an earlier run (same result key); 2 to measure: 2 because "
                            "plugin crc32: "),
              std::string::npos)
        << r.output;
}
