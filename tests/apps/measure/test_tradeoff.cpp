// `bvhlab tradeoff --quick` end to end on two small generated scenes (a triangle soup and a
// terrain, written as OBJ with env files into a temporary folder): the CSV files have a row per
// scene x configuration and per scene x sample count, sweepbvh's gap to itself is 0, no
// structure disagrees with Embree on the same rays, the image error falls with the sample
// count and is the same for every structure; a second run keeps every result, a missing one is
// measured again, and so is everything when the settings change or with --fresh; a rebuilt
// plugin is measured again.
#include "accel/registry.h"
#include "accel/verify/generated_scenes.h"
#include "apps/measure/builders.h"
#include "apps/measure/tradeoff.h"
#include "tests/support/batch_scenes.h"
#include "tests/support/cli_run.h"
#include "tests/support/json_file.h"
#include "tests/support/scan_plugin.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

using namespace bvhlab;

namespace {

namespace fs = std::filesystem;
using test::Result;
using test::run;

void writeObj(const Scene& scene, const fs::path& file) {
    std::ofstream out(file);
    for (const Vec3& p : scene.positions) out << fmt::format("v {} {} {}\n", p.x, p.y, p.z);
    for (const auto& f : scene.indices) out << fmt::format("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
}

// A fresh folder with soup.obj/.env and terrain.obj/.env (the camera frames each scene).
fs::path makeScenes() {
    const fs::path dir = test::scratchDir("tradeoff");
    fs::remove_all(dir);
    fs::create_directories(dir);
    writeObj(verify::makeSoupScene(1500, 7, 0.2f, 3.0f, 20.0f), dir / "soup.obj");
    writeObj(verify::makeTerrainScene(24, 3), dir / "terrain.obj");
    for (const char* id : {"soup", "terrain"})
        std::ofstream(dir / (std::string(id) + ".env")) << "Scene::file " << id << ".obj\nScene::dir .\n";
    return dir;
}

// The K series beside tdbvh and sweepbvh unless `extra` names the structures.
std::string args(const fs::path& dir, const std::string& extra = "") {
    const std::string accels = extra.find("--accel") == std::string::npos ? " --accel tdbvh,sahbvh,sweepbvh" : "";
    return "tradeoff --quick --scenes " + (dir / "soup.env").string() + " " + (dir / "terrain.env").string() +
           " --size 40 --ray-size 48 -DScene::cacheDir= --out " + (dir / "out").string() + accels + " " + extra;
}

// A CSV file as one map per row, keyed by the header's names.
std::vector<std::map<std::string, std::string>> readCsv(const fs::path& file) {
    std::ifstream in(file);
    std::vector<std::map<std::string, std::string>> rows;
    std::vector<std::string> header;
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> cells;
        std::stringstream fields(line);
        for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
        if (line.back() == ',') cells.push_back("");
        if (header.empty()) {
            header = cells;
            continue;
        }
        EXPECT_EQ(cells.size(), header.size()) << line;
        std::map<std::string, std::string> row;
        for (size_t i = 0; i < std::min(cells.size(), header.size()); ++i) row[header[i]] = cells[i];
        rows.push_back(row);
    }
    return rows;
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

}  // namespace

TEST(Tradeoff, QuickRunWritesRowsAndResumes) {
    const fs::path dir = makeScenes();
    Result r = run(args(dir));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "12 configurations measured, 0 kept")) << r.output;
    const fs::path out = dir / "out";
    for (const char* file :
         {"tradeoff.csv", "image_error.csv", "tradeoff.md", "soup/reference.exr", "terrain/reference.png"})
        EXPECT_TRUE(fs::exists(out / file)) << file;

    // tradeoff.csv: a row per scene x configuration, in order.
    const std::vector<std::string> configs = {"tdbvh", "sahbvh-K4", "sahbvh-K16", "sahbvh-K64", "sweepbvh", "embree"};
    const auto rows = readCsv(out / "tradeoff.csv");
    ASSERT_EQ(rows.size(), 12u);
    for (size_t i = 0; i < rows.size(); ++i) {
        const auto& row = rows[i];
        EXPECT_EQ(row.at("scene"), i < 6 ? "soup" : "terrain");
        EXPECT_EQ(row.at("config"), configs[i % 6]);
        EXPECT_TRUE(fs::exists(out / row.at("scene") / (row.at("config") + ".json"))) << row.at("config");
        // Every structure answers the same rays as Embree and makes Embree's image.
        EXPECT_EQ(row.at("mismatches_primary"), "0") << row.at("scene") << " " << row.at("config");
        EXPECT_EQ(row.at("mismatches_shadow"), "0") << row.at("scene") << " " << row.at("config");
        EXPECT_EQ(row.at("pixels_differing_1spp"), "0") << row.at("scene") << " " << row.at("config");
        EXPECT_EQ(row.at("max_spp"), "16");
        EXPECT_EQ(row.at("series_width"), "40");
        EXPECT_EQ(row.at("primary_rays"), "2304");  // 48 x 48
        EXPECT_GT(std::stod(row.at("time_to_image_max_ms")), std::stod(row.at("build_ms")));
        if (row.at("config") == "embree") {
            EXPECT_EQ(row.at("sah"), "");  // Embree's tree is not visible: no SAH, no gap
            EXPECT_EQ(row.at("sah_gap"), "");
        } else {
            EXPECT_GT(std::stod(row.at("sah")), 0.0);
            ASSERT_NE(row.at("sah_gap"), "");
        }
        // The SAH-greedy sweep is not globally optimal, so binning may beat it: only the
        // sweep's gap to itself is certain.
        if (row.at("config") == "sweepbvh") {
            EXPECT_EQ(std::stod(row.at("sah_gap")), 0.0);
        }
    }

    // image_error.csv: a row per scene x sample count; the error falls with the sample count
    // and is the same for every structure.
    const auto errors = readCsv(out / "image_error.csv");
    ASSERT_EQ(errors.size(), 10u);  // 1, 2, 4, 8, 16 spp
    for (size_t i = 0; i < errors.size(); ++i) {
        EXPECT_EQ(errors[i].at("spp"), std::to_string(1 << (i % 5)));
        EXPECT_LT(std::stod(errors[i].at("rmse_spread")), 1e-6) << i;
        for (const std::string& c : configs) EXPECT_GT(std::stod(errors[i].at("render_ms_" + c)), 0.0) << c;
    }
    for (size_t scene : {0, 5}) EXPECT_LT(std::stod(errors[scene + 4].at("rmse")), std::stod(errors[scene].at("rmse")));

    // Resume: everything kept; a missing result measured again; new settings or --fresh measure all.
    r = run(args(dir));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "0 configurations measured, 12 kept")) << r.output;
    EXPECT_FALSE(contains(r.output, "scene soup:")) << "a scene with nothing to measure is not loaded\n" << r.output;
    fs::remove(out / "terrain" / "sahbvh-K16.json");
    r = run(args(dir));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "1 configurations measured, 11 kept")) << r.output;
    EXPECT_TRUE(contains(r.output, "reference image read from")) << r.output;
    EXPECT_EQ(readCsv(out / "tradeoff.csv").size(), 12u);
    r = run(args(dir, "--passes 1"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "12 configurations measured, 0 kept")) << r.output;
    r = run(args(dir, "--passes 1 --fresh"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "12 configurations measured, 0 kept")) << r.output;
}

