// Scene::frame: render, raycast and rays read an animated scene at the frame it names, with its
// camera then; a frame past the last is an error naming the range, and a still scene ignores
// the key with a warning. The scene moves a triangle out of view and the camera back.
#include "framework/io/image_io.h"
#include "framework/io/ray_file.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

#include <fmt/core.h>
#include <gtest/gtest.h>

#include <fstream>

namespace bvhlab {
namespace {

// tests/support/moving_scene.aff: triangle 1 covers the view's centre at z = 0 at frame 0 and is
// out of view at frame 2, where the static triangle 0 at z = -10 is seen; the eye moves from
// z = 10 to z = 15.
std::filesystem::path movingSceneFile() {
    return std::filesystem::path(test::sourceTree()) / "tests/support/moving_scene.aff";
}

std::string withFrame(const std::string& command, int frame) {
    return fmt::format("{} --no-global-env --threads 1 --scene {} -DScene::frame={}", command,
                       movingSceneFile().string(), frame);
}

TEST(SceneFrame, RenderSeesTheFramesGeometryFromTheFramesCamera) {
    const std::filesystem::path out = test::scratchDir("scene_frame") / "render";
    for (const auto& [frame, depth] : {std::pair{0, 10.0f}, std::pair{2, 25.0f}}) {
        SCOPED_TRACE(frame);
        const test::Result r = test::run(withFrame("render", frame) + " -DOutput::png=false --out " + out.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        int width = 0, height = 0;
        const std::vector<float> depths = readExrChannel(out.string() + ".exr", "Z", width, height);
        ASSERT_EQ(width, 16);
        EXPECT_NEAR(depths[size_t(8 * width + 8)], depth, 0.2f);
    }
}

TEST(SceneFrame, RaycastAnswersForTheFramesGeometry) {
    const std::filesystem::path dir = test::scratchDir("scene_frame");
    writeRayFile(dir / "down.rays", {Ray{.org = Vec3(1, -1, 10), .dir = Vec3(0, 0, -1)}});
    for (const auto& [frame, primitive, t] : {std::tuple{0, 1u, 10.0f}, std::tuple{2, 0u, 20.0f}}) {
        SCOPED_TRACE(frame);
        const test::Result r = test::run(withFrame("raycast", frame) + " --rays " + (dir / "down.rays").string() +
                                         " --out " + (dir / "down.hits").string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        const std::vector<Hit> hits = readHitFile(dir / "down.hits");
        ASSERT_EQ(hits.size(), 1u);
        EXPECT_EQ(hits[0].primitive, primitive);
        EXPECT_NEAR(hits[0].t, t, 1e-4f);
    }
}

TEST(SceneFrame, RaysLeaveTheFramesCamera) {
    const std::filesystem::path rays = test::scratchDir("scene_frame") / "primary.rays";
    for (const auto& [frame, eyeZ] : {std::pair{0, 10.0f}, std::pair{2, 15.0f}}) {
        SCOPED_TRACE(frame);
        const test::Result r = test::run(withFrame("rays", frame) + " --kind primary --out " + rays.string());
        ASSERT_EQ(r.exitCode, 0) << r.output;
        const std::vector<Ray> read = readRayFile(rays);
        ASSERT_FALSE(read.empty());
        EXPECT_FLOAT_EQ(read.front().org.z, eyeZ);
    }
}

TEST(SceneFrame, AFramePastTheLastIsAnErrorAndAStillSceneIgnoresIt) {
    const std::filesystem::path dir = test::scratchDir("scene_frame");
    const test::Result past = test::run(withFrame("rays", 3) + " --out " + (dir / "x.rays").string());
    EXPECT_NE(past.exitCode, 0);
    EXPECT_NE(past.output.find("Scene::frame 3 (from -DScene::frame): moving_scene.aff has 3 frames, 0 to 2"),
              std::string::npos)
        << past.output;

    std::ofstream(dir / "still.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const test::Result still = test::run(fmt::format("rays --no-global-env --scene {} -DScene::frame=2 --out {}",
                                                     (dir / "still.obj").string(), (dir / "x.rays").string()));
    EXPECT_EQ(still.exitCode, 0) << still.output;
    EXPECT_NE(still.output.find("warning: Scene::frame 2 (from -DScene::frame) ignored: still is a still scene"),
              std::string::npos)
        << still.output;
}

}  // namespace
}  // namespace bvhlab
