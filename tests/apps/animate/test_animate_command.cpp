// `bvhlab animate` end to end on a small moving scene: a row per contender and measured frame
// with its update, its traces and their counters; every checked answer agrees with Embree's or
// ties; a structure that cannot run a policy is skipped, not failed; bad frames and a still
// scene are refused by name.
#include "tests/support/cli_run.h"
#include "tests/support/json_file.h"
#include "tests/support/moving_scene.h"
#include "tests/support/scene_files.h"

#include <gtest/gtest.h>

namespace bvhlab::test {
namespace {

TEST(AnimateCommand, MeasuresEveryContenderAtEveryChosenFrame) {
    TempDir dir;
    const fs::path scene = dir.write("moving.aff", movingSceneText());
    const Result r =
        run(fmt::format("animate --scene {} --accel sahbvh8,embree:Embree::quality=refit,"
                        "embree:Embree::quality=low --policies refit,twolevel --frames 0:5:2 --rounds 1 "
                        "--check --threads 1 --quiet --out {}",
                        scene.string(), (dir.path() / "out").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json results = readJson(dir.path() / "out" / "animate.json");
    EXPECT_EQ(results["frames"], nlohmann::json({0, 2, 4}));
    ASSERT_EQ(results["contenders"].size(), 6u);
    size_t skipped = 0;
    for (const nlohmann::json& c : results["contenders"]) {
        SCOPED_TRACE(c["label"].get<std::string>());
        EXPECT_FALSE(c.contains("failed"));
        if (c.contains("skipped")) {  // Embree at low quality has no refit
            EXPECT_EQ(c["label"], "embree:Embree::quality=low/refit");
            ++skipped;
            continue;
        }
        ASSERT_EQ(c["rows"].size(), 3u);
        for (const nlohmann::json& row : c["rows"]) {
            EXPECT_GE(row["update_ms"].get<double>(), 0.0);
            EXPECT_GT(row["primary"]["rays"].get<size_t>(), 0u);
            EXPECT_GT(row["shadow"]["rays"].get<size_t>(), 0u);
            EXPECT_EQ(row["agreement"]["wrong"], 0) << row.dump();
            EXPECT_GT(row["agreement"]["checked"].get<size_t>(), 0u);
        }
        const bool ours = !c["embree"].get<bool>();
        EXPECT_EQ(c["rows"][1]["primary"]["n_it"].is_number(), ours);  // Embree counts nothing, its instances included
        EXPECT_EQ(c["rows"][1]["action"], c["policy"] == "twolevel" ? "move" : "refit");
    }
    EXPECT_EQ(skipped, 1u);
    EXPECT_TRUE(fs::exists(dir.path() / "out" / "animate.md"));
    EXPECT_TRUE(fs::exists(dir.path() / "out" / "frames.csv"));
}

TEST(AnimateCommand, AStructuresOwnPolicyWinsAndTheKeySetsTheOthers) {
    TempDir dir;
    const fs::path scene = dir.write("moving.aff", movingSceneText());
    const Result r =
        run(fmt::format("animate --scene {} --accel sahbvh:Animate::policy=rebuild,sahbvh8 "
                        "-DAnimate::policy=refit --frames 0:2 --rounds 1 --quiet --out {}",
                        scene.string(), (dir.path() / "out").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json results = readJson(dir.path() / "out" / "animate.json");
    ASSERT_EQ(results["contenders"].size(), 2u);
    EXPECT_EQ(results["contenders"][0]["label"], "sahbvh:Animate::policy=rebuild/rebuild");
    EXPECT_EQ(results["contenders"][1]["label"], "sahbvh8/refit");
    EXPECT_EQ(results["contenders"][1]["rows"][1]["action"], "refit");
}

TEST(AnimateCommand, AnimateFramesChoosesTheFramesWithoutTheOptionAndSceneFrameIsIgnored) {
    TempDir dir;
    const fs::path scene = dir.write("moving.aff", movingSceneText());
    const Result r =
        run(fmt::format("animate --scene {} --accel sahbvh --policies refit -DAnimate::frames=1:5:3 "
                        "-DScene::frame=2 --rounds 1 --quiet --out {}",
                        scene.string(), (dir.path() / "out").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readJson(dir.path() / "out" / "animate.json")["frames"], nlohmann::json({1, 4}));
    EXPECT_NE(r.output.find("Scene::frame 2 (from -DScene::frame) ignored"), std::string::npos) << r.output;
}

TEST(AnimateCommand, RefusesFramesOutsideTheAnimationAndStillScenes) {
    TempDir dir;
    const fs::path scene = dir.write("moving.aff", movingSceneText());
    Result r = run(
        fmt::format("animate --scene {} --frames 3:9 --quiet --out {}", scene.string(), (dir.path() / "a").string()));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("--frames 3:9: the scene has frames 0 to 4"), std::string::npos) << r.output;
    const fs::path still = dir.write("still.nff", "p 3\n0 0 0\n1 0 0\n0 1 0\n");
    r = run(fmt::format("animate --scene {} --quiet --out {}", still.string(), (dir.path() / "b").string()));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("not an animated scene"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace bvhlab::test
