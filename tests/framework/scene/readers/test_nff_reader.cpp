// The NFF reader: everything the format holds (camera, lights, polygons with and without
// normals, spheres, cones), degenerate spheres and cones counted and skipped, errors.
#include "tests/support/sample_scenes.h"
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

TEST(NffReader, EverythingTheFormatHolds) {
    const Scene scene = loadText("all.nff", kNff);
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->from, Vec3(1, 2, 3));
    EXPECT_EQ(scene.camera->up, Vec3(0, 0, 1));
    EXPECT_EQ(scene.camera->fovyDegrees, 40.0f);
    EXPECT_EQ(scene.camera->width, 320);
    EXPECT_EQ(scene.camera->height, 240);
    EXPECT_EQ(scene.background, Vec3(0.1f, 0.2f, 0.3f));
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].position, Vec3(4, 3, 2));
    EXPECT_EQ(scene.lights[0].intensity, Vec3(1));
    EXPECT_EQ(scene.lights[1].intensity, Vec3(0.5f, 0.25f, 1));

    ASSERT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.materials[1].diffuse, 0.8f * Vec3(1, 0.5f, 0.25f));
    EXPECT_EQ(scene.materials[1].mirror, 0.3f);
    EXPECT_EQ(scene.materials[1].shine, 10.0f);
    EXPECT_EQ(scene.materials[1].transmission, 0.0f);
    EXPECT_EQ(scene.materials[1].ior, 1.0f);
    EXPECT_EQ(scene.materialIds, (std::vector<uint32_t>{0, 1, 1, 1}));

    EXPECT_EQ(scene.indices, (std::vector<uvec3>{{0, 1, 2}, {3, 4, 5}, {3, 5, 6}, {7, 8, 9}}));
    EXPECT_EQ(scene.report.degenerateTriangles, 1u);
    // Spheres and cones are native primitives, after the triangles in the index space.
    ASSERT_EQ(scene.spheres.size(), 1u);
    EXPECT_EQ(scene.spheres[0].centre, Vec3(0));
    EXPECT_EQ(scene.spheres[0].radius, 0.5f);
    ASSERT_EQ(scene.cones.size(), 2u);
    EXPECT_EQ(scene.cones[0].base, Vec3(0));
    EXPECT_EQ(scene.cones[0].baseRadius, 0.15f);
    EXPECT_EQ(scene.cones[0].apex, Vec3(0, 0, 1));
    EXPECT_EQ(scene.cones[0].apexRadius, 0.1f);
    EXPECT_EQ(scene.cones[1].apex, Vec3(0, 0, 2));
    EXPECT_EQ(scene.sphereMaterialIds, (std::vector<uint32_t>{1}));
    EXPECT_EQ(scene.coneMaterialIds, (std::vector<uint32_t>{1, 1}));
    EXPECT_EQ(scene.report.degenerateSpheres, 0u);
    EXPECT_EQ(scene.report.degenerateCones, 0u);
    EXPECT_EQ(scene.validPrimitives, (std::vector<uint32_t>{0, 1, 2, 4, 5, 6}));
    EXPECT_EQ(scene.primitives().kind(4), PrimitiveKind::Sphere);
    EXPECT_EQ(scene.primitives().kind(6), PrimitiveKind::Cone);
    EXPECT_EQ(scene.materialOf(5), 1u);

    // pp normals as given; p polygons get their geometric normal.
    ASSERT_EQ(scene.normals.size(), scene.positions.size());
    EXPECT_EQ(scene.normals[0], Vec3(0, 0, 1));
    EXPECT_EQ(scene.normals[4], Vec3(0, 0.6f, 0.8f));
    EXPECT_EQ(scene.normals[6], Vec3(1, 0, 0));
}

TEST(NffReader, NoNormalsWithoutPp) {
    const Scene scene = loadText("flat.nff", "p 3\n0 0 0\n1 0 0\n0 1 0\n");
    EXPECT_EQ(scene.triangleCount(), 1u);
    EXPECT_TRUE(scene.normals.empty());
    EXPECT_FALSE(scene.camera.has_value());
}

TEST(NffReader, Errors) {
    expectLoadError("entity.nff", "b 0 0 0\nq 1 2 3\n", {"entity.nff:2:", "'q'"});
    expectLoadError("vertex.nff", "p 3\n0 0 0\n1 0\n0 1 0\n", {"vertex.nff:3:"});
    expectLoadError("extra.nff", "p 3\n0 0 0\n1 0 0 7\n0 1 0\n", {"extra.nff:3:", "'7'"});
    expectLoadError("count.nff", "p 2\n0 0 0\n1 0 0\n", {"count.nff:1:", "at least 3"});
    expectLoadError("short.nff", "p 4\n0 0 0\n1 0 0\n0 1 0\n", {"short.nff:", "end of the file"});
    expectLoadError("view.nff", "v\nfrom 0 0 1\nat 0 0 0\nangle 45\n", {"view.nff:4:", "'up'"});
    expectLoadError("light.nff", "l 1 2 3 4\n", {"light.nff:1:"});
}

TEST(NffReader, SpheresAndConesAloneLoad) {
    const Scene scene = loadText("spheres.nff", "s 0 0 0 1\ns 2 0 0 -0.5\nc 0 0 0 1 0 0 1 0.5\n");
    EXPECT_EQ(scene.validPrimitives, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_FALSE(scene.bounds.isEmpty());
}

TEST(NffReader, DegenerateSpheresAndConesAreCountedAndSkipped) {
    const Scene scene = loadText("balls.nff",
                                 "p 4\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\ns 0 0 1 0.5\ns 0 0 2 0\n"
                                 "c 0 0 0 1 0 0 0 1\nc 0 0 0 1 0 0 1 -1\nc 0 0 0 1 0 0 1 0\n");
    EXPECT_EQ(scene.validPrimitives, (std::vector<uint32_t>{0, 1, 2, 6}));
    EXPECT_EQ(scene.report.degenerateSpheres, 1u);
    EXPECT_EQ(scene.report.degenerateCones, 2u);
}

TEST(ReaderFuzz, Nff) { fuzzReader(readNff, kNff); }

}  // namespace
}  // namespace bvhlab::test