// Only batch uses the scene cache (docs/batch.md): tradeoff writes nothing outside --out.
TEST(Tradeoff, WritesNoSceneCache) {
    const fs::path dir = makeScenes();
    const Result r = run(args(dir, "--accel tdbvh --bins 4 -DScene::cacheDir=" + (dir / "cache").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FALSE(fs::exists(dir / "cache")) << r.output;
}

TEST(Tradeoff, BadBinsAreAnError) {
    const Result r = run("tradeoff --quick --bins 4,1 --out " + (test::scratchDir("tradeoff_bad")).string());
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_TRUE(contains(r.output, "--bins")) << r.output;
}

// Without --accel, both modes measure every registered structure of ours (a new one included),
// and Embree as the yardstick; a bare sahbvh is the K series.
TEST(Tradeoff, ByDefaultEveryStructureOfOursIsMeasured) {
    TradeoffSettings settings;
    settings.bins = {4, 16};
    const std::vector<AccelConfig> series = tradeoffConfigs(settings, "");
    const std::vector<AccelConfig> builders = builderConfigs("");
    const auto has = [](const std::vector<AccelConfig>& configs, const std::string& label) {
        return std::any_of(configs.begin(), configs.end(), [&](const AccelConfig& c) { return c.label == label; });
    };
    for (const AcceleratorInfo& info : acceleratorInfos()) {
        if (info.name == "naive" || info.name == "embree") continue;
        EXPECT_TRUE(has(builders, info.name)) << info.name;
        EXPECT_TRUE(info.name == "sahbvh" ? has(series, "sahbvh-K4") && has(series, "sahbvh-K16")
                                          : has(series, info.name))
            << info.name;
    }
    EXPECT_TRUE(has(series, "embree"));
    EXPECT_TRUE(has(builders, "embree-medium"));
    EXPECT_FALSE(has(series, "naive"));
}

// `tradeoff --builders --quick`: a row per scene x builder in builders.csv, the ratios to
// embree-medium are 1 for itself, Embree has no SAH or EPO and ours have both, the Pareto front
// is not empty, the report has the rank correlations, a second run keeps every result, and
// `bvhlab plot` draws from the folder.
TEST(Tradeoff, BuildersQuickRunWritesRowsAndResumes) {
    const fs::path dir = makeScenes();
    const std::string command =
        args(dir, "--builders --builds 1 --passes 1 --accel sahbvh,sahbvh8,sbvh,sbvh8,ploc,ploc8,tdbvh,sweepbvh");
    Result r = run(command);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "30 configurations measured, 0 kept")) << r.output;
    EXPECT_TRUE(contains(r.output, "Spearman")) << r.output;
    // What each configuration is: our builders with their BVH:: keys, Embree's qualities with Embree's.
    EXPECT_TRUE(contains(r.output, "- `sbvh`: BVH::allAxes=false, BVH::batchTraversal=auto, BVH::bins=16")) << r.output;
    EXPECT_TRUE(contains(r.output, "- `embree-high`: Embree::isa=auto, Embree::quality=high, Embree::robust=false"))
        << r.output;
    const fs::path out = dir / "out";
    const std::vector<std::string> configs = {"sahbvh",
                                              "sahbvh8",
                                              "sbvh",
                                              "sbvh8",
                                              "ploc",
                                              "ploc8",
                                              "tdbvh",
                                              "sweepbvh",
                                              "sahbvh+insertion",
                                              "sahbvh8+insertion",
                                              "ploc8+insertion",
                                              "tdbvh+insertion",
                                              "embree-low",
                                              "embree-medium",
                                              "embree-high"};
    const size_t n = configs.size();
    const auto rows = readCsv(out / "builders.csv");
    ASSERT_EQ(rows.size(), 2 * n);
    std::map<std::string, double> sah;  // scene/config
    int onFront = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
        const auto& row = rows[i];
        EXPECT_EQ(row.at("scene"), i < n ? "soup" : "terrain");
        EXPECT_EQ(row.at("config"), configs[i % n]);
        if (!row.at("sah").empty()) sah[row.at("scene") + "/" + row.at("config")] = std::stod(row.at("sah"));
        EXPECT_EQ(row.at("primary_rays"), "2304");  // 48 x 48
        const bool embree = row.at("config").starts_with("embree");
        EXPECT_EQ(row.at("sah").empty(), embree) << row.at("config");
        EXPECT_EQ(row.at("epo").empty(), embree) << row.at("config");
        for (const char* set : {"primary", "shadow", "incoherent"}) {
            EXPECT_GT(std::stod(row.at(fmt::format("t_r_{}_cpu_us", set))), 0.0);
            EXPECT_NE(row.at(fmt::format("ratio_embree_bare_{}", set)), "") << row.at("config") << " " << set;
            if (row.at("config") == "embree-medium") {
                EXPECT_EQ(row.at(fmt::format("ratio_embree_medium_{}", set)), "1.0000");
            }
            onFront += row.at(fmt::format("pareto_{}", set)) == "1";
        }
    }
    EXPECT_GE(onFront, 6);  // at least one per scene and ray set
    // The insertion pass never raises the SAH of the tree it follows.
    for (const char* scene : {"soup", "terrain"}) {
        for (const char* builder : {"sahbvh", "sahbvh8", "ploc8", "tdbvh"}) {
            const std::string plain = fmt::format("{}/{}", scene, builder);
            EXPECT_LE(sah.at(plain + "+insertion"), sah.at(plain)) << plain;
        }
    }
    EXPECT_EQ(readCsv(out / "builders_summary.csv").size(), n);

    r = run(command);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "0 configurations measured, 30 kept")) << r.output;

    // bvhlab plot draws both charts from that folder (where Debian's matplotlib is installed).
    if (std::system("/usr/bin/python3 -c 'import matplotlib' 2>/dev/null") != 0) return;
    r = run("plot " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* png : {"builders_pareto.png", "builders_pareto_scenes.png"})
        EXPECT_GT(fs::file_size(out / "plots" / png), 1000u) << png;
}

