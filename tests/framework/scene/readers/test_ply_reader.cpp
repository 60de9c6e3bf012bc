// The PLY reader in its three encodings: properties and elements it skips, truncated data,
// carriage returns, errors that name the record.
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

class PlyEncodings : public testing::TestWithParam<PlyEncoding> {};

TEST_P(PlyEncodings, SkipsWhatItDoesNotUseAndKeepsTheRest) {
    const Scene scene = loadText("mesh.ply", testPly(GetParam()));
    ASSERT_EQ(scene.positions.size(), 5u);
    EXPECT_EQ(scene.positions[2], Vec3(1, 1, -2));
    EXPECT_EQ(scene.positions[4], Vec3(2, 0, -4));
    ASSERT_EQ(scene.normals.size(), 5u);
    EXPECT_EQ(scene.normals[3], Vec3(0, 3, 1));
    // The quad (z = -x - 2y at three corners, -3 at the fourth) is not planar: skipped, named.
    EXPECT_EQ(scene.indices, (std::vector<uvec3>{{0, 1, 1}, {1, 4, 2}}));
    EXPECT_EQ(scene.report.skippedPolygons, 1u);
    EXPECT_EQ(scene.report.degenerateTriangles, 1u);
    EXPECT_EQ(scene.validPrimitives, (std::vector<uint32_t>{1}));
    ASSERT_EQ(scene.report.warnings.size(), 3u);  // material and edge were skipped, and the quad
    EXPECT_NE(
        scene.report.warnings[2].find("polygon of 4 vertices skipped: not planar (element 'face', record 1 of 3)"),
        std::string::npos)
        << scene.report.warnings[2];
}

TEST_P(PlyEncodings, TruncatedDataIsAnError) {
    const std::string full = testPly(GetParam());
    const size_t dataStart = full.find("end_header\n") + 11;
    // Cut inside the vertices, the skipped material element, the faces and the edges.
    for (const double fraction : {0.1, 0.65, 0.8, 0.9}) {
        const size_t cut = dataStart + size_t(fraction * double(full.size() - dataStart));
        SCOPED_TRACE(cut);
        const bool binary = GetParam() != PlyEncoding::Ascii;
        expectLoadError("cut.ply", full.substr(0, cut), {"cut.ply", binary ? "record" : "end of the file"});
    }
}

INSTANTIATE_TEST_SUITE_P(PlyReader, PlyEncodings,
                         testing::Values(PlyEncoding::Ascii, PlyEncoding::LittleEndian, PlyEncoding::BigEndian),
                         [](const testing::TestParamInfo<PlyEncoding>& info) {
                             return PlyWriter(info.param).format();
                         });

TEST(PlyReader, AsciiWithCarriageReturnsAndFanOrder) {
    const Scene scene =
        loadText("crlf.ply",
                 "ply\r\nformat ascii 1.0\r\nelement vertex 5\r\nproperty float x\r\nproperty float y\r\n"
                 "property float z\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
                 "0 0 0\r\n1 0 0\r\n1 1 0\r\n0.5 2 0\r\n0 1 0\r\n5 0 1 2 3 4\r\n");
    EXPECT_EQ(scene.indices, (std::vector<uvec3>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
    EXPECT_TRUE(scene.normals.empty());
}

TEST(PlyReader, Errors) {
    const std::string vertexHeader =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string faceHeader = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
    expectLoadError("magic.ply", "plx\nformat ascii 1.0\nend_header\n", {"magic.ply:1:"});
    expectLoadError("keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 3\nend_header\n",
                    {"keyword.ply:3:", "'elemnt'"});
    expectLoadError("type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty flt x\nend_header\n",
                    {"type.ply:4:", "'flt'"});
    expectLoadError("format.ply", "ply\nformat binary 1.0\nend_header\n", {"format.ply:2:"});
    expectLoadError("count.ply", "ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", {"count.ply:3:"});
    expectLoadError("noend.ply", vertexHeader, {"noend.ply:6:", "end_header"});
    expectLoadError("noz.ply",
                    "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nend_header\n",
                    {"noz.ply:3:", "'z'"});
    expectLoadError("noindices.ply",
                    vertexHeader + "element face 0\nproperty int vertex_indices\nend_header\n" + vertices,
                    {"noindices.ply:7:", "vertex_indices"});
    expectLoadError("range.ply", vertexHeader + faceHeader + vertices + "3 0 1 3\n", {"range.ply:13:", "out of range"});
    expectLoadError("negative.ply", vertexHeader + faceHeader + vertices + "3 0 -1 2\n",
                    {"negative.ply:13:", "out of range"});
    expectLoadError("garbage.ply", vertexHeader + faceHeader + "0 0 0\n1 O 0\n0 1 0\n3 0 1 2\n",
                    {"garbage.ply:11:", "'O'"});
    expectLoadError("fraction.ply", vertexHeader + faceHeader + vertices + "3 0 1.5 2\n", {"fraction.ply:13:"});
    expectLoadError("short.ply", vertexHeader + faceHeader + vertices + "3 0 1\n", {"short.ply:", "end of the file"});

    // A header that promises more than the file holds must fail on the data, without
    // allocating for the promise.
    const std::string liar =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
        "property float y\nproperty float z\nelement face 4000000000\n"
        "property list uchar int vertex_indices\nend_header\n";
    expectLoadError("liar.ply", liar + std::string(30, '\0'), {"liar.ply", "element 'vertex', record 3 of 4000000000"});
    expectLoadError("huge.ply",
                    "ply\nformat binary_little_endian 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n",
                    {"huge.ply:3:"});
}

TEST(PlyReader, BinaryIndexOutOfRangeNamesTheRecord) {
    PlyWriter w(PlyEncoding::LittleEndian);
    w.put(0.0f).put(0.0f).put(0.0f).put(1.0f).put(0.0f).put(0.0f).put(0.0f).put(1.0f).put(0.0f);
    w.put(uint8_t(3)).put(0).put(1).put(2);
    w.put(uint8_t(3)).put(0).put(1).put(7);
    expectLoadError("index.ply",
                    "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n" +
                        w.data(),
                    {"index.ply", "vertex index 7 out of range", "element 'face', record 2 of 2"});
}

TEST(ReaderFuzz, Ply) {
    fuzzReader(readPly, testPly(PlyEncoding::Ascii));
    fuzzReader(readPly, testPly(PlyEncoding::LittleEndian));
    fuzzReader(readPly, testPly(PlyEncoding::BigEndian));
}

}  // namespace
}  // namespace bvhlab::test
