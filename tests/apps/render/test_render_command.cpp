// `bvhlab render` with a -D key that only structures read: said when the chosen one does not
// read it, silent when it does.
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>

using namespace bvhlab;

TEST(RenderCommand, AKeyTheStructureDoesNotReadIsAWarning) {
    const std::string args = "render -DCamera::width=16 -DCamera::height=12 -DBVH::maxLeaf=3 --out " +
                             (test::scratchDir("render_command") / "x").string();
    const test::Result embree = test::run(args + " -DASDS::type=embree");
    ASSERT_EQ(embree.exitCode, 0) << embree.output;
    EXPECT_NE(
        embree.output.find("warning: BVH::maxLeaf is read by none of the chosen structures (embree); it is ignored"),
        std::string::npos)
        << embree.output;
    const test::Result bvh = test::run(args + " -DASDS::type=sahbvh");
    ASSERT_EQ(bvh.exitCode, 0) << bvh.output;
    EXPECT_EQ(bvh.output.find("is read by none"), std::string::npos) << bvh.output;
}