// bvhlab plot draws from a tradeoff folder into its plots/ subfolder, which it creates, and leaves
// the plots committed in docs/plots alone. Skipped where Debian's matplotlib is missing (setup.sh
// installs it).
TEST(TradeoffPlots, PlotWritesIntoTheDataFolderNotDocs) {
    if (std::system("/usr/bin/python3 -c 'import matplotlib' 2>/dev/null") != 0)
        GTEST_SKIP() << "no python3-matplotlib for /usr/bin/python3";
    const fs::path docs = fs::path(test::sourceTree()) / "docs" / "plots";
    const fs::path data = test::scratchDir("tradeoff_plots") / "data";
    fs::create_directories(data);
    for (const char* csv : {"tradeoff.csv", "image_error.csv"})
        fs::copy_file(docs / csv, data / csv, fs::copy_options::overwrite_existing);
    const auto committed = fs::last_write_time(docs / "tradeoff_build_vs_gap.png");
    const Result r = run("plot " + data.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* png : {"tradeoff_build_vs_gap.png", "tradeoff_time_to_image.png", "tradeoff_error_vs_time.png"})
        EXPECT_GT(fs::file_size(data / "plots" / png), 1000u) << png;
    EXPECT_EQ(fs::last_write_time(docs / "tradeoff_build_vs_gap.png"), committed);
}

