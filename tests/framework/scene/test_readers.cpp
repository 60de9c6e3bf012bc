// The scene readers on tiny files written here: triangles and their order, degenerate
// triangles kept in place, normals, materials, NFF's camera and lights, gzip, and errors
// that name file and line, files with nothing to render refused. The fuzz tests feed truncated
// and corrupted files.
#include "framework/core/error.h"
#include "framework/scene/scene_loader.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstring>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <random>
#include <unistd.h>

namespace bvhlab {
namespace {

namespace fs = std::filesystem;
using glm::uvec3;

// A directory of its own under the system's temp directory, removed afterwards.
class TempDir {
public:
    TempDir() {
        static std::atomic<int> counter{0};
        path_ = fs::temp_directory_path() / fmt::format("bvhlab_readers_{}_{}", getpid(), counter++);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    fs::path write(const std::string& name, std::string_view bytes) const {
        const fs::path file = path_ / name;
        std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
        return file;
    }
    fs::path writeGzipped(const std::string& name, std::string_view bytes) const {
        const fs::path file = path_ / name;
        gzFile gz = gzopen(file.c_str(), "wb");
        EXPECT_NE(gz, nullptr);
        EXPECT_EQ(gzwrite(gz, bytes.data(), unsigned(bytes.size())), int(bytes.size()));
        EXPECT_EQ(gzclose(gz), Z_OK);
        return file;
    }
    fs::path path() const { return path_; }

private:
    fs::path path_;
};

Scene loadText(const std::string& name, std::string_view text) {
    TempDir dir;
    return loadScene(dir.write(name, text));
}

// Runs `load`, which must throw an InputError whose message contains every one of `parts`.
void expectInputError(const std::function<void()>& load, std::initializer_list<std::string_view> parts) {
    try {
        load();
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& e) {
        const std::string_view message = e.what();
        for (std::string_view part : parts) EXPECT_NE(message.find(part), std::string_view::npos) << message << "\n  lacks: " << part;
    }
}

void expectLoadError(const std::string& name, std::string_view text, std::initializer_list<std::string_view> parts) {
    TempDir dir;
    const fs::path file = dir.write(name, text);
    expectInputError([&] { loadScene(file); }, parts);
}

// ---------------------------------------------------------------------------------------------
// OBJ

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

// ---------------------------------------------------------------------------------------------
// PLY

enum class PlyEncoding { Ascii, LittleEndian, BigEndian };

// Writes PLY records in any of the three encodings from the same calls.
class PlyWriter {
public:
    explicit PlyWriter(PlyEncoding encoding) : encoding_(encoding) {}

    std::string format() const {
        switch (encoding_) {
            case PlyEncoding::Ascii: return "ascii";
            case PlyEncoding::LittleEndian: return "binary_little_endian";
            case PlyEncoding::BigEndian: return "binary_big_endian";
        }
        return "";
    }

