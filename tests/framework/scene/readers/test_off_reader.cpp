// The OFF reader: vertices, faces, comments and colours, counts on the keyword line, errors.
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

TEST(ReaderFuzz, Off) {
    fuzzReader(readOff, "OFF\n# c\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 1 2 3 1 1 1\n");
}

}  // namespace
}  // namespace bvhlab::test
