// AFF files unlike BART's kitchen and museum: other encodings and layouts (a UTF-8 BOM, CR LF and
// CR line ends, tabs, blank and comment lines between any two lines, Latin-1 names, include paths
// with backslashes), constructs
// those scenes do not use (keyframe blocks of only a rotation or a scale, nested animated
// transforms, animated triangles of one or three keys, a camera that only turns, a camera track
// without a viewpoint, lights whose track does not move them) and malformed files, which fail
// with file and line and never crash or hang.
#include "framework/scene/scene_loader.h"
#include "tests/support/scene_checks.h"
#include "tests/support/scene_files.h"

#include <gtest/gtest.h>

#include <string>

namespace bvhlab::test {
namespace {

// Four keys making a spline that is `from` at t = 0 and `to` at t = 1 (the end keys shape the
// tangents only): "transl", "scale" or, with an axis and degrees, "rot".
std::string keyframes(std::string_view type, std::string_view from, std::string_view to) {
    return fmt::format(" {} 4\n -1 {} 0 0 0\n 0 {} 0 0 0\n 1 {} 0 0 0\n 2 {} 0 0 0\n", type, from, from, to, to);
}

// A viewpoint, a static triangle, a moving one under `x caf\xe9` (Latin-1) from an included file,
// an animated triangle and a light; the camera moves back along z.
std::string sampleRoot() {
    return "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 8 8\n"
           "l 0 10 0\np 3\n0 0 0\n1 0 0\n0 1 0\n"
           "x caf\xe9\n{\n i 0 m\xf6"
           "bel.aff\n}\n"
           "tpa 2\n0\n0 0 1 0 0 1\n1 0 1 0 0 1\n0 1 1 0 0 1\n1\n0 0 2 0 0 1\n1 0 2 0 0 1\n0 1 2 0 0 1\n"
           "a 0 1 2\n"
           "k caf\xe9\n{\n" +
           keyframes("transl", "0 0 0", "5 0 0") + "}\nk camera\n{\n" + keyframes("transl", "0 0 10", "0 0 20") + "}\n";
}
constexpr std::string_view kIncluded = "p 3\n0 0 0\n1 0 0\n0 1 0\n";

// Each line of `text` as another writer would put it: `lineEnd` for "\n", tabs for spaces, and
// a blank line and a comment line after each line.
std::string rewritten(std::string_view text, std::string_view lineEnd) {
    std::string out;
    for (const char c : text) {
        if (c == '\n') {
            out += std::string(lineEnd) + "\t" + std::string(lineEnd) + "# r\xe9sum\xe9 %" + std::string(lineEnd);
        } else {
            out += c == ' ' ? '\t' : c;
        }
    }
    return out;
}

AnimatedScene loadPair(std::string_view root, std::string_view included) {
    TempDir dir;
    dir.write(
        "m\xf6"
        "bel.aff",
        included);
    return loadAnimatedScene(dir.write("root.aff", root));
}

void expectSameAnimation(AnimatedScene& a, AnimatedScene& b) {
    ASSERT_EQ(a.scene.triangleCount(), b.scene.triangleCount());
    ASSERT_EQ(a.frameCount, b.frameCount);
    for (const float time : {0.0f, 0.5f, 1.0f}) {
        a.setTime(time);
        b.setTime(time);
        for (size_t i = 0; i < a.scene.triangleCount(); ++i) {
            EXPECT_EQ(a.scene.triangles[i].v0, b.scene.triangles[i].v0) << i << " at " << time;
            EXPECT_EQ(a.scene.triangles[i].v1, b.scene.triangles[i].v1) << i << " at " << time;
        }
        EXPECT_EQ(a.scene.camera->from, b.scene.camera->from);
    }
}

TEST(AffUnseenFiles, OtherLineEndsTabsBlankAndCommentLinesAndABom) {
    AnimatedScene plain = loadPair(sampleRoot(), kIncluded);
    ASSERT_EQ(plain.scene.triangleCount(), 3u);
    plain.setTime(1.0f);
    expectVec(plain.scene.triangles[1].v1, {6, 0, 0});
    expectVec(plain.scene.camera->from, {0, 0, 20});
    for (const std::string_view lineEnd : {"\n", "\r\n", "\r"}) {
        SCOPED_TRACE(testing::PrintToString(std::string(lineEnd)));
        AnimatedScene other =
            loadPair("\xef\xbb\xbf" + rewritten(sampleRoot(), lineEnd), "\xef\xbb\xbf" + rewritten(kIncluded, lineEnd));
        expectSameAnimation(plain, other);
    }
    // Mixed line ends in one file, and a BOM before a comment.
    std::string mixed = sampleRoot();
    for (size_t at = mixed.find('\n'), k = 0; at != std::string::npos; at = mixed.find('\n', at + 2), ++k)
        mixed.replace(at, 1, k % 3 == 0 ? "\r\n" : k % 3 == 1 ? "\r" : "\n");
    AnimatedScene mixedEnds = loadPair("\xef\xbb\xbf% BART\n" + mixed, kIncluded);
    expectSameAnimation(plain, mixedEnds);
}

TEST(AffUnseenFiles, ErrorsCountLinesOfEveryLineEnd) {
    for (const std::string_view lineEnd : {"\n", "\r\n", "\r"}) {
        const std::string text = fmt::format("\xef\xbb\xbfp 3{0}0 0 0{0}1 0 0{0}0 1 0{0}{0}zz{0}", lineEnd);
        expectLoadError("ends.aff", text, {"ends.aff:6:", "unknown AFF keyword 'zz'"});
    }
}

TEST(AffUnseenFiles, KeyframeBlocksOfOnlyARotationOrAScale) {
    TempDir dir;
    const std::string triangle = "{\n p 3\n 1 0 0\n 2 0 0\n 1 1 0\n}\n";
    const fs::path file = dir.write(
        "partial.aff", "x turn\n" + triangle + "x grow\n" + triangle + "x both\n" + triangle + "k turn\n{\n" +
                           keyframes("rot", "0 0 1 0", "0 0 1 90") + "}\nk grow\n{\n" +
                           keyframes("scale", "1 1 1", "2 2 2") + "}\nk both\n{\n" +
                           keyframes("scale", "1 1 1", "3 3 3") + keyframes("rot", "0 0 1 0", "0 0 1 180") + "}\n");
    AnimatedScene animated = loadAnimatedScene(file);
    ASSERT_EQ(animated.parts.size(), 3u);
    expectVec(animated.scene.triangles[0].v0, {1, 0, 0});
    animated.setTime(1.0f);
    expectVec(animated.scene.triangles[0].v0, {0, 1, 0});
    expectVec(animated.scene.triangles[0].v1, {0, 2, 0});
    expectVec(animated.scene.triangles[1].v1, {4, 0, 0});
    expectVec(animated.scene.triangles[2].v1, {-6, 0, 0});
    expectDerivedAsFinalize(animated.scene);
}

// Outer first: the inner transform turns the triangle, the outer moves it; static transforms
// between and below them stay in the chain.
TEST(AffUnseenFiles, NestedAnimatedTransforms) {
    TempDir dir;
    const fs::path file =
        dir.write("nested.aff",
                  "x outer\n{\n xs 1 1 1 0 0 1 0 0 0 3\n {\n  x inner\n  {\n   xs 2 2 2 0 0 1 0 0 0 0\n   {\n"
                  "    p 3\n    1 0 0\n    2 0 0\n    1 1 0\n   }\n  }\n }\n}\n"
                  "k outer\n{\n" +
                      keyframes("transl", "0 0 0", "10 0 0") + "}\nk inner\n{\n" +
                      keyframes("rot", "0 0 1 0", "0 0 1 90") + "}\n");
    AnimatedScene animated = loadAnimatedScene(file);
    ASSERT_EQ(animated.parts.size(), 1u);
    EXPECT_EQ(animated.parts[0].positions[0], Vec3(2, 0, 0));  // the innermost xs, applied at load
    expectVec(animated.scene.triangles[0].v0, {2, 0, 3});
    animated.setTime(1.0f);
    expectVec(animated.scene.triangles[0].v0, {10, 2, 3});
    expectVec(animated.scene.triangles[0].v1, {10, 4, 3});
    expectVec(Vec3(animated.transformAt(animated.parts[0], 1.0f)[3]), {10, 0, 3});
}

TEST(AffUnseenFiles, AnimatedTrianglesOfOneThreeAndRepeatedKeys) {
    const auto key = [](float time, float z) {
        return fmt::format("{} 0 0 {} 0 0 1 1 0 {} 0 0 1 0 1 {} 0 0 1\n", time, z, z, z);
    };
    TempDir dir;
    const fs::path file = dir.write("tpa.aff", "tpa 1\n" + key(5, 7) + "tpa 3\n" + key(0, 0) + key(1, 1) + key(2, 3) +
                                                   "tpa 4\n" + key(0, 0) + key(1, 1) + key(1, 5) + key(2, 5));
    AnimatedScene animated = loadAnimatedScene(file);
    ASSERT_EQ(animated.animatedTriangles.size(), 3u);
    for (const auto& [time, one, three, repeated] :
         {std::tuple{0.0f, 7.0f, 0.0f, 0.0f}, std::tuple{0.5f, 7.0f, 0.5f, 0.5f}, std::tuple{1.5f, 7.0f, 2.0f, 5.0f},
          std::tuple{9.0f, 7.0f, 3.0f, 5.0f}}) {
        animated.setTime(time);
        EXPECT_FLOAT_EQ(animated.scene.triangles[0].v0.z, one) << time;
        EXPECT_FLOAT_EQ(animated.scene.triangles[1].v0.z, three) << time;
        EXPECT_FLOAT_EQ(animated.scene.triangles[2].v0.z, repeated) << time;
    }
    animated.setTime(1.0f);  // the later of two keys at one time holds from it
    EXPECT_FLOAT_EQ(animated.scene.triangles[2].v0.z, 5.0f);
}

TEST(AffUnseenFiles, CamerasAndLightsOfOtherTracks) {
    TempDir dir;
    constexpr std::string_view kView = "v\nfrom 1 2 3\nat 1 2 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 8 8\n";
    const std::string turning = std::string(kView) + "p 3\n0 0 0\n1 0 0\n0 1 0\nla lamp 4 5 6 0.5 0.5 0.5\n" +
                                "k camera\n{\n" + keyframes("rot", "0 1 0 0", "0 1 0 90") + "}\nk lamp\n{\n" +
                                keyframes("rot", "0 1 0 0", "0 1 0 90") + "}\n";
    AnimatedScene turns = loadAnimatedScene(dir.write("turning.aff", turning));
    turns.setTime(1.0f);
    expectVec(turns.scene.camera->from, {1, 2, 3});  // only turned
    expectVec(turns.scene.camera->at, {0, 2, 3});
    expectVec(turns.scene.lights[0].position, {4, 5, 6});  // a track without a translation
    EXPECT_EQ(turns.scene.lights[0].intensity, Vec3(0.5f));

    // A camera track without a viewpoint block moves the default camera.
    AnimatedScene noView = loadAnimatedScene(dir.write(
        "noview.aff", "p 3\n0 0 0\n1 0 0\n0 1 0\nk camera\n{\n" + keyframes("transl", "0 0 5", "0 0 9") + "}\n"));
    noView.setTime(1.0f);
    ASSERT_TRUE(noView.scene.camera.has_value());
    expectVec(noView.scene.camera->from, {0, 0, 9});
}

TEST(AffUnseenFiles, MalformedFilesNameFileAndLine) {
    constexpr std::string_view kTriangle = "p 3\n0 0 0\n1 0 0\n0 1 0\n";
    const std::string t(kTriangle);
    // Truncated blocks.
    expectLoadError("k.aff", t + "k car\n{\n transl 4\n 0 0 0 0 0 0 0\n", {"k.aff:8:", "the end of the file"});
    expectLoadError("kbrace.aff", t + "k car\n{\n" + keyframes("transl", "0 0 0", "1 0 0"),
                    {"kbrace.aff:5:", "'k car'"});
    expectLoadError("tpa.aff", t + "tpa 2\n0\n0 0 0 0 0 1\n", {"tpa.aff:7:", "the end of the file"});
    expectLoadError("mesh.aff", "m\nvertices 3\n0 0 0\n1 0 0\n", {"mesh.aff:4:", "the end of the file"});
    expectLoadError("view.aff", "v\nfrom 0 0 1\nat 0 0 0\n", {"view.aff:3:", "expected 'up'"});
    expectLoadError("x.aff", t + "x car\n", {"x.aff:5:", "'{'"});
    // Numbers that are not, as other locales and tools write them.
    expectLoadError("comma.aff", "p 3\n0 0 0\n1,5 0 0\n0 1 0\n", {"comma.aff:3:", "'1,5'"});
    expectLoadError("dots.aff", t + "a 0 1.2.3 4\n", {"dots.aff:5:", "'1.2.3'"});
    expectLoadError("frames.aff", t + "a 0 1 2.5\n", {"frames.aff:5:", "'2.5'"});
    expectLoadError("span.aff", t + "a 2 1 5\n", {"span.aff:5:", "end at or after its start"});
    expectLoadError("none.aff", t + "a 0 1 0\n", {"none.aff:5:", "0 frames"});
    // Keys out of order.
    expectLoadError("tpaorder.aff",
                    "tpa 2\n1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n",
                    {"tpaorder.aff:6:", "not decrease"});
    expectLoadError("rotorder.aff",
                    t + "k r\n{\n rot 4\n 0 0 1 0 0 0 0 0\n 2 0 1 0 5 0 0 0\n 1 0 1 0 9 0 0 0\n 3 0 1 0 9 0 0 0\n}\n",
                    {"rotorder.aff:10:", "not decrease"});
    expectLoadError("nan.aff", t + "k r\n{\n transl 4\n -1 0 0 0 0 0 0\n nan 0 0 0 0 0 0\n 1 0 0 0 0 0 0\n}\n",
                    {"nan.aff:9:", "finite"});
    // Counts that the file cannot hold end at its end, without allocating them.
    expectLoadError("tpabig.aff", t + "tpa 4000000000\n0\n", {"tpabig.aff:6:", "the end of the file"});
    expectLoadError("keybig.aff", t + "k r\n{\n transl 18446744073709551615\n", {"keybig.aff:7:", "the end"});
    expectLoadError("visbig.aff", t + "k r\n{\n visibility 99999999999\n 0 1\n", {"visbig.aff:8:", "the end"});
    expectLoadError("meshbig.aff", "m\nvertices 2000000000\n0 0 0\n", {"meshbig.aff:3:", "the end of the file"});
    // Nothing to render, whatever comes first.
    expectLoadError("bom.aff", "\xef\xbb\xbf", {"bom.aff", "nothing to render"});
    expectLoadError("empty.aff", "", {"empty.aff", "nothing to render"});
}

TEST(AffUnseenFiles, DeepBlocksWindowsPathsAndIncludesOfWhatIsNoFile) {
    std::string deep;
    constexpr int kDepth = 5000;
    for (int k = 0; k < kDepth; ++k) deep += "xs 1 1 1 0 0 1 0 0 0 1\n{\n";
    deep += "p 3\n0 0 0\n1 0 0\n0 1 0\n";
    for (int k = 0; k < kDepth; ++k) deep += "}\n";
    TempDir dir;
    const Scene scene = loadScene(dir.write("deep.aff", deep));
    expectVec(scene.triangles[0].v0, {0, 0, kDepth});

    // A path written on Windows.
    fs::create_directories(dir.path() / "sub");
    dir.write("sub/tri.aff", "p 3\n0 0 0\n1 0 0\n0 1 0\n");
    EXPECT_EQ(loadScene(dir.write("windows.aff", "i 0 sub\\tri.aff\r\n")).triangleCount(), 1u);

    fs::create_directories(dir.path() / "folder.aff");
    expectInputError([&] { loadScene(dir.write("dir.aff", "i 0 folder.aff\n")); },
                     {"dir.aff:1:", "cannot open the included file 'folder.aff'"});
}

// What the result key checksums: every include at any detail level, nested ones, each once,
// without reading the scene; names that are no file and a name `i` are passed by.
TEST(AffUnseenFiles, IncludedFilesAreFoundWithoutReadingTheScene) {
    TempDir dir;
    fs::create_directories(dir.path() / "sub");
    dir.write("sub/a.aff", "i 0 b.aff\ni 0 ../c.aff\n");
    dir.write("sub/b.aff", "i 0 a.aff\n");
    dir.write("c.aff", "p 3\n0 0 0\n1 0 0\n0 1 0\n");
    const fs::path root = dir.write("root.aff",
                                    "\xef\xbb\xbf% root\r\ni 0 sub\\a.aff\r\ni 7 c.aff\r\nx i\r\n{\r\n}\r\n"
                                    "i 0 none.aff\r\n");
    std::vector<std::string> names;
    for (const fs::path& file : includedFiles(root)) names.push_back(file.lexically_relative(dir.path()).string());
    EXPECT_EQ(names, (std::vector<std::string>{"sub/a.aff", "c.aff", "sub/b.aff"}));
    EXPECT_TRUE(includedFiles(dir.write("still.obj", "v 0 0 0\n")).empty());
}

TEST(AffUnseenFiles, SurvivesTruncationsAndMutationsOfOtherEncodings) {
    fuzzReader(readAff,
               "\xef\xbb\xbfv\r\nfrom 0 0 5\r\nat 0 0 0\r\nup 0 1 0\r\nangle 40\r\nhither 1\r\n"
               "resolution 8 8\r\nx t\r\n{\r\n\tx u\r\n\t{\r\np 3\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n\t}\r\n}\r\n"
               "a 0 1 2\r\nk t\r\n{\r\nscale 4\r\n-1 1 1 1 0 0 0\r\n0 1 1 1 0 0 0\r\n1 2 2 2 0 0 0\r\n"
               "2 2 2 2 0 0 0\r\n}\r\nk u\r\n{\r\ntransl 4\r\n-1 0 0 0 0 0 0\r\n0 0 0 0 0 0 0\r\n"
               "1 0 0 1 0 0 0\r\n2 0 0 1 0 0 0\r\n}\r\n");
}

}  // namespace
}  // namespace bvhlab::test
