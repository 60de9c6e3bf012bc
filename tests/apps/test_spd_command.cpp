// `bvhlab spd` end to end on a small NFF scene with a reference folder of its own, and the
// reader of Havran's published statistics on the shared files (skipped where absent).
#include "apps/spd/havran_reference.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace bvhlab {
namespace {

using test::run;

namespace fs = std::filesystem;

// Havran's layout in small: an invariants table and, per scene, tables of N_IT and N_TS.
constexpr const char* kGrids = R"(Invariants
                  balls    gears  lattice  mount   rings teapot  tetra    tree
PrimaryRay[-]        100      100      100    100     100    100     100     100
UsedIntPrimRay[-]     90       90       90     90      90     90      90      90

BALLS
 N_IT              30.5           20.25           40.0
 N_TS               5.0            6.0             7.0
)";
constexpr const char* kOctrees = R"(BALLS
 N_IT              19.0           18.0
 N_TS              11.0           12.0
)";

fs::path referenceFolder() {
    const fs::path dir = test::scratchDir("spd_reference");
    std::ofstream(dir / "havran_stats_grids.txt") << kGrids;
    std::ofstream(dir / "havran_stats_octrees.txt") << kOctrees;
    return dir;
}

TEST(HavranReference, InvariantsAndTheBestGridAndOctree) {
    const auto scenes = readHavranReference(referenceFolder());
    ASSERT_TRUE(scenes.count("balls"));
    const HavranScene& balls = scenes.at("balls");
    EXPECT_EQ(balls.invariants.at("PrimaryRay"), 100.0);
    EXPECT_EQ(balls.invariants.at("UsedIntPrimRay"), 90.0);
    ASSERT_TRUE(balls.bestGrid && balls.bestOctree);
    EXPECT_EQ(balls.bestGrid->nIt, 20.25);  // the column with the fewest N_IT, with its N_TS
    EXPECT_EQ(balls.bestGrid->nTs, 6.0);
    EXPECT_EQ(balls.bestOctree->nIt, 18.0);
    EXPECT_EQ(balls.bestOctree->nTs, 12.0);
    EXPECT_EQ(scenes.at("tree").invariants.at("PrimaryRay"), 100.0);
    EXPECT_FALSE(scenes.at("tree").bestGrid);
}

TEST(HavranReference, AMissingFileIsAnErrorNamingIt) {
    try {
        readHavranReference(test::scratchDir("spd_reference_missing"));
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("havran_stats_grids.txt"), std::string::npos) << e.what();
    }
}

TEST(HavranReference, ThePublishedFilesReadWhole) {
    const fs::path dir = fs::path(test::sourceTree()) / ".." / "shared" / "reference" / "spd";
    if (!fs::exists(dir)) GTEST_SKIP() << "no " << dir;
    const auto scenes = readHavranReference(dir);
    for (const char* name : {"balls", "mount", "rings", "teapot", "tetra", "tree"}) {
        ASSERT_TRUE(scenes.count(name)) << name;
        const HavranScene& s = scenes.at(name);
        for (const char* invariant : kHavranInvariants) EXPECT_TRUE(s.invariants.count(invariant)) << name << " " << invariant;
        // Every SPD image is 513 x 513 eye rays, and the summary rows add up.
        EXPECT_EQ(s.invariants.at("PrimaryRay"), 513.0 * 513.0) << name;
        EXPECT_EQ(s.invariants.at("AllRays"),
                  s.invariants.at("PrimaryRay") + s.invariants.at("ShadowRay") + s.invariants.at("SecondaryRay"))
            << name;
        EXPECT_TRUE(s.bestGrid && s.bestOctree) << name;
    }
}

TEST(SpdCommand, WritesTheComparisonForEveryAccelerator) {
    const fs::path dir = test::scratchDir("spd_command");
    const fs::path scene = dir / "balls.nff";
    std::ofstream(scene) << "v\nfrom 0 -6 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 8 8\n"
                            "l 4 -3 6\nl -4 -4 5\nf 1 0.75 0.33 0.8 0 100000 0 1\n"
                            "p 4\n12 12 -0.5\n-12 12 -0.5\n-12 -12 -0.5\n12 -12 -0.5\n"
                            "f 1 0.9 0.7 0.5 0.5 3.0827 0.5 1.3\ns 0 0 0.5 1\ns 1.5 0 0 0.4\nc 0 2 -0.5 0.3 0 2 1 0.1\n";
    const fs::path out = dir / "out";
    const auto r = run("spd " + scene.string() + " --accel naive,sahbvh8,embree --out " + out.string() +
                       " -DSpd::reference=" + referenceFolder().string() + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(out / "spd.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_EQ(j["scenes"].size(), 1u);
    const nlohmann::json& s = j["scenes"][0];
    ASSERT_EQ(s["accels"].size(), 3u);
    const nlohmann::json& naive = s["accels"][0]["invariants"];
    EXPECT_EQ(naive["PrimaryRay"], 81);
    EXPECT_GT(naive["SecondaryRay"].get<int>(), 0);  // the spheres reflect and refract
    EXPECT_GT(naive["UsedIntShadRay"].get<int>(), 0);
    for (size_t a = 1; a < 3; ++a) EXPECT_EQ(s["accels"][a]["invariants"], naive) << s["accels"][a]["accel"];
    EXPECT_TRUE(s["accels"][2]["n_it"].is_null());  // Embree has no counters
    EXPECT_GT(s["accels"][1]["n_it_sphere"].get<double>(), 0.0);
    EXPECT_GT(s["accels"][1]["n_it_cone"].get<double>(), 0.0);
    EXPECT_EQ(s["havran"]["invariants"]["PrimaryRay"], 100.0);
    std::ifstream md(out / "spd.md");
    const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("| PrimaryRay | 81 | 100 | -19.00 % |"), std::string::npos) << text;
    EXPECT_NE(text.find("Havran's best grid | 20.25 | 6.00"), std::string::npos) << text;
    EXPECT_TRUE(fs::exists(out / "balls.sahbvh8.png"));
}

}  // namespace
}  // namespace bvhlab
