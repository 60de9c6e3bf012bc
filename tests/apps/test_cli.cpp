// The bvhlab program end to end: render writes its files, raycast answers a ray file, and
// broken input gives a one-line error with file and line and a non-zero exit, never a crash.
#include "framework/core/cpu_levels.h"
#include "framework/io/ray_file.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <utility>

using namespace bvhlab;

namespace {

using test::Result;
using test::run;

std::filesystem::path cliScratchDir() { return test::scratchDir("cli"); }

// A file of `bytes` in the scratch folder: a scene, env or ray file a run reads.
std::filesystem::path scratchFile(const std::string& name, const std::string& bytes) {
    const auto path = cliScratchDir() / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// `bvhlab render ARGS`, its images (should it get that far) in a throwaway path: the runs that
// must fail.
Result renderToScratch(const std::string& args) {
    return run("render " + args + " --out " + (cliScratchDir() / "x").string());
}

}  // namespace

TEST(Cli, RenderWritesImagesAndStatistics) {
    const auto out = cliScratchDir() / "default";
    const Result r =
        run("render -DASDS::type=naive -DSetRayTracing::depthLimit=1 -DCamera::width=80 -DCamera::height=60 --out " +
            out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("N_IT"), std::string::npos) << r.output;
    for (const char* ext : {".exr", ".png", ".json"}) EXPECT_TRUE(std::filesystem::exists(out.string() + ext)) << ext;
    std::ifstream in(out.string() + ".json");
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const char* key :
         {"scene", "accel", "prims", "nodes", "leaves", "sah", "build_ms", "render_ms", "threads", "env", "provenance"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["accel"], "naive");
    EXPECT_EQ(j["primary"]["queries"], 80 * 60);
    EXPECT_GT(j["primary"]["n_it"].get<double>(), 0.0);
    EXPECT_EQ(j["env"]["ASDS::type"]["from"], "-DASDS::type");
}

TEST(Cli, BadEnvFileIsOneLineErrorWithFileAndLine) {
    const auto env = scratchFile("bad.env", "# ok\nSetRayTracing::cntSamples 1\nSetRayTracing::shadowz true\n");
    const Result r = renderToScratch("--env " + env.string());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("bad.env:3"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("SetRayTracing::shadows"), std::string::npos) << r.output;  // the suggestion
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST(Cli, BadValueAndUnknownAcceleratorAreErrors) {
    Result r = renderToScratch("-DSetRayTracing::cntSamples=0");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("cntSamples"), std::string::npos) << r.output;
    r = renderToScratch("-DASDS::type=bsptree");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("bsptree"), std::string::npos) << r.output;
}

