// The OBJ reader on tiny files written here: fan triangulation in file order, degenerate
// triangles kept in place, normals, groups, materials, gzip, errors that name file and line.
#include "tests/support/scene_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace bvhlab::test {
namespace {

using glm::uvec3;

TEST(ObjReader, FanTriangulatesConvexFacesInFileOrderAndKeepsDegenerateTriangles) {
    const Scene scene = loadText("fan.obj",
                                 "# quad, a zero-area triangle, a convex pentagon with a straight corner\n"
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
                                 "f 1 2 3 4\n"
                                 "f 1 2 5\n"  // collinear: zero area
                                 "f 1 2 5 3 4\n");
    EXPECT_EQ(scene.name, "fan");
    // The pentagon's first fan triangle (0, 1, 4) is on its straight bottom edge: zero area.
    EXPECT_EQ(scene.indices, (std::vector<uvec3>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}, {0, 1, 4}, {0, 4, 2}, {0, 2, 3}}));
    EXPECT_EQ(scene.report.degenerateTriangles, 2u);
    EXPECT_EQ(scene.validPrimitives, (std::vector<uint32_t>{0, 1, 4, 5}));
    EXPECT_TRUE(scene.normals.empty());
    EXPECT_TRUE(scene.materialIds.empty());
}

TEST(ObjReader, NanAndInfinityCoordinatesMakeDegenerateTriangles) {
    const Scene scene = loadText("nan.obj",
                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nv 0 -inf 0\nv +1e3 2.5E-1 -.5\n"
                                 "f 1 2 3\nf 1 2 4\nf 5 2 3\nf 1 2 6\n");
    ASSERT_EQ(scene.triangleCount(), 4u);
    EXPECT_TRUE(std::isnan(scene.positions[3].x));
    EXPECT_EQ(scene.positions[4].y, -kInfinity);
    EXPECT_EQ(scene.positions[5], Vec3(1000.0f, 0.25f, -0.5f));
    EXPECT_EQ(scene.report.degenerateTriangles, 2u);
    EXPECT_EQ(scene.validPrimitives, (std::vector<uint32_t>{0, 3}));
}

TEST(ObjReader, RelativeIndicesAndGroups) {
    const Scene scene = loadText("relative.obj",
                                 "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                                 "g second\nv 0 0 1\nf 1/1 2/2 -1/3\n");
    EXPECT_EQ(scene.indices, (std::vector<uvec3>{{0, 1, 2}, {0, 1, 3}}));
}

TEST(ObjReader, PerVertexNormalsWhenEveryCornerHasOne) {
    const Scene withNormals = loadText("normals.obj",
                                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 0\n"
                                       "f 1//1 2//1 3//2\n");
    ASSERT_EQ(withNormals.normals.size(), 3u);
    EXPECT_EQ(withNormals.normals[0], Vec3(0, 0, 1));
    EXPECT_EQ(withNormals.normals[2], Vec3(0, 1, 0));

    const Scene partial = loadText("partial.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 3\n");
    EXPECT_TRUE(partial.normals.empty());
}

TEST(ObjReader, MaterialsFromMtl) {
    TempDir dir;
    dir.write("lit.mtl", "newmtl red\nKd 1 0 0\nnewmtl grey\nKd 0.5 0.5 0.5\n");
    const fs::path file = dir.write("lit.obj",
                                    "mtllib lit.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                    "f 1 2 3\nusemtl grey\nf 1 2 3\nusemtl red\nf 1 2 3\n");
    const Scene scene = loadScene(file);
    ASSERT_EQ(scene.materials.size(), 3u);
    EXPECT_EQ(scene.materials[1].diffuse, Vec3(1, 0, 0));
    EXPECT_EQ(scene.materials[2].diffuse, Vec3(0.5f));
    EXPECT_EQ(scene.materialIds, (std::vector<uint32_t>{0, 2, 1}));
    EXPECT_TRUE(scene.report.warnings.empty());
}

TEST(ObjReader, MissingMtlIsAWarning) {
    const Scene scene = loadText("nomtl.obj", "mtllib absent.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
    EXPECT_EQ(scene.triangleCount(), 1u);
    ASSERT_FALSE(scene.report.warnings.empty());
    EXPECT_NE(scene.report.warnings[0].find("absent.mtl"), std::string::npos) << scene.report.warnings[0];
}

TEST(ObjReader, GzipRoundTrip) {
    const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n";
    TempDir dir;
    const fs::path file = dir.writeGzipped("packed.OBJ.gz", text);  // the extension is case-insensitive

    EXPECT_EQ(readFileBytes(file), text);
    const Scene scene = loadScene(file);
    EXPECT_EQ(scene.name, "packed");
    EXPECT_EQ(scene.source, file);
    EXPECT_EQ(scene.indices, (std::vector<uvec3>{{0, 1, 3}, {0, 3, 2}}));
}

TEST(ObjReader, Errors) {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    expectLoadError("range.obj", vertices + "f 1 2 3\nf 1 2 4\n", {"range.obj:5:", "out of range"});
    expectLoadError("behind.obj", vertices + "f -4 1 2\n", {"behind.obj:4:", "out of range"});
    expectLoadError("normal.obj", vertices + "vn 0 0 1\nf 1//1 2//2 3//1\n", {"normal.obj:5:", "normal index"});
    expectLoadError("garbage.obj", "v 0 0 0\nv 1 zero 0\n", {"garbage.obj:2:", "'zero'"});
    expectLoadError("short.obj", "v 0 0\n", {"short.obj:1:"});
    expectLoadError("zero.obj", vertices + "f 0 1 2\n", {"zero.obj:4:"});
    expectLoadError("line.obj", vertices + "\nf 1 2\n", {"line.obj:5:", "face with 2 corners"});
}

TEST(ReaderFuzz, Obj) {
    fuzzReader(readObj, "v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf -1 -2 -3\ng g\nf 1 2 3 1\n");
}

}  // namespace
}  // namespace bvhlab::test
