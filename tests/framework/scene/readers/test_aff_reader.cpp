// The AFF reader (BART's animated scenes): every construct on small files written here (includes,
// NFF's entities, meshes, nested static transforms, animated transforms and their keyframes,
// animated triangles, the camera's and a light's tracks, textures counted and skipped), line
// ends and bytes of other encodings, what setTime moves and what it leaves, and malformed files.
#include "framework/scene/scene_loader.h"
#include "tests/support/scene_checks.h"
#include "tests/support/scene_files.h"

#include <gtest/gtest.h>

#include <string>

namespace bvhlab::test {
namespace {

// Triangles in file order: 0 a polygon, 1 under two static transforms, 2-3 the included mesh,
// 4 the car (x car, with a sphere), 5 an animated triangle, 6 a textured triangle; a cone.
constexpr std::string_view kRoot = R"(% BART-like header comment
# another comment
v
from 0 0 10
at 0 0 0
up 0 1 0
angle 45
hither 0.01
resolution 64 48
b 0.1 0.2 0.3
am 1 1 1
l 0 10 0 0.5 0.5 0.5
la lamp 1 2 3
f 1 0 0 1 0 0 0 1
p 3
0 0 0
1 0 0
0 1 0
xs 2 2 2  0 0 1 90  10 0 0
{
  xs 1 1 1
     0 0 1 0
     0 0 5
  {
    p 3
    1 0 0
    2 0 0
    1 1 0
  }
}
fm 0.1 0.1 0.1
   0.5 0.6 0.7
   0.2 0.2 0.2
   20 0 1
i 0 sub/mesh.aff
x car
{
  p 3
  0 0 0
  1 0 0
  0 1 0
  s 0 0 0 0.5
}
tpa 2
 0
 0 0 0  0 0 1
 1 0 0  0 0 1
 0 1 0  0 0 1
 2
 0 0 2  0 0 1
 1 0 2  0 0 1
 0 1 2  0 0 1
tt tex.ppm
 0 0 -5 0 0
 1 0 -5 1 0
 0 1 -5 0 1
c
0 0 -10 1
0 1 -10 0.5
a 0 2 3  % start, end, frames
k car
{
  transl 5
  -1  -1 0 0  0 0 0
   0   0 0 0  0 0 0
   1   1 0 0  0 0 0
   2   2 0 0  0 0 0
   3   3 0 0  0 0 0
}
k camera
{
  transl 4
  -1  0 0 10  0 0 0
   0  0 0 10  0 0 0
   2  0 0 20  0 0 0
   3  0 0 20  0 0 0
  rot 4
  -1  0 1 0 0   0 0 0
   0  0 1 0 0   0 0 0
   2  0 1 0 90  0 0 0
   3  0 1 0 90  0 0 0
}
k lamp
{
  transl 4
  -1  -1 0 0  0 0 0
   0   0 0 0  0 0 0
   1   1 0 0  0 0 0
   2   2 0 0  0 0 0
}
)";

constexpr std::string_view kMesh = R"(m
 vertices 4
 0 0 0
 1 0 0
 1 1 0
 0 1 0
 normals 1
 0 0 1
 texturecoords 4 wood.ppm
 0 0  1 0  1 1  0 1
 triangles 2
 0 1 2  0 0 0  0 1 2
 0 2 3  0 0 0  0 2 3
)";

