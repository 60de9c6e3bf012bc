// `bvhlab batch` with an animated scene beside a still one: the still scene is rendered as ever,
// the animated one is measured frame by frame (Animate::frames under Animate::policy) into a
// section of its own, animate's summary table, and every frame in animation_frames.csv; a rerun
// keeps its jobs; a frame range the scene lacks fails its jobs, not the batch; Batch::animate=false
// renders the animated scene at Scene::frame like a still one.
#include "tests/support/batch_scenes.h"
#include "tests/support/cli_run.h"
#include "tests/support/json_file.h"
#include "tests/support/moving_scene.h"
#include "tests/support/text_count.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace bvhlab::test {
namespace {

namespace fs = std::filesystem;

// makeScenes' folder with moving.aff beside first.obj.
fs::path makeMovingBesideStill(const std::string& name) {
    const fs::path dir = makeScenes(name);
    std::ofstream(dir / "moving.aff") << movingSceneText();
    return dir;
}

std::string batchOf(const fs::path& dir, const std::string& out, const std::string& more) {
    return fmt::format(
        "batch --scenes {},{} --accel sahbvh,embree:Embree::quality=refit -DScene::cacheDir={} "
        "--quiet --out {} {}",
        (dir / "first.env").string(), (dir / "moving.aff").string(), (dir / "cache").string(), (dir / out).string(),
        more);
}

TEST(BatchAnimation, AnAnimatedSceneBesideAStillOneIsMeasuredFrameByFrame) {
    const fs::path dir = makeMovingBesideStill("animation");
    const Result r = run(batchOf(dir, "out", "-DAnimate::frames=0:5:2"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const fs::path out = dir / "out";

    const std::string md = readText(out / "results.md");
    EXPECT_NE(md.find("| first | sahbvh |"), std::string::npos) << md;
    EXPECT_EQ(md.find("| moving |"), std::string::npos) << md;  // not a still row
    EXPECT_NE(md.find("## moving: an animation"), std::string::npos) << md;
    EXPECT_NE(md.find("3 frames measured of 5 (0 to 4)"), std::string::npos) << md;
    EXPECT_NE(md.find("| sahbvh | 3 |"), std::string::npos) << md;  // animate's row: the structure, its frames
    EXPECT_NE(md.find("| embree:Embree::quality=refit | 3 |"), std::string::npos) << md;

    for (const char* accel : {"sahbvh", "embree_Embree__quality-refit"}) {
        SCOPED_TRACE(accel);
        const nlohmann::json job = readJson(out / "jobs" / fmt::format("moving__{}.json", accel));
        EXPECT_TRUE(job["animated"].get<bool>());
        EXPECT_EQ(job["animation"]["frames"], nlohmann::json({0, 2, 4}));
        EXPECT_EQ(job["contender"]["policy"], "adaptive");  // Animate::policy's default
        ASSERT_EQ(job["contender"]["rows"].size(), 3u);
        EXPECT_EQ(job["contender"]["rows"][0]["action"], "build");
        for (const nlohmann::json& row : job["contender"]["rows"]) {
            EXPECT_GT(row["primary"]["rays"].get<size_t>(), 0u);
            EXPECT_GT(row["shadow"]["rays"].get<size_t>(), 0u);
        }
        EXPECT_FALSE(fs::exists(out / "images" / fmt::format("moving__{}.png", accel)));  // it renders no image
    }
    const nlohmann::json results = readJson(out / "results.json");
    ASSERT_EQ(results["animations"].size(), 1u);
    EXPECT_EQ(results["animations"][0]["contenders"].size(), 2u);
    EXPECT_EQ(results["jobs"].size(), 2u);  // the still scene's

    const std::string frames = readText(out / "animation_frames.csv");
    EXPECT_EQ(frames.rfind("scene,label,accel,policy,frame,", 0), 0u) << frames;
    EXPECT_EQ(occurrences(frames, "\nmoving,"), 6u) << frames;  // two structures, three frames

    // The same batch again keeps every job, the animated ones included.
    const Result again = run(batchOf(dir, "out", "-DAnimate::frames=0:5:2"));
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_NE(again.output.find("4 jobs kept from an earlier run"), std::string::npos) << again.output;
}

TEST(BatchAnimation, FramesTheSceneLacksFailItsJobsNotTheBatch) {
    const fs::path dir = makeMovingBesideStill("animation-frames");
    const Result r = run(batchOf(dir, "out", "-DAnimate::frames=3:9"));
    EXPECT_EQ(r.exitCode, 3) << r.output;  // some jobs failed, the tables are written
    const std::string md = readText(dir / "out" / "results.md");
    EXPECT_NE(md.find("| first | sahbvh |"), std::string::npos) << md;
    EXPECT_EQ(occurrences(md, "failed: Animate::frames 3:9: the scene has frames 0 to 4"), 2u) << md;
}

TEST(BatchAnimation, WithoutBatchAnimateTheSceneIsRenderedAtItsFrame) {
    const fs::path dir = makeMovingBesideStill("animation-still");
    const Result r = run(batchOf(dir, "out", "-DBatch::animate=false -DScene::frame=2"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string md = readText(dir / "out" / "results.md");
    EXPECT_NE(md.find("| moving | sahbvh |"), std::string::npos) << md;
    EXPECT_EQ(md.find("an animation"), std::string::npos) << md;
    EXPECT_TRUE(fs::exists(dir / "out" / "images" / "moving__sahbvh_shadows.png"));
    EXPECT_EQ(readJson(dir / "out" / "jobs" / "moving__sahbvh.json")["env"]["Scene::frame"]["value"], "2");
}

}  // namespace
}  // namespace bvhlab::test