    template <typename T>
    PlyWriter& put(T value) {
        if (encoding_ == PlyEncoding::Ascii) {
            data_ += fmt::format("{} ", +value);  // unary + prints chars as numbers
            return *this;
        }
        char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        const bool fileIsBig = encoding_ == PlyEncoding::BigEndian;
        if (fileIsBig != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
        data_.append(raw, sizeof(T));
        return *this;
    }

    PlyWriter& endRecord() {
        if (encoding_ == PlyEncoding::Ascii) data_ += "\n";
        return *this;
    }

    const std::string& data() const { return data_; }

private:
    PlyEncoding encoding_;
    std::string data_;
};

// Five vertices with x y z of three types and properties to skip on either side of the
// normals; a quad, a zero-area triangle and a triangle; elements to skip before and after
// the faces, lists included.
std::string testPly(PlyEncoding encoding) {
    PlyWriter w(encoding);
    const std::string header = "ply\nformat " + w.format() +
                               " 1.0\n"
                               "comment every scalar type somewhere\n"
                               "obj_info made by test_readers\n"
                               "element vertex 5\n"
                               "property double x\n"
                               "property float y\n"
                               "property short z\n"
                               "property uchar red\n"
                               "property list uchar float texcoord\n"
                               "property float nx\nproperty float ny\nproperty float nz\n"
                               "property int8 tag\n"
                               "element material 2\n"
                               "property list int uint8 name\n"
                               "property float shininess\n"
                               "element face 3\n"
                               "property uint8 flags\n"
                               "property list ushort uint vertex_index\n"
                               "property list uchar int extra\n"
                               "element edge 2\n"
                               "property int vertex1\nproperty uint32 vertex2\nproperty float64 crease\n"
                               "end_header\n";
    const double xs[] = {0, 1, 1, 0, 2};
    const float ys[] = {0, 0, 1, 1, 0};
    for (int i = 0; i < 5; ++i) {
        w.put(xs[i]).put(ys[i]).put(int16_t(-i)).put(uint8_t(200));
        w.put(uint8_t(2)).put(0.5f).put(0.25f);
        w.put(0.0f).put(float(i)).put(1.0f).put(int8_t(-1)).endRecord();
    }
    w.put(int32_t(3)).put(uint8_t('a')).put(uint8_t('b')).put(uint8_t('c')).put(2.0f).endRecord();
    w.put(int32_t(0)).put(7.0f).endRecord();
    w.put(uint8_t(1)).put(uint16_t(4)).put(0u).put(1u).put(2u).put(3u).put(uint8_t(1)).put(int32_t(-9)).endRecord();
    w.put(uint8_t(1)).put(uint16_t(3)).put(0u).put(1u).put(1u).put(uint8_t(0)).endRecord();
    w.put(uint8_t(1)).put(uint16_t(3)).put(1u).put(4u).put(2u).put(uint8_t(2)).put(int32_t(5)).put(int32_t(6)).endRecord();
    w.put(int32_t(0)).put(1u).put(0.5).endRecord();
    w.put(int32_t(1)).put(2u).put(0.5).endRecord();
    return header + w.data();
}

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
    EXPECT_NE(scene.report.warnings[2].find("polygon of 4 vertices skipped: not planar (element 'face', record 1 of 3)"),
              std::string::npos) << scene.report.warnings[2];
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
    const Scene scene = loadText("crlf.ply",
                                 "ply\r\nformat ascii 1.0\r\nelement vertex 5\r\nproperty float x\r\nproperty float y\r\n"
                                 "property float z\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
                                 "0 0 0\r\n1 0 0\r\n1 1 0\r\n0.5 2 0\r\n0 1 0\r\n5 0 1 2 3 4\r\n");
    EXPECT_EQ(scene.indices, (std::vector<uvec3>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
    EXPECT_TRUE(scene.normals.empty());
}

TEST(PlyReader, Errors) {
    const std::string vertexHeader = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string faceHeader = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
    expectLoadError("magic.ply", "plx\nformat ascii 1.0\nend_header\n", {"magic.ply:1:"});
    expectLoadError("keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 3\nend_header\n", {"keyword.ply:3:", "'elemnt'"});
    expectLoadError("type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty flt x\nend_header\n", {"type.ply:4:", "'flt'"});
    expectLoadError("format.ply", "ply\nformat binary 1.0\nend_header\n", {"format.ply:2:"});
    expectLoadError("count.ply", "ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", {"count.ply:3:"});
    expectLoadError("noend.ply", vertexHeader, {"noend.ply:7:", "end_header"});
    expectLoadError("noz.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nend_header\n",
                    {"noz.ply:3:", "'z'"});
    expectLoadError("noindices.ply", vertexHeader + "element face 0\nproperty int vertex_indices\nend_header\n" + vertices,
                    {"noindices.ply:7:", "vertex_indices"});
    expectLoadError("range.ply", vertexHeader + faceHeader + vertices + "3 0 1 3\n", {"range.ply:13:", "out of range"});
    expectLoadError("negative.ply", vertexHeader + faceHeader + vertices + "3 0 -1 2\n", {"negative.ply:13:", "out of range"});
    expectLoadError("garbage.ply", vertexHeader + faceHeader + "0 0 0\n1 O 0\n0 1 0\n3 0 1 2\n", {"garbage.ply:11:", "'O'"});
    expectLoadError("fraction.ply", vertexHeader + faceHeader + vertices + "3 0 1.5 2\n", {"fraction.ply:13:"});
    expectLoadError("short.ply", vertexHeader + faceHeader + vertices + "3 0 1\n", {"short.ply:", "end of the file"});

    // A header that promises more than the file holds must fail on the data, without
    // allocating for the promise.
    const std::string liar = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 4000000000\n"
                             "property list uchar int vertex_indices\nend_header\n";
    expectLoadError("liar.ply", liar + std::string(30, '\0'), {"liar.ply", "element 'vertex', record 3 of 4000000000"});
    expectLoadError("huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n",
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

// ---------------------------------------------------------------------------------------------
// OFF

TEST(OffReader, VerticesFacesCommentsAndColours) {
    const Scene scene = loadText("box.off",
                                 "COFF\n# a comment line\n5 3 0\n"
                                 "0 0 0 255 0 0 255\n1 0 0 255 0 0 255\n1 1 0 0 0 0 255\n0 1 0 0 0 0 255\n"
                                 "2 0 0 1 1 1 1 # trailing comment\n"
                                 "4 0 1 2 3 255 0 0\n3 0 1 4\n\n3 1 4 2 0.5 0.5 0.5\n");
    EXPECT_EQ(scene.positions[3], Vec3(0, 1, 0));
    EXPECT_EQ(scene.indices, (std::vector<uvec3>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}, {1, 4, 2}}));
    EXPECT_EQ(scene.report.degenerateTriangles, 1u);
    EXPECT_EQ(scene.validPrimitives, (std::vector<uint32_t>{0, 1, 3}));
}

TEST(OffReader, CountsOnTheKeywordLine) {
    const Scene scene = loadText("inline.off", "OFF 3 1\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0\n");
    EXPECT_EQ(scene.indices, (std::vector<uvec3>{{2, 1, 0}}));
}

TEST(OffReader, Errors) {
    expectLoadError("magic.off", "OBJ\n3 1 0\n", {"magic.off:1:", "'OBJ'"});
    expectLoadError("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", {"range.off:6:", "out of range"});
    expectLoadError("garbage.off", "OFF\n3 1 0\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n", {"garbage.off:4:", "'x'"});
    expectLoadError("short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", {"short.off:6:"});
    expectLoadError("missing.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", {"missing.off:", "end of the file"});
    expectLoadError("count.off", "OFF\n-3 1 0\n", {"count.off:2:", "vertex count"});
}

// ---------------------------------------------------------------------------------------------
// NFF

const char* const kNff = R"(# test scene
b 0.1 0.2 0.3
v
from 1 2 3
at 0 0 0
up 0 0 1
angle 40
hither 0.01
resolution 320 240
l 4 3 2
l 1 -4 4 0.5 0.25 1
p 3
0 0 0
1 0 0
0 1 0
f 1 0.5 0.25 0.8 0.3 10 0 1
pp 4
0 0 1 0 0 1
1 0 1 0 0.6 0.8
1 1 1 0 0 1
0 1 1 1 0 0
s 0 0 0 0.5
c 0 0 0 0.15 0 0 1 0.1
c
0 0 0 0.2
0 0 2 0.1

p 3
0 0 0
1 1 1
2 2 2
)";

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

// ---------------------------------------------------------------------------------------------
// loadScene and readFileBytes

TEST(ReaderFiles, MissingFileAndUnknownExtension) {
    TempDir dir;
    expectInputError([&] { loadScene(dir.path() / "absent.obj"); }, {"absent.obj", "cannot open"});
    expectInputError([&] { loadScene(dir.write("mesh.stl", "solid")); }, {"mesh.stl", ".obj", ".ply", ".off", ".nff"});
    expectInputError([&] { loadScene(dir.write("mesh.gz", "")); }, {"mesh.gz", "unknown"});
}

TEST(ReaderFiles, EmptyFileIsEmptyBytes) {
    TempDir dir;
    EXPECT_EQ(readFileBytes(dir.write("empty.off", "")), "");
}

TEST(ReaderFiles, CorruptGzip) {
    TempDir dir;
    const fs::path file = dir.writeGzipped("broken.off.gz", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_EQ(loadScene(file).triangleCount(), 1u);
    std::ifstream in(file, std::ios::binary);
    const std::string packed{std::istreambuf_iterator<char>(in), {}};

    expectInputError([&] { loadScene(dir.write("cut.off.gz", packed.substr(0, packed.size() / 2))); }, {"cut.off.gz"});
    std::string flipped = packed;
    flipped[12] = char(~flipped[12]);
    expectInputError([&] { loadScene(dir.write("flipped.off.gz", flipped)); }, {"flipped.off.gz"});
}

// ---------------------------------------------------------------------------------------------
// Files that are not scenes, or scenes with nothing to render: an error naming the file and
// why, never an empty image.

std::string randomBytes(size_t n) {
    std::mt19937 rng(9);
    std::string bytes(n, '\0');
    for (char& c : bytes) c = char(rng());
    return bytes;
}

TEST(SceneErrors, EmptyObj) {
    expectLoadError("empty.obj", "", {"empty.obj:", "nothing to render", "no primitives"});
    expectLoadError("points.obj", "# only vertices\nv 0 0 0\nv 1 0 0\n", {"points.obj:", "2 vertices but no faces"});
}

TEST(SceneErrors, AllDegenerateObj) {
    expectLoadError("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n",
                    {"flat.obj:", "nothing to render", "all 2 triangles are degenerate"});
}

TEST(SceneErrors, AllNanObj) {
    expectLoadError("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 inf 0\nv 0 1 0\nf 1 2 4\nf 2 3 4\n",
                    {"nan.obj:", "nothing to render", "all 2 triangles are degenerate"});
}

TEST(SceneErrors, RandomBytesObj) {
    expectLoadError("random.obj", randomBytes(4096), {"random.obj:", "binary data, not a text .obj file"});
}

TEST(SceneErrors, RandomBytesObjGz) {
    // Not gzip at all (zlib passes such files through), and gzip holding garbage.
    expectLoadError("random.obj.gz", randomBytes(4096), {"random.obj.gz:", "binary data"});
    TempDir dir;
    const fs::path packed = dir.writeGzipped("packed.obj.gz", randomBytes(4096));
    expectInputError([&] { loadScene(packed); }, {"packed.obj.gz:", "binary data"});
}

TEST(SceneErrors, TextThatIsNoObj) {
    expectLoadError("README.obj", "# bvhlab\n\nA research ray tracer.\n\n## Building\n\n    cmake -S . -B build\n",
                    {"README.obj:", "not an OBJ file", "no vertex or face statements", "'A research ray tracer.'"});
}

TEST(SceneErrors, PlyNamedObj) {
    for (PlyEncoding encoding : {PlyEncoding::Ascii, PlyEncoding::LittleEndian}) {
        expectLoadError("mesh.obj", testPly(encoding), {"mesh.obj:", "a PLY file", "name it .ply"});
    }
}

TEST(SceneErrors, NffWithOnlyDegenerateSpheresAndCones) {
    expectLoadError("spheres.nff", "s 0 0 0 0\ns 2 0 0 1e-30\nc 0 0 0 1 0 0 0 0.5\n",
                    {"spheres.nff:", "nothing to render", "2 spheres and 1 cones/cylinders are degenerate",
                     "no polygons"});
}

TEST(NffReader, SpheresAndConesAloneLoad) {
    const Scene scene = loadText("spheres.nff", "s 0 0 0 1\ns 2 0 0 -0.5\nc 0 0 0 1 0 0 1 0.5\n");
    EXPECT_EQ(scene.validPrimitives, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_FALSE(scene.bounds.isEmpty());
}

TEST(NffReader, DegenerateSpheresAndConesAreCountedAndSkipped) {
    const Scene scene = loadText("balls.nff", "p 4\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\ns 0 0 1 0.5\ns 0 0 2 0\n"
                                              "c 0 0 0 1 0 0 0 1\nc 0 0 0 1 0 0 1 -1\nc 0 0 0 1 0 0 1 0\n");
    EXPECT_EQ(scene.validPrimitives, (std::vector<uint32_t>{0, 1, 2, 6}));
    EXPECT_EQ(scene.report.degenerateSpheres, 1u);
    EXPECT_EQ(scene.report.degenerateCones, 2u);
}

// ---------------------------------------------------------------------------------------------
// Truncated and corrupted input never crashes a reader: it loads or throws InputError.

void expectLoadsOrThrowsInputError(Scene (*read)(const fs::path&, const std::string&), const std::string& bytes) {
    const fs::path file = "fuzz";
    try {
        Scene scene = read(file, bytes);
        scene.finalize();
    } catch (const InputError&) {
    }
}

void fuzz(Scene (*read)(const fs::path&, const std::string&), const std::string& valid) {
    ASSERT_NO_THROW(read("valid", valid));
    for (size_t length = 0; length < valid.size(); ++length) expectLoadsOrThrowsInputError(read, valid.substr(0, length));
    // Every byte replaced by characters that change meaning in one format or another.
    for (size_t i = 0; i < valid.size(); ++i) {
        for (const char c : {'\0', '\n', ' ', '-', '9', '#', '/', '\xff', '\x80'}) {
            std::string mutated = valid;
            mutated[i] = c;
            expectLoadsOrThrowsInputError(read, mutated);
        }
    }
}

TEST(ReaderFuzz, Obj) {
    fuzz(readObj, "v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf -1 -2 -3\ng g\nf 1 2 3 1\n");
}

TEST(ReaderFuzz, Ply) {
    fuzz(readPly, testPly(PlyEncoding::Ascii));
    fuzz(readPly, testPly(PlyEncoding::LittleEndian));
    fuzz(readPly, testPly(PlyEncoding::BigEndian));
}

TEST(ReaderFuzz, Off) { fuzz(readOff, "OFF\n# c\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 1 2 3 1 1 1\n"); }

TEST(ReaderFuzz, Nff) { fuzz(readNff, kNff); }

}  // namespace
}  // namespace bvhlab