std::string replaceAll(std::string text, std::string_view from, std::string_view to) {
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

AnimatedScene loadSample(std::string_view lineEnd = "\n", std::string_view extraComment = "") {
    TempDir dir;
    fs::create_directories(dir.path() / "sub");
    dir.write("sub/mesh.aff", replaceAll(std::string(kMesh), "\n", lineEnd));
    const std::string root = std::string(extraComment) + std::string(kRoot);
    return loadAnimatedScene(dir.write("root.aff", replaceAll(root, "\n", lineEnd)));
}

TEST(AffReader, EveryConstructAtTheStartTime) {
    const AnimatedScene animated = loadSample();
    const Scene& scene = animated.scene;
    EXPECT_EQ(scene.triangleCount(), 7u);
    EXPECT_EQ(scene.spheres.size(), 1u);
    EXPECT_EQ(scene.cones.size(), 1u);
    EXPECT_EQ(scene.validPrimitives.size(), 9u);
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->width, 64);
    EXPECT_EQ(scene.background, Vec3(0.1f, 0.2f, 0.3f));
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].intensity, Vec3(0.5f));

    // Nested static transforms, outer last: translate (0,0,5), then scale 2, turn 90 degrees about z,
    // move by (10,0,0).
    expectVec(scene.triangles[1].v0, {10, 2, 10});
    expectVec(scene.triangles[1].v1, {10, 4, 10});
    expectVec(scene.triangles[1].v2, {8, 2, 10});
    // The included mesh: a vertex per (position, normal) pair, its normal as given.
    EXPECT_EQ(scene.triangles[2].v2, Vec3(1, 1, 0));
    EXPECT_EQ(scene.triangles[3].v2, Vec3(0, 1, 0));
    ASSERT_EQ(scene.normals.size(), scene.positions.size());
    EXPECT_EQ(scene.normals[scene.indices[2].x], Vec3(0, 0, 1));
    EXPECT_EQ(scene.normals[scene.indices[0].x], Vec3(0, 0, 1));  // a polygon's own normal
    EXPECT_EQ(scene.normals[scene.indices[6].x], Vec3(0));        // none given: the geometric one

    // Materials: "f" then "fm"'s diffuse colour, exponent, transmittance and index.
    ASSERT_EQ(scene.materials.size(), 3u);
    EXPECT_EQ(scene.materials[2].diffuse, Vec3(0.5f, 0.6f, 0.7f));
    EXPECT_EQ(scene.materials[2].shine, 20.0f);
    EXPECT_EQ(scene.materialIds, (std::vector<uint32_t>{1, 1, 2, 2, 2, 2, 2}));

    // Texture references: the mesh's texturecoords and the tt triangle.
    EXPECT_EQ(scene.report.skippedTextureReferences, 2u);
    EXPECT_NE(std::find_if(scene.report.warnings.begin(), scene.report.warnings.end(),
                           [](const std::string& w) { return w.find("2 texture references") != std::string::npos; }),
              scene.report.warnings.end());

    // The animation.
    EXPECT_EQ(animated.frameCount, 3);
    EXPECT_EQ(animated.frameTime(0), 0.0f);
    EXPECT_EQ(animated.frameTime(1), 1.0f);
    EXPECT_EQ(animated.frameTime(2), 2.0f);
    ASSERT_EQ(animated.parts.size(), 1u);
    EXPECT_EQ(animated.parts[0].triangles.first, 4u);
    EXPECT_EQ(animated.parts[0].triangles.count, 1u);
    EXPECT_EQ(animated.parts[0].spheres.count, 1u);
    ASSERT_EQ(animated.animatedTriangles.size(), 1u);
    EXPECT_EQ(animated.animatedTriangles[0].triangle, 5u);
    EXPECT_EQ(animated.movingPrimitives(), (std::vector<uint32_t>{4, 5, 7}));
    expectVec(scene.camera->from, {0, 0, 10});
    expectVec(scene.camera->at, {0, 0, 9});
}

TEST(AffReader, LoadSceneGivesTheStartTime) {
    TempDir dir;
    fs::create_directories(dir.path() / "sub");
    dir.write("sub/mesh.aff", kMesh);
    const Scene still = loadScene(dir.write("root.aff", kRoot));
    const AnimatedScene animated = loadSample();
    EXPECT_EQ(still.triangleCount(), 7u);
    for (size_t i = 0; i < still.triangleCount(); ++i) {
        EXPECT_EQ(still.triangles[i].v0, animated.scene.triangles[i].v0) << i;
        EXPECT_EQ(still.triangles[i].v2, animated.scene.triangles[i].v2) << i;
    }
    EXPECT_EQ(still.name, "root");
}

TEST(AffReader, SetTimeMovesWhatMovesAndNothingElse) {
    AnimatedScene animated = loadSample();
    Scene& scene = animated.scene;
    const std::vector<Triangle> before = scene.triangles;
    const Cone cone = scene.cones[0];
    EXPECT_FALSE(animated.setTime(1.0f));
    EXPECT_EQ(animated.time(), 1.0f);
    // The car at its keyframe at t = 1: moved by (1, 0, 0), sphere and all.
    expectVec(scene.triangles[4].v0, {1, 0, 0}, 1e-6f);
    expectVec(scene.triangles[4].v2, {1, 1, 0}, 1e-6f);
    expectVec(scene.spheres[0].centre, {1, 0, 0}, 1e-6f);
    EXPECT_FLOAT_EQ(scene.spheres[0].radius, 0.5f);
    // Between keys, on a line of evenly spaced keys: on the line.
    animated.setTime(0.5f);
    expectVec(scene.triangles[4].v0, {0.5f, 0, 0}, 1e-6f);
    // The part's transform, as the two-level structures will take it.
    const glm::mat4 m = animated.transformAt(animated.parts[0], 0.5f);
    expectVec(Vec3(m[3]), {0.5f, 0, 0}, 1e-6f);
    expectVec(animated.parts[0].positions[0], {0, 0, 0}, 0.0f);  // object space kept
    // The animated triangle, linear between its keys at t = 0 and 2.
    animated.setTime(1.0f);
    expectVec(scene.triangles[5].v1, {1, 0, 1});
    // The camera's track at its key t = 2: eye at (0,0,20), turned 90 degrees about y.
    animated.setTime(2.0f);
    expectVec(scene.camera->from, {0, 0, 20});
    expectVec(scene.camera->at, {-1, 0, 20});
    expectVec(scene.camera->up, {0, 1, 0});
    expectVec(scene.lights[1].position, {1, 0, 0});  // its track ends at t = 1
    // Clamped after the last key; the static primitives untouched, bit for bit.
    expectVec(scene.triangles[4].v0, {2, 0, 0}, 1e-6f);
    for (const uint32_t i : {0u, 1u, 2u, 3u, 6u}) {
        EXPECT_EQ(scene.triangles[i].v0, before[i].v0) << i;
        EXPECT_EQ(scene.triangles[i].v1, before[i].v1) << i;
        EXPECT_EQ(scene.triangles[i].v2, before[i].v2) << i;
    }
    EXPECT_EQ(scene.cones[0].base, cone.base);
    expectDerivedAsFinalize(scene);
}