TEST(Cli, BrokenSceneIsOneLineErrorWithFileAndLine) {
    const auto scene = scratchFile("broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
    const Result r = renderToScratch("-DASDS::type=naive --scene " + scene.string());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("broken.obj"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Segmentation"), std::string::npos) << r.output;
}

TEST(Cli, SceneWithNothingToRenderIsAnErrorNamingTheFile) {
    // Files that once rendered as an empty image with exit 0.
    const std::pair<const char*, std::string> files[] = {
        {"empty.obj", ""},
        {"flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"},
        {"binary.obj", std::string("\x7f"
                                   "ELF\x02\x01\x01\0\0\0",
                                   10)},
        {"notes.obj", "Not a scene, just notes.\n"},
        {"munich.obj", "ply\nformat binary_little_endian 1.0\nelement vertex 0\nend_header\n"},
        {"spheres.nff", "s 0 0 0 0\n"},  // a degenerate sphere only
    };
    for (const auto& [name, bytes] : files) {
        const auto scene = scratchFile(name, bytes);
        const Result r = renderToScratch("-DASDS::type=naive --scene " + scene.string());
        EXPECT_EQ(r.exitCode, 1) << name << ": " << r.output;
        EXPECT_NE(r.output.find("error: " + scene.string() + ": "), std::string::npos) << r.output;
    }
}

TEST(Cli, SpheresAndConesAreRenderedAndTheirDegenerateOnesCounted) {
    // balls.nff in small: a ground quad, three spheres (one of radius 0) and a cone.
    const auto scene = scratchFile("balls.nff",
                                   "p 4\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n"
                                   "s 0 0 1 0.5\ns 0 0 2 0\ns 0 0 3 0.5\nc 0 0 0 0.2 0 0 1 0.1\n");
    const auto out = cliScratchDir() / "balls";
    const Result r = run("render -DASDS::type=naive -DCamera::width=16 -DCamera::height=16 --scene " + scene.string() +
                         " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("degenerate, skipped: 0 triangles, 1 spheres, 0 cones/cylinders"), std::string::npos)
        << r.output;
    std::ifstream in(out.string() + ".json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["prims"], 6);
    EXPECT_EQ(j["degenerate"], 0);
    EXPECT_EQ(j["degenerate_spheres"], 1);
    EXPECT_EQ(j["degenerate_cones"], 0);
    // Naive tests every valid primitive per query: 2 triangles, 2 spheres, 1 cone.
    EXPECT_EQ(j["primary"]["n_it"], 5.0);
    EXPECT_EQ(j["primary"]["n_it_sphere"], 2.0);
    EXPECT_EQ(j["primary"]["n_it_cone"], 1.0);
}

TEST(Cli, RaycastAnswersRayFileWithNaive) {
    const auto scene = scratchFile("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
    const std::vector<Ray> rays = {{Vec3(0.5f, -0.5f, 5), Vec3(0, 0, -1), 0.0f, kInfinity},
                                   {Vec3(3, 3, 5), Vec3(0, 0, -1), 0.0f, kInfinity},
                                   {Vec3(0, 0, 5), Vec3(0, 0, -2), 0.0f, 1.0f}};
    const auto raysFile = cliScratchDir() / "rays.bin", hitsFile = cliScratchDir() / "hits.bin";
    writeRayFile(raysFile, rays);
    Result r = run("raycast -DASDS::type=naive --scene " + scene.string() + " --rays " + raysFile.string() + " --out " +
                   hitsFile.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("naive closest-hit queries: 3  T_R "), std::string::npos) << r.output;
    std::vector<Hit> hits = readHitFile(hitsFile);
    ASSERT_EQ(hits.size(), 3u);
    EXPECT_FLOAT_EQ(hits[0].t, 5.0f);
    EXPECT_EQ(hits[0].primitive, 0u);  // fan (1,2,3), (1,3,4): (0.5,-0.5) lies in the first
    EXPECT_EQ(hits[1].primitive, kInvalidPrimitive);
    EXPECT_EQ(hits[2].primitive, kInvalidPrimitive);  // tmax = 1 ends 3 units short (dir has length 2)

    r = run("raycast --any -DASDS::type=naive --scene " + scene.string() + " --rays " + raysFile.string() + " --out " +
            hitsFile.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    hits = readHitFile(hitsFile);
    EXPECT_EQ(hits[0].t, 0.0f);
    EXPECT_EQ(hits[0].primitive, 0u);
    EXPECT_EQ(hits[1].primitive, kInvalidPrimitive);
}

// `bvhlab rays` writes the bench's ray sets of a scene's camera and lights for raycast: the
// primary rays one per pixel, the shadow and incoherent rays from their hits, any-hit queries.
TEST(Cli, RaysWritesTheBenchRaySetsForRaycast) {
    const std::string tiny = " -DCamera::width=16 -DCamera::height=12 --out ";
    for (const std::string kind : {"primary", "shadow", "incoherent"}) {
        SCOPED_TRACE(kind);
        const auto file = cliScratchDir() / (kind + ".rays");
        Result r = run("rays --kind " + kind + tiny + file.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        const std::vector<Ray> rays = readRayFile(file);
        if (kind == "primary") {
            EXPECT_EQ(rays.size(), 16u * 12u);
        } else {
            EXPECT_GT(rays.size(), 0u);
        }
        for (const Ray& ray : rays) EXPECT_TRUE(ray.isValid());
        const auto hits = cliScratchDir() / (kind + ".hits");
        r = run("raycast --rays " + file.string() + (kind == "primary" ? "" : " --any") + " --out " + hits.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_EQ(readHitFile(hits).size(), rays.size());
    }
    const Result bad = run("rays --kind sideways --out " + (cliScratchDir() / "x.rays").string());
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.output.find("sideways"), std::string::npos) << bad.output;
}

// `bvhlab bench`, tiny: a row per structure and kind of query with every round kept; Embree's
// counters are unavailable (null), not zero; a paired ratio of a series to itself is exactly 1.
// Single rows are measured against embree-bare, batch rows against embree-batch, which names the
// Embree API it kept per ray set.
TEST(Cli, BenchMeasuresInRoundsWithPairedRatios) {
    const auto env = scratchFile("tiny.env", "Camera::width 24\nCamera::height 16\n");
    const auto out = cliScratchDir() / "bench.json";
    const Result r =
        run("bench --scenes " + env.string() +
            " --accel sahbvh,sahbvh:BVH::robust=false --threads 1 --builds 2 --passes 3 --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("geometric means"), std::string::npos) << r.output;
    std::ifstream in(out);
    const nlohmann::json j = nlohmann::json::parse(in);
    std::vector<std::string> labels;
    for (const nlohmann::json& row : j["rows"]) {
        const std::string accel = row["accel"], queries = row["queries"];
        labels.push_back(accel + " " + queries);
        EXPECT_EQ(row["build_ms_all"].size(), 2u) << accel;
        EXPECT_EQ(row["primary"]["t_r_us_all"].size(), 3u) << accel;
        EXPECT_EQ(row["primary"]["queries"], 24 * 16) << accel;
        EXPECT_EQ(row["primary"]["n_it"].is_null(), accel.starts_with("embree")) << accel;
        if (accel == "embree") {
            EXPECT_EQ(row["ratio_to_embree"]["primary"], 1.0);
        }
        // The rows of a query that does nothing count no work.
        if (accel.starts_with("nothing")) {
            EXPECT_EQ(row["primary"]["n_it"], 0.0) << accel;
        }
        // Every row has its ratios to Embree as its users call it, ray by ray and in batches.
        EXPECT_TRUE(row["ratio_to_embree-bare"]["shadow"].is_number()) << accel;
        EXPECT_TRUE(row["ratio_to_embree-batch"]["incoherent"].is_number()) << accel;
        if (accel == "embree-bare") {
            EXPECT_EQ(queries, "single");
            EXPECT_EQ(row["ratio_to_embree-bare"]["primary"], 1.0);
        }
        if (accel == "embree-batch") {
            EXPECT_EQ(queries, "batch");
            EXPECT_EQ(row["ratio_to_embree-batch"]["primary"], 1.0);
            for (const char* set : {"primary", "shadow", "incoherent"}) {
                const std::string api = row["embree_batch_api"][set];
                EXPECT_TRUE(api == "stream" || api == "packet8" || api == "packet16") << set << ": " << api;
                EXPECT_TRUE(row[set]["t_r_us_by_api"]["stream"].is_number()) << set;
                EXPECT_EQ(row[set]["t_r_us"], row[set]["t_r_us_by_api"][api]) << set;
            }
        } else {
            EXPECT_FALSE(row.contains("embree_batch_api")) << accel;
        }
    }
    EXPECT_EQ(labels, (std::vector<std::string>{"sahbvh single", "sahbvh:BVH::robust=false single", "embree single",
                                                "embree-robust single", "nothing single", "nothing-guarded single",
                                                "embree-bare single", "sahbvh batch", "sahbvh:BVH::robust=false batch",
                                                "embree batch", "embree-robust batch", "nothing batch",
                                                "nothing-guarded batch", "embree-batch batch"}));
    EXPECT_NE(r.output.find("embree-batch"), std::string::npos) << r.output;
}

// --isa-pairs avx2: on an AVX-512 CPU each structure and Embree's rows again at avx2, labelled
// LABEL@avx2 and measured against Embree's rows at avx2, beside the headline pair; on an AVX2
// CPU the headline pair is the AVX2 pair, said once and timed once. An ISA of neither key set is
// an error naming it.
TEST(Cli, BenchIsaPairsTimeTheAvx2PairBesideTheHeadline) {
    const auto env = scratchFile("tiny.env", "Camera::width 8\nCamera::height 8\n");
    const auto out = cliScratchDir() / "bench-isa.json";
    const Result r = run("bench --scenes " + env.string() +
                         " --accel sahbvh8 --isa-pairs avx2 --queries single "
                         "--threads 1 --builds 1 --passes 1 --out " +
                         out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(out);
    const nlohmann::json j = nlohmann::json::parse(in);
    std::vector<std::string> labels;
    for (const nlohmann::json& row : j["rows"]) labels.push_back(row["accel"]);
    if (!cpuLevels().v4) {
        EXPECT_NE(r.output.find("avx2 is this CPU's best ISA, so the headline pair is the avx2 pair (timed once)"),
                  std::string::npos)
            << r.output;
        EXPECT_EQ(labels, (std::vector<std::string>{"sahbvh8", "embree", "embree-robust", "nothing", "nothing-guarded",
                                                    "embree-bare"}));
        return;
    }
    EXPECT_EQ(labels, (std::vector<std::string>{"sahbvh8", "sahbvh8@avx2", "embree", "embree@avx2", "embree-robust",
                                                "embree-robust@avx2", "nothing", "nothing-guarded", "embree-bare",
                                                "embree-bare@avx2"}));
    for (const nlohmann::json& row : j["rows"]) {
        const std::string accel = row["accel"];
        const bool avx2 = accel.ends_with("@avx2");
        EXPECT_EQ(row["isa"], avx2 ? "avx2" : "best") << accel;
        // Each row's ratios are to Embree at its own ISA, and only to those.
        EXPECT_EQ(row.contains("ratio_to_embree-bare@avx2"), avx2) << accel;
        EXPECT_EQ(row.contains("ratio_to_embree-bare"), !avx2) << accel;
        EXPECT_EQ(row.contains("ratio_to_embree-robust@avx2"), avx2) << accel;
        if (accel == "embree-bare@avx2") {
            EXPECT_EQ(row["ratio_to_embree-bare@avx2"]["primary"], 1.0);
        }
        // What ran: 256-bit kernels in the AVX2 pair, 512-bit ones in the headline pair.
        if (accel.starts_with("sahbvh8") || accel.starts_with("embree")) {
            EXPECT_EQ(row["figures"]["kernel_bits"]["value"], avx2 ? 256 : 512) << accel;
        }
    }
    EXPECT_EQ(j["rows"][1]["structure"]["keys"]["BVH::isa"], "avx2");
    // The table: ours at both ISAs, and what the @avx2 rows are.
    EXPECT_NE(r.output.find("  1 sahbvh8@avx2 "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("rows LABEL@avx2: BVH::isa=avx2 or Embree::isa=avx2"), std::string::npos) << r.output;

    const Result bad =
        run("bench --scenes " + env.string() + " --accel sahbvh8 --isa-pairs sse2 --out " + out.string());
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.output.find("--isa-pairs sse2: 'sse2' is not avx2 or avx512"), std::string::npos) << bad.output;
}

// --quiet leaves the table and the file written, and drops the line per measured row.
TEST(Cli, BenchQuietPrintsNoProgress) {
    const auto env = scratchFile("tiny.env", "Camera::width 8\nCamera::height 8\n");
    const auto out = cliScratchDir() / "bench-quiet.json";
    const Result r = run("bench --quiet --scenes " + env.string() +
                         " --accel sahbvh --queries single --threads 1 --builds 1 --passes 1 --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("geometric means"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("sahbvh single: build"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(out));
}

// --queries single or batch alone measures that kind only (and its yardstick); a kind it does not
// know is an error naming it.
TEST(Cli, BenchQueriesChoosesTheKinds) {
    const auto env = scratchFile("tiny.env", "Camera::width 24\nCamera::height 16\n");
    const auto out = cliScratchDir() / "bench.json";
    for (const std::string kind : {"single", "batch"}) {
        const Result r = run("bench --scenes " + env.string() + " --accel sahbvh --queries " + kind +
                             " --threads 1 --builds 1 --passes 1 --out " + out.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        std::ifstream in(out);
        const nlohmann::json j = nlohmann::json::parse(in);
        std::vector<std::string> labels;
        for (const nlohmann::json& row : j["rows"]) {
            EXPECT_EQ(row["queries"], kind);
            labels.push_back(row["accel"]);
            EXPECT_EQ(row.contains("ratio_to_embree-bare"), kind == "single");
            EXPECT_EQ(row.contains("ratio_to_embree-batch"), kind == "batch");
        }
        EXPECT_EQ(labels, (std::vector<std::string>{"sahbvh", "embree", "embree-robust", "nothing", "nothing-guarded",
                                                    kind == "single" ? "embree-bare" : "embree-batch"}));
    }
    const Result bad =
        run("bench --scenes " + env.string() + " --accel sahbvh --queries single,packets --out " + out.string());
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.output.find("packets"), std::string::npos) << bad.output;
}
