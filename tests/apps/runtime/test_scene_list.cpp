// How --scene and --scenes name scenes (apps/runtime/scene_choice.h, scene_list.h): a scene file
// takes the env file under env/scenes/ that names a file of its name, wherever it lives; a
// scene's name is its env file; --scenes is repeatable and comma-separated; labels become file
// names without ':' or '=' (apps/runtime/output_paths.h).
#include "apps/runtime/output_paths.h"
#include "apps/runtime/scene_choice.h"
#include "apps/runtime/scene_list.h"
#include "framework/config/install_paths.h"
#include "framework/core/error.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>

#include <fstream>

namespace bvhlab {
namespace {

namespace fs = std::filesystem;

fs::path writeQuad(const fs::path& file) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
    return file;
}

TEST(SceneList, ASceneFileTakesTheEnvFileNamingItsName) {
    const fs::path dir = test::scratchDir("scene_list");
    const EnvOptions options;
    EXPECT_EQ(sceneEnvFor(writeQuad(dir / "copy" / "a10.obj"), options), dataFile("env/scenes/a10.env"));
    EXPECT_EQ(sceneEnvFor(writeQuad(dir / "gz" / "munich.ply.gz"), options), dataFile("env/scenes/munich.env"));
    EXPECT_EQ(sceneEnvFor(writeQuad(dir / "quad.obj"), options), fs::path());
    // Not by a part of the name: a10.obj.bak is no a10.obj.
    EXPECT_EQ(sceneEnvFor(writeQuad(dir / "a10.obj.bak"), options), fs::path());
}

TEST(SceneList, ScenesTakeNamesFilesAndListsRepeatedOrCommaSeparated) {
    const fs::path dir = test::scratchDir("scene_list");
    const fs::path a10 = writeQuad(dir / "copy" / "a10.obj"), quad = writeQuad(dir / "quad.obj");
    const std::vector<SceneArgument> scenes =
        expandSceneList({"teapots", a10.string() + "," + quad.string(), dataFile("env/scenes/munich.env")}, {});
    ASSERT_EQ(scenes.size(), 4u);
    EXPECT_EQ(scenes[0].id, "teapots");
    EXPECT_EQ(scenes[0].envFile, dataFile("env/scenes/teapots.env"));
    EXPECT_TRUE(scenes[0].sceneFile.empty());
    EXPECT_EQ(scenes[1].id, "a10");
    EXPECT_EQ(scenes[1].envFile, dataFile("env/scenes/a10.env"));
    EXPECT_EQ(scenes[1].sceneFile, a10);
    EXPECT_EQ(scenes[2].id, "quad");
    EXPECT_TRUE(scenes[2].envFile.empty());
    EXPECT_EQ(scenes[3].id, "munich");

    EXPECT_THROW(expandSceneList({"no_such_scene"}, {}), InputError);
    EXPECT_THROW(expandSceneList({"teapots", "teapots"}, {}), InputError);  // two scenes of one id
}

TEST(SceneList, LabelsAsFileNamesHaveNoColonOrEquals) {
    EXPECT_EQ(labelAsFileName("sahbvh8"), "sahbvh8");
    EXPECT_EQ(labelAsFileName("sahbvh:BVH::bins=4"), "sahbvh_BVH__bins-4");
    EXPECT_EQ(labelAsFileName("grid:Grid::density=2.5:Grid::objects=-1"), "grid_Grid__density-2.5_Grid__objects--1");
    EXPECT_EQ(labelAsFileName("a b/c"), "a_b_c");
}

}  // namespace
}  // namespace bvhlab