// An include inside transform blocks is transformed once, by all of them; static transforms
// below the animated one are the part's object space.
TEST(AffReader, IncludesInsideTransforms) {
    TempDir dir;
    dir.write("tri.aff", "p 3\n0 0 0\n1 0 0\n0 1 0\n");
    const fs::path root = dir.write("root.aff",
                                    "xs 1 1 1 0 0 1 0 0 0 5\n{\n x up\n {\n  xs 2 2 2 0 0 1 0 0 0 0\n  {\n"
                                    "   i 0 tri.aff\n  }\n }\n}\n"
                                    "k up\n{\n transl 4\n -1 0 0 0 0 0 0\n 0 0 0 0 0 0 0\n"
                                    " 1 0 1 0 0 0 0\n 2 0 2 0 0 0 0\n}\n");
    AnimatedScene animated = loadAnimatedScene(root);
    ASSERT_EQ(animated.parts.size(), 1u);
    EXPECT_EQ(animated.parts[0].positions[1], Vec3(2, 0, 0));  // the inner xs, applied at load
    expectVec(animated.scene.triangles[0].v1, {2, 0, 5});
    animated.setTime(1.0f);
    expectVec(animated.scene.triangles[0].v1, {2, 1, 5});
    expectDerivedAsFinalize(animated.scene);
}

// Includes above the detail level are skipped; visibility keys and keyframes that move nothing are
// warnings; keyframes read again (a file included twice) replace the earlier ones.
TEST(AffReader, DetailLevelsAndWarnings) {
    TempDir dir;
    dir.write("tri.aff", "p 3\n0 0 0\n1 0 0\n0 1 0\n");
    for (const char* y : {"1", "3"}) {
        dir.write(
            fmt::format("keys{}.aff", y),
            fmt::format("k up\n{{\n transl 4\n -1 0 0 0 0 0 0\n 0 0 0 0 0 0 0\n 1 0 {} 0 0 0 0\n 2 0 2 0 0 0 0\n}}\n",
                        y));
    }
    const fs::path root = dir.write("root.aff",
                                    "i 0 tri.aff\ni 1 tri.aff\nd 1\ni 1 tri.aff\ni 2 tri.aff\n"
                                    "x up\n{\n i 0 tri.aff\n}\ni 0 keys1.aff\ni 0 keys3.aff\n"
                                    "k unused\n{\n visibility 2\n 0 1\n 1 0\n}\n");
    AnimatedScene animated = loadAnimatedScene(root);
    EXPECT_EQ(animated.scene.triangleCount(), 3u);
    const auto warns = [&](std::string_view part) {
        return std::any_of(animated.scene.report.warnings.begin(), animated.scene.report.warnings.end(),
                           [&](const std::string& w) { return w.find(part) != std::string::npos; });
    };
    EXPECT_TRUE(warns("root.aff:12: keyframes 'k unused' move nothing"));
    EXPECT_TRUE(warns("1 visibility keyframe blocks ignored"));
    animated.setTime(1.0f);
    expectVec(animated.scene.triangles[2].v0, {0, 3, 0});  // keys3.aff's key
}

TEST(AffReader, LineEndsCommentsAndOtherEncodings) {
    const AnimatedScene lf = loadSample();
    const AnimatedScene crlf = loadSample("\r\n");
    const AnimatedScene cr = loadSample("\r");
    const AnimatedScene latin1 = loadSample("\n", "# Joachims f\xf6rslag, \xe9t\xe9\n% \xff\xfe\n");
    for (const AnimatedScene* other : {&crlf, &cr, &latin1}) {
        ASSERT_EQ(other->scene.triangleCount(), lf.scene.triangleCount());
        for (size_t i = 0; i < lf.scene.triangleCount(); ++i)
            EXPECT_EQ(other->scene.triangles[i].v1, lf.scene.triangles[i].v1);
        EXPECT_EQ(other->frameCount, lf.frameCount);
    }
}

