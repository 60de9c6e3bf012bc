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
constexpr const char* kOctrees = R"(Octree84-C
----------
                   maximum depth
scene:              4            5

BALLS
 N_IN              57          117
 N_V              400          820
 N_EV             300          570
 N_OIV           9171        10946
 N_IT              19.0           18.0
 N_TS              11.0           12.0
 N_ETS              9.93         15.39
 N_EETS             3.67          9.52
 N_B[s]             0.14          0.16

TREE
 N_IT             500.0          600.0
 N_TS              50.0           60.0

Octree comparison
-----------------
                                      Octree method
       ----------------------------------------
------     Octree84-C  Octree84-A
scene:

BALLS         md = 7      md = 5
 N_IT          19.0        18.0
 N_TS          11.0        12.0

TREE          md = 7      md = 7
 N_IT         400.0       450.0
 N_TS          40.0        45.0
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
    // The comparison table's rows are its scenes' ("TREE   md = 7 ..."), not the scene above it.
    ASSERT_TRUE(scenes.at("tree").bestOctree);
    EXPECT_EQ(scenes.at("tree").bestOctree->nIt, 400.0);
    EXPECT_EQ(scenes.at("tree").bestOctree->nTs, 40.0);
}

TEST(HavranReference, EveryTableByItsSectionRowsWithoutTheirUnits) {
    const auto scenes = readHavranReference(referenceFolder());
    const HavranTable& octree = scenes.at("balls").tables.at("Octree84-C");
    EXPECT_EQ(octree.at("N_IN"), (std::vector<double>{57.0, 117.0}));
    EXPECT_EQ(octree.at("N_EETS"), (std::vector<double>{3.67, 9.52}));
    EXPECT_EQ(octree.at("N_B"), (std::vector<double>{0.14, 0.16}));
    EXPECT_EQ(scenes.at("tree").tables.at("Octree comparison").at("N_IT"), (std::vector<double>{400.0, 450.0}));
    EXPECT_FALSE(scenes.at("tree").tables.at("Octree84-C").count("N_IN"));
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
        for (const char* invariant : kHavranInvariants)
            EXPECT_TRUE(s.invariants.count(invariant)) << name << " " << invariant;
        // Every SPD image is 513 x 513 eye rays, and the summary rows add up.
        EXPECT_EQ(s.invariants.at("PrimaryRay"), 513.0 * 513.0) << name;
        EXPECT_EQ(s.invariants.at("AllRays"),
                  s.invariants.at("PrimaryRay") + s.invariants.at("ShadowRay") + s.invariants.at("SecondaryRay"))
            << name;
        EXPECT_TRUE(s.bestGrid && s.bestOctree) << name;
        // His octree tables: four methods, the eight rows bvhlab measures at depths 4 to 7.
        for (const char* table : {"Octree84-C", "Octree84-A", "Octree89-C", "Octree93-C", "Octree93-A"})
            for (const char* row : kHavranOctreeRows)
                EXPECT_EQ(s.tables.at(table).at(row).size(), 4u) << table << " " << row;
    }
    // Figures of his, read where they are printed.
    const auto scenes2 = readHavranReference(dir);
    EXPECT_EQ(scenes2.at("tetra").tables.at("Octree84-C").at("N_OIV"),
              (std::vector<double>{13312.0, 32768.0, 110592.0, 512000.0}));
    EXPECT_EQ(scenes2.at("tree").tables.at("Octree93-A").at("N_IT")[3], 23.79);
    EXPECT_EQ(scenes2.at("tree").bestOctree->nIt, 23.79);  // Octree93-A at depth 7
}

TEST(SpdCommand, WritesTheComparisonForEveryAccelerator) {
    const fs::path dir = test::scratchDir("spd_command");
    const fs::path scene = dir / "balls.nff";
    std::ofstream(scene)
        << "v\nfrom 0 -6 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 8 8\n"
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

TEST(SpdCommand, AnOctreeBesideHavransColumnOfItsMethodAndDepth) {
    const fs::path dir = test::scratchDir("spd_octree");
    const fs::path scene = dir / "balls.nff";
    std::ofstream(scene) << "v\nfrom 0 -6 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 8 8\n"
                            "l 4 -3 6\nf 1 0.75 0.33 0.8 0 100000 0 1\n"
                            "p 4\n12 12 -0.5\n-12 12 -0.5\n-12 -12 -0.5\n12 -12 -0.5\ns 0 0 0.5 1\ns 1.5 0 0 0.4\n";
    const fs::path out = dir / "out";
    const auto r = run("spd " + scene.string() + " --accel octree:Octree::maxDepth=4,octree:Octree::maxDepth=9 --out " +
                       out.string() + " -DSpd::reference=" + referenceFolder().string() + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(out / "spd.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    const nlohmann::json& octree = j["scenes"][0]["accels"][0];
    EXPECT_EQ(octree["havran"]["table"], "Octree84-C");
    EXPECT_EQ(octree["havran"]["max_depth"], 4);
    EXPECT_EQ(octree["havran"]["values"]["N_OIV"], 9171.0);
    EXPECT_EQ(octree["havran"]["values"]["N_EETS"], 3.67);
    EXPECT_GT(octree["figures"]["N_ETS"]["value"].get<double>(), 0.0);  // per ray, after the trace
    EXPECT_TRUE(j["scenes"][0]["accels"][1]["havran"].is_null());       // depth 9: no column of his
    std::ifstream md(out / "spd.md");
    const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("| Havran's Octree84-C, depth 4 | 57 | 400 | 300 | 9171 | 19.00 | 11.00 | 9.93 | 3.67 | |"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("| octree:Octree::maxDepth=4 | "), std::string::npos) << text;
}

// Havran's tables not where Spd::reference points (an installed bvhlab's default): an error that
// names the folder and the key to set, before any scene is read.
TEST(SpdCommand, MissingReferenceNamesTheKeyToSet) {
    const fs::path dir = test::scratchDir("spd_no_reference"), nowhere = dir / "nowhere";
    const auto r = run("spd " + (dir / "none.nff").string() + " --out " + (dir / "out").string() +
                       " -DSpd::reference=" + nowhere.string());
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("Havran's statistics (havran_stats_grids.txt, havran_stats_octrees.txt): no folder " +
                            nowhere.string() + "; Spd::reference is " + nowhere.string() +
                            " (from -DSpd::reference; set it with -DSpd::reference=... or a line 'Spd::reference "
                            "...' in an env file)"),
              std::string::npos)
        << r.output;
}

}  // namespace
}  // namespace bvhlab
