// `bvhlab plot` (apps/plot/): it tells a bench or animate JSON file from a tradeoff, batch or
// animate folder, and the scripts draw their PNG files; a tradeoff run without the K series of sahbvh and without
// sweepbvh plots what it has. Skipped where Debian's matplotlib is missing (setup.sh installs it).
#include "tests/support/animate_results.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace bvhlab::test {
namespace {

namespace fs = std::filesystem;

bool haveMatplotlib() { return std::system("/usr/bin/python3 -c 'import matplotlib' 2>/dev/null") == 0; }

void expectPng(const fs::path& png) {
    ASSERT_TRUE(fs::exists(png)) << png;
    EXPECT_GT(fs::file_size(png), 1000u) << png;
}

TEST(Plot, DrawsABenchJsonFile) {
    if (!haveMatplotlib()) GTEST_SKIP() << "no python3-matplotlib for /usr/bin/python3";
    const fs::path dir = scratchDir("plot_bench");
    std::ofstream(dir / "tiny.env") << "Camera::width 8\nCamera::height 8\n";
    Result r = run("bench --quiet --scenes " + (dir / "tiny.env").string() +
                   " --accel sahbvh --queries single --threads 1 --builds 1 --passes 1 --out " +
                   (dir / "bench.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = run("plot " + (dir / "bench.json").string() + " --out " + (dir / "plots").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectPng(dir / "plots" / "bench.png");

    // A failed scene's row (its job crashed, threw or ran out of time) has nothing to draw.
    std::ifstream in(dir / "bench.json");
    nlohmann::json bench = nlohmann::json::parse(in);
    bench["rows"].push_back({{"scene", "crashed"}, {"failed", "crashed: SIGSEGV"}});
    std::ofstream(dir / "failed.json") << bench.dump();
    r = run("plot " + (dir / "failed.json").string() + " --out " + (dir / "plots").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectPng(dir / "plots" / "failed.png");
}

// Both ratios the tradeoff plot divides by are missing: sahbvh-K16 and sweepbvh. Two scenes of
// the run committed in docs/plots, tdbvh and embree only.
TEST(Plot, DrawsATradeoffFolderWithoutTheKSeriesOrSweepbvh) {
    if (!haveMatplotlib()) GTEST_SKIP() << "no python3-matplotlib for /usr/bin/python3";
    const fs::path docs = fs::path(sourceTree()) / "docs" / "plots";
    const fs::path dir = scratchDir("plot_tradeoff");
    fs::copy_file(docs / "image_error.csv", dir / "image_error.csv", fs::copy_options::overwrite_existing);
    std::ifstream in(docs / "tradeoff.csv");
    std::ofstream out(dir / "tradeoff.csv");
    std::string line;
    std::getline(in, line);
    out << line << "\n";
    while (std::getline(in, line))
        if ((line.starts_with("sibenik,") || line.starts_with("mount,")) &&
            (line.find(",tdbvh,") != std::string::npos || line.find(",embree,") != std::string::npos))
            out << line << "\n";
    out.close();
    const Result r = run("plot " + dir.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("Error"), std::string::npos) << r.output;
    for (const char* png : {"tradeoff_build_vs_gap.png", "tradeoff_time_to_image.png", "tradeoff_error_vs_time.png"})
        expectPng(dir / "plots" / png);
}

// A batch's results.csv as batch writes it, with a structure that counts nothing (n/a).
TEST(Plot, DrawsABatchFolder) {
    if (!haveMatplotlib()) GTEST_SKIP() << "no python3-matplotlib for /usr/bin/python3";
    const fs::path dir = scratchDir("plot_batch");
    std::ofstream(dir / "results.csv")
        << "scene,accel,shadows,prims,leaves,nodes,sah,t_b_ms,t_r_us,n_it,n_tr,n_q,render_ms\n"
           "cube,sahbvh,true,12,4,7,3.5,0.2,0.05,2.5,6.0,1.2,4.0\n"
           "cube,embree,true,12,,,,0.3,0.04,,,1.2,3.0\n";
    const Result r = run("plot " + dir.string() + " --out " + (dir / "pngs").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectPng(dir / "pngs" / "batch.png");
}

// animate's results file: as the folder animate wrote (plots into its plots/) and as the file
// (plots beside it); Embree's contenders report no SAH, and a failed one has nothing to draw.
TEST(Plot, DrawsAnAnimateFolderAndFile) {
    if (!haveMatplotlib()) GTEST_SKIP() << "no python3-matplotlib for /usr/bin/python3";
    const fs::path dir = scratchDir("plot_animate");
    std::ofstream(dir / "animate.json") << smallAnimateResults().dump();
    Result r = run("plot " + dir.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectPng(dir / "plots" / "animate_cost.png");
    expectPng(dir / "plots" / "animate_sah.png");

    nlohmann::json embreeOnly = smallAnimateResults();
    embreeOnly["contenders"].erase(0);  // sahbvh8/refit
    embreeOnly["contenders"].erase(0);  // sahbvh8/adaptive
    std::ofstream(dir / "embree.json") << embreeOnly.dump();
    r = run("plot " + (dir / "embree.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectPng(dir / "embree_cost.png");
    expectPng(dir / "embree_sah.png");  // saying that no contender reports its SAH
}

TEST(Plot, AFolderOfNoKnownOutputIsRefusedNamingWhatItLooksFor) {
    const fs::path dir = scratchDir("plot_nothing");
    const Result r = run("plot " + dir.string());
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find(dir.string() + ": holds no output that bvhlab plot draws: no tradeoff.csv (tradeoff)"),
              std::string::npos)
        << r.output;
}

}  // namespace
}  // namespace bvhlab::test