TEST(AffReader, QuadricsUnderAnimatedTransforms) {
    constexpr std::string_view kKeys = "k spin\n{\n scale 4\n -1 {0}\n 0 {0}\n 1 {1}\n 2 {1}\n}\n";
    const auto scene = [&](std::string_view from, std::string_view to) {
        return fmt::format("x spin\n{{\n s 1 0 0 1\n}}\n") +
               replaceAll(replaceAll(std::string(kKeys), "{0}", std::string(from) + " 0 0 0"), "{1}",
                          std::string(to) + " 0 0 0");
    };
    TempDir dir;
    AnimatedScene uniform = loadAnimatedScene(dir.write("uniform.aff", scene("1 1 1", "2 2 2")));
    uniform.setTime(1.0f);
    expectVec(uniform.scene.spheres[0].centre, {2, 0, 0});
    EXPECT_FLOAT_EQ(uniform.scene.spheres[0].radius, 2.0f);
    expectInputError([&] { loadAnimatedScene(dir.write("stretched.aff", scene("1 1 1", "2 1 1"))); },
                     {"stretched.aff:3:", "non-uniform scale"});
    expectLoadError("static.aff", "xs 1 2 1 0 0 1 0 0 0 0\n{\nc\n0 0 0 1\n0 1 0 1\n}\n",
                    {"static.aff:3:", "non-uniform scale"});
}

TEST(AffReader, MalformedFilesNameFileAndLine) {
    constexpr std::string_view kTriangle = "p 3\n0 0 0\n1 0 0\n0 1 0\n";
    expectLoadError("brace.aff", std::string("xs 1 1 1 0 0 1 0 0 0 0\n{\n") + std::string(kTriangle),
                    {"brace.aff:2:", "missing '}'"});
    expectLoadError("extra.aff", std::string(kTriangle) + "}\n", {"extra.aff:5:", "'}' without"});
    expectLoadError("ghost.aff", std::string(kTriangle) + "x ghost\n{\n" + std::string(kTriangle) + "}\n",
                    {"ghost.aff:5:", "unknown transform name 'ghost'"});
    expectLoadError("number.aff", std::string(kTriangle) + "a 0 two 3\n", {"number.aff:5:", "'two'"});
    expectLoadError("keyword.aff", std::string(kTriangle) + "\nzz 1 2\n",
                    {"keyword.aff:6:", "unknown AFF keyword 'zz'"});
    expectLoadError("few.aff", "k car\n{\n transl 3\n 0 0 0 0 0 0 0\n 1 0 0 0 0 0 0\n 2 0 0 0 0 0 0\n}\n",
                    {"few.aff:3:", "at least 4"});
    expectLoadError("back.aff",
                    "k car\n{\n transl 4\n 0 0 0 0 0 0 0\n 1 0 0 0 0 0 0\n 0.5 0 0 0 0 0 0\n 2 0 0 0 0 0 0\n}\n",
                    {"back.aff:6:", "not decrease"});
    expectLoadError("missing.aff", std::string(kTriangle) + "i 0 nothere.aff\n", {"missing.aff:5:", "nothere.aff"});
    expectLoadError("index.aff", "m\nvertices 3\n0 0 0\n1 0 0\n0 1 0\ntriangles 1\n0 1 3\n",
                    {"index.aff:7:", "out of range"});

    TempDir dir;
    dir.write("b.aff", std::string(kTriangle) + "i 0 a.aff\n");
    const fs::path a = dir.write("a.aff", "i 0 b.aff\n");
    expectInputError([&] { loadScene(a); }, {"b.aff:5:", "include cycle"});
}

TEST(AffReader, SurvivesTruncationsAndMutations) {
    const std::string small =
        "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 8\n"
        "xs 1 1 1 0 1 0 30 0 0 0\n{\nx t\n{\np 3\n0 0 0\n1 0 0\n0 1 0\n}\n}\n"
        "tpa 2\n0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n1\n0 0 1 0 0 1\n1 0 1 0 0 1\n0 1 1 0 0 1\n"
        "a 0 1 2\nk t\n{\nrot 4\n-1 0 1 0 0 0 0 0\n0 0 1 0 10 0 0 0\n1 0 1 0 20 0 0 0\n"
        "2 0 1 0 30 0 0 0\n}\n";
    fuzzReader(readAff, small);
}

}  // namespace
}  // namespace bvhlab::test