// A rebuilt plugin (the scan plugin's two builds, copied in turn to one path) is measured again,
// Embree's result kept; so is a changed key of the plugin's. The tables say what scan is and
// leave out the columns it has no figure in.
TEST(TradeoffResume, ARebuiltPluginIsMeasuredAgain) {
    const fs::path dir = test::makeScenes("resume_tradeoff");
    const fs::path plugin = test::installScan(dir, 1);
    const std::string args = "tradeoff --quick --scenes " + (dir / "first.env").string() +
                             " --accel scan --size 8 --ray-size 8 --max-spp 2 --reference-spp 2 --builds 1 "
                             "--passes 1 -DScene::cacheDir= --plugin " +
                             plugin.string() + " --out " + (dir / "out").string();
    Result r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "2 configurations measured, 0 kept")) << r.output;
    // The tables: what scan is, and no column that is n/a in every row (no sweepbvh: no gap; no SAH).
    const std::string md = test::readText(dir / "out" / "tradeoff.md");
    EXPECT_TRUE(contains(md, "- `scan`: Scan::passes=1; plugin scan.so, CRC-32 ")) << md;
    EXPECT_TRUE(contains(md, "| scene | config | T_B [ms] | T_R primary [µs] |")) << md;
    EXPECT_FALSE(contains(md, "gap [%]") || contains(md, "gap mean")) << md;

    test::installScan(dir, 2);
    r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output,
                         "tradeoff: 1 configurations kept from an earlier run (same result key); 1 to "
                         "measure: 1 because plugin crc32: "))
        << r.output;
    EXPECT_TRUE(contains(r.output, "1 configurations measured, 1 kept")) << r.output;

    r = run(args + " -DScan::passes=2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "1 because structure Scan::passes: 1 -> 2")) << r.output;
}
