// `bvhlab stress` end to end, tiny: tables on stdout, JSON in --out, every registered structure
// by default, an unknown one refused.
#include "accel/registry.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <set>

namespace bvhlab {
namespace {

TEST(StressCommand, WritesTablesAndJson) {
    const auto out = test::scratchDir("stress") / "stress.json";
    const test::Result r = test::run(
        "stress --rays 2000 --scenes cube --parts watertight,acne --acne-pixels 16 "
        "--accel naive,sahbvh,embree:Embree::robust=true --threads 1 --out " +
        out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("per million"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("stress: all checks passed"), std::string::npos) << r.output;
    std::ifstream in(out);
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_TRUE(j.contains("watertight"));
    size_t rows = 0;
    for (const auto& row : j["watertight"]) {
        ++rows;
        EXPECT_EQ(row["rays"], 2000);
        if (row["accel"] != "embree-robust") {
            EXPECT_EQ(row["leaks"], 0) << row.dump();
        }
        if (row["accel"] == "naive") {
            EXPECT_EQ(row["mesh"], "cube4") << "naive only on small meshes";
        }
    }
    EXPECT_EQ(rows, 5u);  // cube4: naive, sahbvh, embree-robust; cube64: sahbvh, embree-robust
    EXPECT_TRUE(j["failures"].empty());
    EXPECT_EQ(j["acne"].size(), 6u * 3u);  // 4 planes and 2 grounds, 3 accelerators

    // By default every registered structure is checked (Embree reported, not failed).
    const test::Result help = test::run("stress --help");
    for (const AcceleratorInfo& info : acceleratorInfos())
        EXPECT_NE(help.output.find(info.name + ","), std::string::npos) << info.name << " is not in\n" << help.output;

    const test::Result bad = test::run("stress --accel nosuch --out " + out.string());
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_NE(bad.output.find("unknown accelerator 'nosuch'"), std::string::npos) << bad.output;
}

// --scenes takes what the other commands' --scenes take, repeatable or comma-separated, beside
// the generated meshes; a scene that is not there is skipped, naming the key to set.
TEST(StressCommand, ScenesAreTakenAsTheOtherCommandsTakeThem) {
    const auto dir = test::scratchDir("stress_scenes");
    std::ofstream(dir / "tetra.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const auto out = dir / "stress.json";
    const test::Result r =
        test::run("stress --rays 500 --scenes cube --scenes " + (dir / "tetra.obj").string() +
                  ",teapots --parts watertight --accel sahbvh --threads 1 -DScene::dir=" + (dir / "nowhere").string() +
                  " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // teapots, a scene's name, is found (env/scenes/teapots.env) but its file is not in Scene::dir.
    EXPECT_NE(r.output.find("skipping: scene file teapots.obj (Scene::file, from "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("Scene::dir is " + (dir / "nowhere").string() + " (from -DScene::dir; set it with"),
              std::string::npos)
        << r.output;
    std::ifstream in(out);
    const nlohmann::json j = nlohmann::json::parse(in);
    std::set<std::string> meshes;
    for (const auto& row : j["watertight"]) meshes.insert(row["mesh"].get<std::string>());
    EXPECT_EQ(meshes, (std::set<std::string>{"cube4", "cube64", "tetra"}));
    // tetra.obj has no scene env: said in the JSON as on stderr.
    ASSERT_EQ(j["run"]["warnings"].size(), 1u) << j["run"].dump();
    EXPECT_NE(j["run"]["warnings"][0].get<std::string>().find("tetra.obj: no scene env file in"), std::string::npos);
}

// An animated scene file is read through its env, at Scene::frame: a frame past its last skips it,
// said why, and the run goes on.
TEST(StressCommand, AnAnimatedSceneIsTakenAtSceneFrame) {
    const auto dir = test::scratchDir("stress_frame");
    // A closed tetrahedron that travels along x over 5 frames.
    std::string tetra = "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 32 32\n";
    tetra += "x travel\n{\n";
    for (const char* face :
         {"0 0 0\n0 1 0\n1 0 0", "0 0 0\n1 0 0\n0 0 1", "0 0 0\n0 0 1\n0 1 0", "1 0 0\n0 1 0\n0 0 1"})
        tetra += std::string("p 3\n") + face + "\n";
    tetra += "}\na 0 4 5\nk travel\n{\n transl 4\n -1 0 0 0 0 0 0\n 0 0 0 0 0 0 0\n 4 3 0 0 0 0 0\n";
    tetra += " 5 3 0 0 0 0 0\n}\n";
    std::ofstream(dir / "tetra.aff") << tetra;
    const auto out = dir / "stress.json";
    const std::string command = "stress --rays 500 --scenes " + (dir / "tetra.aff").string() +
                                " --parts watertight --accel sahbvh --threads 1 --out " + out.string();

    test::Result r = test::run(command + " -DScene::frame=2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    {
        std::ifstream in(out);
        const nlohmann::json j = nlohmann::json::parse(in);
        ASSERT_EQ(j["watertight"].size(), 1u) << j.dump();
        EXPECT_EQ(j["watertight"][0]["mesh"], "tetra");
        EXPECT_EQ(j["watertight"][0]["leaks"], 0);
        EXPECT_FALSE(j.contains("skipped")) << j.dump();
    }

    r = test::run(command + " -DScene::frame=5");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string why = "Scene::frame 5 (from -DScene::frame): tetra.aff has 5 frames, 0 to 4";
    EXPECT_NE(r.output.find("skipping: " + why), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\nSKIP watertight: " + why + "\n"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("stress: all checks passed (Embree's leaks are reported only), 1 skipped"),
              std::string::npos)
        << r.output;
    std::ifstream in(out);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_TRUE(j["watertight"].empty()) << j.dump();
    ASSERT_EQ(j["skipped"].size(), 1u) << j.dump();
    EXPECT_EQ(j["skipped"][0], "watertight: " + why);
}

}  // namespace
}  // namespace bvhlab
