// The public test scenes in ../shared/scenes (or $BVHLAB_SCENES_DIR) load with the triangle,
// sphere and cone counts stated in that folder's README. Skipped where the folder is absent.
#include "framework/scene/animated_scene.h"
#include "framework/scene/scene_loader.h"
#include "tests/support/scene_checks.h"
#include "tests/support/test_paths.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

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
                                         SharedScene{"nff/tree.nff", 2, 4'095, 4'095},
                                         // BART, at its start time: museum's 10,143 polygons (133
                                         // "p" as 274 triangles, 10,000 mesh triangles, 10 "tt")
                                         // and its 1,024 animated triangles.
                                         SharedScene{"bart/kitchen/kitchen.aff", 110'561},
                                         SharedScene{"bart/museum/museum5.aff", 11'308, 0, 8}),
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

// BART's animated scenes (docs/file-formats.md): what moves, and that setTime moves only that.
void expectBartAnimation(const char* file, size_t moving, size_t parts, size_t animatedTriangles) {
    AnimatedScene animated = loadAnimatedScene(scenesDir() / file);
    Scene& scene = animated.scene;
    EXPECT_EQ(animated.movingPrimitives().size(), moving);
    EXPECT_EQ(animated.parts.size(), parts);
    EXPECT_EQ(animated.animatedTriangles.size(), animatedTriangles);
    ASSERT_GE(animated.cameraTrack, 0);
    const std::vector<Triangle> start = scene.triangles;
    const Vec3 eye = scene.camera->from;
    std::vector<bool> moves(scene.triangleCount());
    for (const uint32_t prim : animated.movingPrimitives())
        if (prim < moves.size()) moves[prim] = true;
    for (const int frame : {animated.frameCount / 3, animated.frameCount / 2, animated.frameCount - 1}) {
        animated.setTime(animated.frameTime(frame));
        size_t moved = 0;
        for (size_t i = 0; i < start.size(); ++i) {
            const bool same = scene.triangles[i].v0 == start[i].v0 && scene.triangles[i].v1 == start[i].v1 &&
                              scene.triangles[i].v2 == start[i].v2;
            if (!moves[i]) {
                ASSERT_TRUE(same) << "static triangle " << i << " moved at frame " << frame;
            } else {
                moved += !same;
            }
        }
        EXPECT_GT(moved, moving / 2) << "frame " << frame;
        EXPECT_NE(scene.camera->from, eye) << "frame " << frame;
        test::expectDerivedAsFinalize(scene);
    }
}

TEST(SharedScenesAnimated, KitchenMovesTheCarOnly) {
    SKIP_WITHOUT_SCENES();
    // The car's body (3,658 triangles) and its four wheels (890 each), each wheel a part of its own.
    expectBartAnimation("bart/kitchen/kitchen.aff", 7'218, 5, 0);
}

TEST(SharedScenesAnimated, MuseumMovesItsAnimatedTriangles) {
    SKIP_WITHOUT_SCENES();
    expectBartAnimation("bart/museum/museum5.aff", 1'024, 0, 1'024);
}

// An evaluation at a keyframe's time reproduces the keyframe: the camera at t = 12 (its key
// 1.76 0.21 1.30) and the toy car at t = 5 (translation 3.75 0 2.75, 172.019909 degrees about y).
TEST(SharedScenesAnimated, KitchenKeyframesExactly) {
    SKIP_WITHOUT_SCENES();
    AnimatedScene animated = loadAnimatedScene(scenesDir() / "bart/kitchen/kitchen.aff");
    EXPECT_EQ(animated.frameCount, 800);
    EXPECT_FLOAT_EQ(animated.frameTime(799), 20.0f);
    animated.setTime(12.0f);
    EXPECT_LT(glm::distance(animated.scene.camera->from, Vec3(1.76f, 0.21f, 1.30f)), 1e-6f);
    const auto node = std::find_if(animated.nodes.begin(), animated.nodes.end(), [&](const TransformNode& n) {
        return n.track >= 0 && animated.tracks[size_t(n.track)].name == "toycar";
    });
    ASSERT_NE(node, animated.nodes.end());
    ASSERT_EQ(node->parent, -1);
    const glm::dmat4 m = animated.nodeTransformAt(int(node - animated.nodes.begin()), 5.0);
    const glm::dmat4 want = glm::rotate(glm::dmat4(1.0), glm::radians(172.019909), glm::dvec3(0, 1, 0));
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(m[c][r], want[c][r], 1e-12) << c << r;
    EXPECT_NEAR(m[3][0], 3.75, 1e-12);
    EXPECT_NEAR(m[3][1], 0.0, 1e-12);
    EXPECT_NEAR(m[3][2], 2.75, 1e-12);
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
