// The public test scenes in ../shared/scenes (or $BVHLAB_SCENES_DIR) load with the triangle,
// sphere and cone counts stated in that folder's README. Skipped where the folder is absent.
#include "framework/scene/scene_loader.h"
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <ostream>

namespace bvhlab {
namespace {

namespace fs = std::filesystem;

fs::path scenesDir() {
    if (const char* dir = std::getenv("BVHLAB_SCENES_DIR")) return dir;
    return fs::path(test::sourceTree()) / ".." / "shared" / "scenes";
}

struct SharedScene {
    const char* file;
    size_t triangles;
    size_t spheres = 0;
    size_t cones = 0;
};

std::ostream& operator<<(std::ostream& os, const SharedScene& s) { return os << s.file; }

#define SKIP_WITHOUT_SCENES() \
    if (!fs::exists(scenesDir())) GTEST_SKIP() << "no scenes folder at " << scenesDir()

class SharedScenes : public testing::TestWithParam<SharedScene> {};

TEST_P(SharedScenes, LoadWithTheirStatedCounts) {
    const SharedScene& expected = GetParam();
    SKIP_WITHOUT_SCENES();
    const Scene scene = loadScene(scenesDir() / expected.file);
    EXPECT_EQ(scene.triangleCount(), expected.triangles);
    EXPECT_EQ(scene.spheres.size(), expected.spheres);
    EXPECT_EQ(scene.cones.size(), expected.cones);
    EXPECT_EQ(scene.validPrimitives.size(), scene.primitiveCount() - scene.report.degenerateTriangles -
                                                scene.report.degenerateSpheres - scene.report.degenerateCones);
    EXPECT_EQ(scene.triangles.size(), scene.triangleCount());
    EXPECT_FALSE(scene.bounds.isEmpty());
}

// rings.nff and tree.nff each hold one ground quad besides their spheres and cylinders/cones.
INSTANTIATE_TEST_SUITE_P(Files, SharedScenes,
                         testing::Values(SharedScene{"a10.obj", 69'918}, SharedScene{"igea.ply", 268'686},
                                         SharedScene{"littlest_tokyo.ply", 141'852}, SharedScene{"munich.ply", 38'938},
                                         SharedScene{"conference.obj", 331'179}, SharedScene{"florence.ply", 35'373},
                                         SharedScene{"sibenik.obj", 75'284}, SharedScene{"spd_tree_tess.ply", 540'542},
                                         SharedScene{"teapots.obj", 202'242}, SharedScene{"nff/teapot.nff", 2'328},
                                         SharedScene{"nff/tetra.nff", 4'096}, SharedScene{"nff/mount.nff", 8'192, 4},
                                         SharedScene{"nff/balls.nff", 2, 7'381},
                                         SharedScene{"nff/rings.nff", 2, 4'200, 4'200},
                                         SharedScene{"nff/tree.nff", 2, 4'095, 4'095}),
                         [](const testing::TestParamInfo<SharedScene>& info) {
                             std::string name = fs::path(info.param.file).stem().string();
                             std::replace_if(
                                 name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
                             return name;
                         });

TEST(SharedScenesDetail, ConferenceZeroAreaTriangles) {
    SKIP_WITHOUT_SCENES();
    const Scene scene = loadScene(scenesDir() / "conference.obj");
    EXPECT_EQ(scene.report.degenerateTriangles, 53'627u);
}

TEST(SharedScenesDetail, TeapotNffMaterialsLightsAndNormals) {
    SKIP_WITHOUT_SCENES();
    const Scene scene = loadScene(scenesDir() / "nff/teapot.nff");
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->from, Vec3(4.86f, 7.2f, 5.4f));
    EXPECT_EQ(scene.camera->width, 512);
    EXPECT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.materials.size(), 4u);                    // the default and three "f"
    EXPECT_EQ(scene.normals.size(), scene.positions.size());  // pp polygons give normals
}

// Separate because it takes seconds: 159 MB of gzipped binary PLY.
TEST(SharedScenesLarge, TerrainGzipPly) {
    SKIP_WITHOUT_SCENES();
    const Scene scene = loadScene(scenesDir() / "spd_mount_s11_tess.ply.gz");
    EXPECT_EQ(scene.triangleCount(), 8'389'040u);
    EXPECT_EQ(scene.name, "spd_mount_s11_tess");
}

}  // namespace
}  // namespace bvhlab
