// loadScene and readFileBytes: missing files, unknown extensions, corrupt gzip; and files that
// are not scenes, or scenes with nothing to render: an error naming the file and why, never an
// empty image.
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
    expectLoadError(
        "spheres.nff", "s 0 0 0 0\ns 2 0 0 1e-30\nc 0 0 0 1 0 0 0 0.5\n",
        {"spheres.nff:", "nothing to render", "2 spheres and 1 cones/cylinders are degenerate", "no polygons"});
}

}  // namespace
}  // namespace bvhlab::test
