// `bvhlab batch` end to end on two tiny generated scenes: the tables, images and contact sheet
// are written; a second run reads the scenes from the cache; two shards merged give the table
// of one run (timings aside); a corrupt cache entry is ignored; bad --shard values are errors;
// a folder holds one batch (another is refused, the same one resumed), and its tables count and
// order what they show; a scene's heat maps share one scale; two shards racing on one scene
// through a shared cache holding a half-written entry each get the whole scene; the tables say
// what ran (each structure's own settings, its plugin, an unoptimised mark) and a -D key that no
// chosen structure reads is a warning.
#include "framework/io/image_io.h"
#include "tests/support/batch_results.h"
#include "tests/support/batch_scenes.h"
#include "tests/support/cli_run.h"
#include "tests/support/scan_plugin.h"
#include "tests/support/test_paths.h"
#include "tests/support/text_count.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

using namespace bvhlab;
using test::batchArgs;
using test::csvWithoutTimings;
using test::makeScenes;
using test::makeSolidScenes;
using test::readJson;
using test::readText;
using test::Result;
using test::run;

namespace fs = std::filesystem;

TEST(Batch, RunWritesTablesImagesAndContactSheet) {
    const fs::path dir = makeScenes("run");
    const Result r = run(batchArgs(dir, "out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const fs::path out = dir / "out";
    for (const char* file : {"results.md", "results.csv", "results.json", "contact_sheet.png"})
        EXPECT_TRUE(fs::exists(out / file)) << file;
    for (const char* job : {"first__naive", "first__sahbvh", "second__naive", "second__sahbvh"}) {
        EXPECT_TRUE(fs::exists(out / "jobs" / (std::string(job) + ".json"))) << job;
        for (const char* suffix : {".png", ".exr", "_shadows.png", "_shadows.exr"})
            EXPECT_TRUE(fs::exists(out / "images" / (job + std::string(suffix)))) << job << suffix;
    }
    // Progress off a terminal: a line per phase of every job.
    EXPECT_NE(r.output.find("[job 4/4] second sahbvh: rendering with shadows\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("2 read from the cache, 2 parsed"), std::string::npos) << r.output;

    // Markdown: the report's layout, two rows per job, in scene then accelerator order.
    const std::string md = readText(out / "results.md");
    EXPECT_NE(md.find("| #Prims | #Leaves | #Nodes | SAH | T_B [ms] | T_R [µs] | N_IT | N_TR | N_Q | render [ms] |"),
              std::string::npos)
        << md;
    EXPECT_EQ(test::occurrences(md, "| + shadows |"), 4u) << md;
    EXPECT_LT(md.find("| first | naive |"), md.find("| first | sahbvh |"));
    EXPECT_LT(md.find("| first | sahbvh |"), md.find("| second | naive |"));
    EXPECT_NE(r.output.find("| second | sahbvh |"), std::string::npos) << r.output;  // the table on stdout

    // CSV: header and two rows per job.
    const auto csv = csvWithoutTimings(out / "results.csv");
    ASSERT_EQ(csv.size(), 9u);
    EXPECT_EQ(csv[0],
              (std::vector<std::string>{"scene", "accel", "shadows", "prims", "leaves", "nodes", "sah", "n_it", "n_tr",
                                        "n_q", "settings", "plugin", "plugin_crc32", "plugin_optimized", "failed"}));
    EXPECT_EQ(csv[1][0], "first");
    EXPECT_EQ(csv[1][2], "false");
    EXPECT_EQ(csv[2][2], "true");
    EXPECT_EQ(csv[1][3], "6");  // triangles of the first scene
    EXPECT_EQ(csv[5][3], "8");

    // JSON: primary and shadow kept apart; the "+ shadows" row counts both.
    std::ifstream in(out / "results.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_EQ(j["rows"].size(), 8u);
    ASSERT_EQ(j["jobs"].size(), 4u);
    const nlohmann::json& job = j["jobs"][0];
    EXPECT_EQ(job["no_shadows"]["shadow"]["queries"], 0);
    EXPECT_EQ(job["no_shadows"]["primary"]["queries"], 24 * 18);
    const uint64_t primary = job["shadows"]["primary"]["queries"], shadow = job["shadows"]["shadow"]["queries"];
    EXPECT_GT(shadow, 0u);
    EXPECT_EQ(j["rows"][1]["n_q"].get<uint64_t>(), primary + shadow);
    EXPECT_EQ(j["rows"][0]["n_q"].get<uint64_t>(), 24u * 18u);
    // The row without shadows has its figures: the untraced shadow rays add no weight.
    for (const char* figure : {"t_r_us", "n_it", "n_tr"}) EXPECT_TRUE(j["rows"][0][figure].is_number()) << figure;

    // The job file: provenance, env, the cache flag and both renders of one build. Each job loads
    // its scene in its own process: the scene's first job parses it, the next reads the cache.
    std::ifstream jobIn(out / "jobs" / "first__sahbvh.json");
    const nlohmann::json jobFile = nlohmann::json::parse(jobIn);
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(out / "jobs" / "first__naive.json"))["scene_from_cache"], false);
    EXPECT_EQ(jobFile["scene_from_cache"], true);
    EXPECT_EQ(jobFile["env"]["ASDS::type"]["value"], "sahbvh");
    EXPECT_EQ(jobFile["env"]["SetRayTracing::threads"]["value"], "1");  // Batch::threads by default
    EXPECT_TRUE(jobFile.contains("provenance"));
    EXPECT_EQ(jobFile["runs"]["no_shadows"]["build_ms"], jobFile["runs"]["shadows"]["build_ms"]);
}

TEST(Batch, SecondRunReadsScenesFromCache) {
    const fs::path dir = makeScenes("cache");
    const Result first = run(batchArgs(dir, "out1"));
    ASSERT_EQ(first.exitCode, 0) << first.output;
    const Result second = run(batchArgs(dir, "out2"));
    ASSERT_EQ(second.exitCode, 0) << second.output;
    EXPECT_EQ(test::occurrences(second.output, "read from cache"), 4u) << second.output;
    EXPECT_NE(second.output.find("4 read from the cache, 0 parsed"), std::string::npos) << second.output;
    EXPECT_NE(readText(dir / "out2" / "results.md").find("from the scene cache in 4 of them"), std::string::npos);
    std::ifstream in(dir / "out2" / "jobs" / "second__naive.json");
    EXPECT_EQ(nlohmann::json::parse(in)["scene_from_cache"], true);
    EXPECT_EQ(csvWithoutTimings(dir / "out1" / "results.csv"), csvWithoutTimings(dir / "out2" / "results.csv"));
}

TEST(Batch, TwoShardsMergedGiveTheTableOfOneRun) {
    const fs::path dir = makeScenes("shards");
    const Result whole = run(batchArgs(dir, "whole"));
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    for (const char* shard : {"0/2", "1/2"}) {
        const Result r = run(batchArgs(dir, std::string("shard") + shard[0]) + " --shard " + shard);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("runs 2 of them"), std::string::npos) << r.output;
    }
    // Every n-th job: shard 0 has jobs 0 and 2 (both naive), shard 1 jobs 1 and 3.
    EXPECT_TRUE(fs::exists(dir / "shard0" / "jobs" / "second__naive.json"));
    EXPECT_FALSE(fs::exists(dir / "shard0" / "jobs" / "first__sahbvh.json"));

    const Result merged = run("batch --merge " + (dir / "shard0").string() + " " + (dir / "shard1").string() +
                              " --out " + (dir / "merged").string());
    ASSERT_EQ(merged.exitCode, 0) << merged.output;
    EXPECT_EQ(csvWithoutTimings(dir / "merged" / "results.csv"), csvWithoutTimings(dir / "whole" / "results.csv"));
    // Each shard scaled the heat maps of its own accelerators: the merged table says so.
    EXPECT_NE(merged.output.find("the heat maps of first have different full scales"), std::string::npos)
        << merged.output;
    EXPECT_TRUE(fs::exists(dir / "merged" / "contact_sheet.png"));
    EXPECT_TRUE(fs::exists(dir / "merged" / "images" / "first__sahbvh_shadows.png"));

    const Result notBatch = run("batch --merge " + dir.string() + " --out " + (dir / "merged2").string());
    EXPECT_EQ(notBatch.exitCode, 1);
    EXPECT_NE(notBatch.output.find("no jobs/ folder"), std::string::npos) << notBatch.output;
}

TEST(Batch, CorruptCacheEntryIsIgnoredAndRewritten) {
    const fs::path dir = makeScenes("corrupt");
    ASSERT_EQ(run(batchArgs(dir, "out1")).exitCode, 0);
    std::vector<fs::path> entries;
    for (const auto& e : fs::directory_iterator(dir / "cache")) entries.push_back(e.path());
    ASSERT_EQ(entries.size(), 2u);
    std::sort(entries.begin(), entries.end());
    // One entry with a flipped byte in its payload, the other cut short.
    std::string bytes = readText(entries[0]);
    bytes[bytes.size() - 10] ^= 0x5a;
    std::ofstream(entries[0], std::ios::binary | std::ios::trunc) << bytes;
    fs::resize_file(entries[1], 100);

    const Result r = run(batchArgs(dir, "out2"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(test::occurrences(r.output, "ignored cache entry"), 2u) << r.output;
    EXPECT_NE(r.output.find("2 read from the cache, 2 parsed"), std::string::npos) << r.output;
    EXPECT_EQ(csvWithoutTimings(dir / "out1" / "results.csv"), csvWithoutTimings(dir / "out2" / "results.csv"));

    const Result again = run(batchArgs(dir, "out3"));  // rewritten: read from the cache now
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_NE(again.output.find("4 read from the cache, 0 parsed"), std::string::npos) << again.output;
}

TEST(Batch, TwoShardsRacingOnOneSceneNeverReadAHalfWrittenEntry) {
    // Two shards start at once on one scene (61k triangles, parsed for a while) with a shared
    // cache holding half of its entry, as a copy in progress leaves one: each either parses for
    // itself (the entry ignored, then written whole by a rename) or reads the other's whole entry.
    const fs::path dir = makeSolidScenes("race", 5);
    const std::string args = "batch --scenes " + (dir / "spheres.env").string() +
                             " --accel sahbvh,tdbvh -DCamera::width=32 -DCamera::height=24 -DScene::cacheDir=";
    const Result whole = run(args + (dir / "seed").string() + " --out " + (dir / "whole").string());
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    const fs::path entry = fs::directory_iterator(dir / "seed")->path();
    const std::string bytes = readText(entry);
    fs::create_directories(dir / "cache");
    std::ofstream(dir / "cache" / entry.filename(), std::ios::binary) << bytes.substr(0, bytes.size() / 2);

    std::string both;
    for (const char* shard : {"0", "1"})
        both += fmt::format("{} {}{} --shard {}/2 --out {} >{} 2>&1 & pids=\"$pids $!\"; ", test::bvhlabProgram(), args,
                            (dir / "cache").string(), shard, (dir / "shard").string() + shard,
                            (dir / "shard").string() + shard + ".log");
    const Result raced = test::runShell(both + "for pid in $pids; do wait $pid || exit 1; done");
    const std::string logs = readText(dir / "shard0.log") + readText(dir / "shard1.log");
    ASSERT_EQ(raced.exitCode, 0) << logs;
    for (const char* shard : {"shard0.log", "shard1.log"}) {
        const std::string log = readText(dir / shard);
        EXPECT_TRUE(log.find("read from cache") != std::string::npos ||
                    log.find("(truncated); parsing and rewriting it") != std::string::npos)
            << shard << ":\n"
            << log;
    }
    const Result merged = run("batch --merge " + (dir / "shard0").string() + " " + (dir / "shard1").string() +
                              " --out " + (dir / "merged").string());
    ASSERT_EQ(merged.exitCode, 0) << merged.output;
    EXPECT_EQ(csvWithoutTimings(dir / "merged" / "results.csv"), csvWithoutTimings(dir / "whole" / "results.csv"));

    // One whole entry is left, no temporary file beside it, and the next run reads it.
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(dir / "cache")) files.push_back(e.path().filename().string());
    EXPECT_EQ(files, std::vector<std::string>{entry.filename().string()});
    EXPECT_EQ(readText(dir / "cache" / entry.filename()), bytes);
    const Result again = run(args + (dir / "cache").string() + " --out " + (dir / "again").string());
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_NE(again.output.find("2 read from the cache, 0 parsed"), std::string::npos) << again.output;
}

TEST(Batch, BadArgumentsAreOneLineErrors) {
    const fs::path dir = makeScenes("bad");
    for (const char* shard : {"2", "2/2", "-1/2", "1/0", "a/b", "1/2x", "/2"}) {
        const Result r = run(batchArgs(dir, "out") + " --shard " + shard);
        EXPECT_EQ(r.exitCode, 1) << shard << ": " << r.output;
        EXPECT_NE(r.output.find("--shard " + std::string(shard) + ": expected i/n"), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    }
    Result r = run(batchArgs(dir, "out") + " --accel naive,bsptree");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("bsptree"), std::string::npos) << r.output;
    r = run(batchArgs(dir, "out") + " --shard 0/2 --merge " + (dir / "out").string());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_FALSE(fs::exists(dir / "out" / "jobs" / "first__naive.json"));  // nothing ran
}

TEST(Batch, FolderOfAnotherBatchIsRefusedWithWhatDiffers) {
    const fs::path dir = makeScenes("refuse");
    const fs::path out = dir / "out";
    const std::string first = batchArgs(dir, "out") + " -DCamera::width=16 -DCamera::height=12";
    ASSERT_EQ(run(first).exitCode, 0);
    const std::string table = readText(out / "results.md");

    // Another image size and other accelerators into the same folder: refused, naming both
    // settings and the ways out; nothing in the folder is touched.
    const std::string second = batchArgs(dir, "out") + " -DCamera::width=8 -DCamera::height=12 --accel sahbvh";
    const Result refused = run(second);
    EXPECT_EQ(refused.exitCode, 1) << refused.output;
    for (const char* what : {"holds 4 jobs of another batch", "Camera::width: 16 -> 8 (first, second)",
                             "--accel: naive,sahbvh -> sahbvh", "--fresh", "another --out"})
        EXPECT_NE(refused.output.find(what), std::string::npos) << what << "\n" << refused.output;
    EXPECT_EQ(refused.output.find("Camera::height"), std::string::npos) << refused.output;  // the same in both
    EXPECT_EQ(readText(out / "results.md"), table);

    // The same settings again: accepted (a resumed or repeated run), the table as before.
    const Result again = run(first);
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_EQ(csvWithoutTimings(out / "results.csv").size(), 9u);

    // --fresh: the old batch deleted, the new one alone in the tables.
    const Result fresh = run(second + " --fresh");
    ASSERT_EQ(fresh.exitCode, 0) << fresh.output;
    const std::string md = readText(out / "results.md");
    EXPECT_NE(md.find("# bvhlab batch: 2 scenes x 1 accelerators"), std::string::npos) << md;
    EXPECT_NE(md.find("Jobs: 2 ("), std::string::npos) << md;
    EXPECT_EQ(md.find("naive"), std::string::npos) << md;
    EXPECT_FALSE(fs::exists(out / "jobs" / "first__naive.json"));
    EXPECT_FALSE(fs::exists(out / "images" / "first__naive.png"));

    // A folder of jobs without recorded settings (an older bvhlab's) is refused as well.
    fs::remove(out / "batch.json");
    const Result unknown = run(second);
    EXPECT_EQ(unknown.exitCode, 1) << unknown.output;
    EXPECT_NE(unknown.output.find("no batch.json"), std::string::npos) << unknown.output;
}

TEST(Batch, ShardsOfDifferentBatchesAreNotMerged) {
    const fs::path dir = makeScenes("mergeguard");
    ASSERT_EQ(run(batchArgs(dir, "shard0") + " --shard 0/2 -DCamera::width=16").exitCode, 0);
    ASSERT_EQ(run(batchArgs(dir, "shard1") + " --shard 1/2 -DCamera::width=8").exitCode, 0);
    const Result r = run("batch --merge " + (dir / "shard0").string() + " " + (dir / "shard1").string() + " --out " +
                         (dir / "merged").string());
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("hold shards of different batches"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("Camera::width: 16 -> 8 (first, second)"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "merged" / "results.md"));

    // Nor is a shard merged into a folder holding another batch.
    const Result into = run("batch --merge " + (dir / "shard0").string() + " --out " + (dir / "shard1").string());
    EXPECT_EQ(into.exitCode, 1) << into.output;
    EXPECT_NE(into.output.find("holds 2 jobs of another batch"), std::string::npos) << into.output;
}

TEST(Batch, TablesAndContactSheetCountAndOrderWhatTheyShow) {
    const fs::path dir = makeScenes("counts");
    std::ofstream(dir / "reversed.list") << "second.env\nfirst.env\n";
    const std::string args = "batch --scenes " + (dir / "reversed.list").string() +
                             " --accel sahbvh,naive -DScene::cacheDir=" + (dir / "cache").string() + " --out ";
    ASSERT_EQ(run(args + (dir / "clean").string()).exitCode, 0);

    // A job file of another batch dropped into the folder (copied by hand): neither shown nor counted.
    ASSERT_EQ(run(batchArgs(dir, "other") + " --accel tdbvh -DCamera::width=12").exitCode, 0);
    ASSERT_EQ(run(args + (dir / "out").string()).exitCode, 0);
    fs::copy_file(dir / "other" / "jobs" / "first__tdbvh.json", dir / "out" / "jobs" / "first__tdbvh.json");
    for (const char* image : {"first__tdbvh.png", "first__tdbvh_shadows.png"})
        fs::copy_file(dir / "other" / "images" / image, dir / "out" / "images" / image);
    const Result r = run(args + (dir / "out").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("first__tdbvh.json: skipped: a job of another batch"), std::string::npos) << r.output;

    // Table order: the scene list's, then --accel's; the title and footer count the jobs shown.
    const std::string md = readText(dir / "out" / "results.md");
    EXPECT_EQ(md.find("| tdbvh |"), std::string::npos) << md;
    EXPECT_NE(md.find("# bvhlab batch: 2 scenes x 2 accelerators"), std::string::npos) << md;
    EXPECT_NE(md.find("Jobs: 4 ("), std::string::npos) << md;
    const size_t rows[] = {md.find("| second | sahbvh |"), md.find("| second | naive |"), md.find("| first | sahbvh |"),
                           md.find("| first | naive |")};
    for (size_t i = 0; i < 4; ++i) ASSERT_NE(rows[i], std::string::npos) << i << md;
    EXPECT_TRUE(std::is_sorted(std::begin(rows), std::end(rows))) << md;
    EXPECT_EQ(csvWithoutTimings(dir / "out" / "results.csv"), csvWithoutTimings(dir / "clean" / "results.csv"));

    // The contact sheet: a row per scene, two tiles per accelerator, as for the clean folder.
    const Rgb8Image sheet = readPng(dir / "out" / "contact_sheet.png"),
                    clean = readPng(dir / "clean" / "contact_sheet.png");
    EXPECT_EQ(sheet.width, 2 * 10 + 4 * 256 + 3 * 10);
    EXPECT_EQ(sheet.width, clean.width);
    EXPECT_EQ(sheet.height, clean.height);

    // A shard's folder: its jobs counted as part of the batch.
    ASSERT_EQ(run(args + (dir / "shard").string() + " --shard 0/2").exitCode, 0);
    const std::string shard = readText(dir / "shard" / "results.md");
    EXPECT_NE(shard.find("# bvhlab batch: 2 scenes x 1 accelerators"), std::string::npos) << shard;
    EXPECT_NE(shard.find("Jobs: 2 of the batch's 4 ("), std::string::npos) << shard;
}

TEST(Batch, HeatmapsOfASceneShareOneScale) {
    const fs::path dir = makeScenes("heatmaps");
    const Result r = run(batchArgs(dir, "out") + " --accel naive,sahbvh,embree -DOutput::heatmap=true");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("heat maps of first: none for embree"), std::string::npos) << r.output;
    for (const char* scene : {"first", "second"}) {
        // Without and with shadows, naive and sahbvh: one scale, the largest 99th percentile of them.
        std::vector<double> scales, percentiles;
        for (const char* accel : {"naive", "sahbvh"}) {
            const nlohmann::json job = readJson(dir / "out" / "jobs" / (std::string(scene) + "__" + accel + ".json"));
            for (const char* name : {"no_shadows", "shadows"}) {
                const nlohmann::json& heatmap = job["runs"][name]["heatmap"];
                scales.push_back(heatmap["scale"]), percentiles.push_back(heatmap["p99"]);
                EXPECT_NE(heatmap["scale_from"].get<std::string>().find("largest 99th percentile"), std::string::npos);
                EXPECT_TRUE(fs::exists(dir / "out" / heatmap["file"].get<std::string>())) << heatmap;
                EXPECT_EQ(job["runs"][name]["images"]["heatmap"], heatmap["file"]);
            }
        }
        EXPECT_EQ(std::count(scales.begin(), scales.end(), scales[0]), 4) << scene;
        EXPECT_EQ(scales[0], *std::max_element(percentiles.begin(), percentiles.end())) << scene;
        EXPECT_LT(*std::min_element(percentiles.begin(), percentiles.end()), scales[0]) << scene;  // naive is cheaper

        // Embree counts nothing: no heat map, and the job says why.
        const nlohmann::json embree = readJson(dir / "out" / "jobs" / (std::string(scene) + "__embree.json"));
        EXPECT_TRUE(embree["runs"]["shadows"]["heatmap"].contains("skipped")) << embree["runs"]["shadows"];
        EXPECT_FALSE(embree["runs"]["shadows"]["images"].contains("heatmap"));
        EXPECT_FALSE(fs::exists(dir / "out" / "images" / (std::string(scene) + "__embree.heatmap.png")));
    }

    // A fixed scale for every heat map.
    ASSERT_EQ(run(batchArgs(dir, "fixed") + " -DOutput::heatmap=true -DOutput::heatmapScale=30").exitCode, 0);
    const nlohmann::json job = readJson(dir / "fixed" / "jobs" / "second__sahbvh.json");
    EXPECT_EQ(job["runs"]["shadows"]["heatmap"]["scale"], 30.0);
    EXPECT_EQ(job["runs"]["shadows"]["heatmap"]["scale_from"], "Output::heatmapScale");
}

TEST(Batch, TablesSayWhatRan) {
    const fs::path dir = makeScenes("what_ran");
    const fs::path plugin = test::installScan(dir, 1);
    fs::copy_file(test::testPlugins() + "/scan-unoptimised/scan.so", plugin, fs::copy_options::overwrite_existing);
    const std::string args = "batch --scenes " + (dir / "scenes.list").string() + " --plugin " + plugin.string() +
                             " -DScene::cacheDir= -DBVH::maxLeaf=3 --out " + (dir / "out").string();
    // A key no chosen structure reads is said, naming the key and the structures.
    Result r = run(args + " --accel scan");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("warning: BVH::maxLeaf is read by none of the chosen structures (scan); it is ignored"),
              std::string::npos)
        << r.output;
    std::string md = readText(dir / "out" / "results.md");
    EXPECT_EQ(md.find("BVH::"), std::string::npos) << md;
    EXPECT_NE(md.find("- `scan`: Scan::passes=1; plugin scan.so, CRC-32 "), std::string::npos) << md;
    EXPECT_NE(md.find(", unoptimised\n"), std::string::npos) << md;
    EXPECT_NE(md.find("| first | scan (unoptimised) |"), std::string::npos) << md;
    const auto csv = csvWithoutTimings(dir / "out" / "results.csv");
    EXPECT_EQ(csv[1][10], "Scan::passes=1");
    EXPECT_EQ(csv[1][11], "scan.so");
    EXPECT_EQ(csv[1][13], "false");
    const nlohmann::json rows = readJson(dir / "out" / "results.json")["rows"];
    EXPECT_EQ(rows[0]["structure"]["plugin"]["file"], "scan.so");
    // Nor is it part of the batch's settings: another value is the same batch, its jobs kept.
    r = run(args + " --accel scan -DBVH::maxLeaf=5");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("batch: 2 jobs kept from an earlier run"), std::string::npos) << r.output;

    // With a structure that reads it, the key is shown for that structure alone.
    r = run(args + " --accel scan,sahbvh --fresh");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("is read by none"), std::string::npos) << r.output;
    md = readText(dir / "out" / "results.md");
    EXPECT_NE(md.find("- `sahbvh`: "), std::string::npos) << md;
    EXPECT_NE(md.find("BVH::maxLeaf=3"), std::string::npos) << md;
    EXPECT_NE(md.find("- `scan`: Scan::passes=1; plugin"), std::string::npos) << md;
}
