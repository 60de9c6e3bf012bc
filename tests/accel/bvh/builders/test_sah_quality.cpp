// The SAH the builders reach and report: binning close to the full sweep, termination that makes
// multi-primitive leaves, the reported cost by its formula, and leaves charged by blocks.
#include "accel/bvh/bvh_accelerator.h"
#include "framework/core/timed_build.h"
#include "tests/support/bvh_checks.h"

#include <gtest/gtest.h>

namespace bvhlab {
namespace {

using test::checkTree;
using test::randomSoup;
using test::Soup;
using test::triangleAndCopy;

double sahOfBuild(const BuilderRecord& kind, const BvhBuildConfig& config, const Soup& soup) {
    BvhAccelerator<BinaryBvh> accel(kind, config);
    return timedBuild(accel, soup.prims()).sah->cost;
}

TEST(Bvh, BinnedSahIsCloseToTheSweep) {
    const Soup soup = randomSoup(4000, 37, 10.0f, 0.5f);
    const double binned = sahOfBuild(builderRecord("sahbvh"), BvhBuildConfig{}, soup);
    const double sweep = sahOfBuild(builderRecord("sweepbvh"), BvhBuildConfig{}, soup);
    const double median = sahOfBuild(builderRecord("tdbvh"), BvhBuildConfig{}, soup);
    EXPECT_LE(sweep, binned * 1.001);
    EXPECT_LE(binned, sweep * 1.03);
    EXPECT_LT(sweep, median);
    // More bins on every axis come closer.
    BvhBuildConfig fine;
    fine.binnedSah.bins = 64;
    fine.binnedSah.allAxes = true;
    EXPECT_LE(sahOfBuild(builderRecord("sahbvh"), fine, soup), sweep * 1.015);
}

TEST(Bvh, SahTerminationMakesMultiPrimitiveLeaves) {
    // Dense, overlapping triangles: splitting does not pay near the bottom.
    const Soup soup = randomSoup(3000, 41, 5.0f, 1.0f);
    for (const BuilderRecord& kind : {builderRecord("sahbvh"), builderRecord("sweepbvh")}) {
        BvhBuildConfig config;
        config.shared.maxLeaf = 1;
        config.shared.cTraversal = 2.0f;
        BvhAccelerator<BinaryBvh> accel(kind, config);
        const BuildStats stats = timedBuild(accel, soup.prims());
        EXPECT_GT(*stats.avgLeafPrimitives, 1.5) << kind.name;
        EXPECT_LE(*stats.maxLeafPrimitives, size_t(config.shared.leafCap));
        checkTree(accel.bvh(), soup);

        config.shared.sahTermination = false;
        BvhAccelerator<BinaryBvh> single(kind, config);
        const BuildStats one = timedBuild(single, soup.prims());
        EXPECT_EQ(*one.leaves, soup.valid.size());
        EXPECT_EQ(*one.maxLeafPrimitives, 1u);
        EXPECT_EQ(*one.nodes, 2 * soup.valid.size() - 1);
        // Termination exists to lower the cost it tests against.
        EXPECT_LT(stats.sah->cost, one.sah->cost);
    }
}

TEST(Bvh, SahCostFollowsTheStatedFormula) {
    // Two unit triangles far apart, one per leaf: the root is the only inner node.
    const Soup soup = triangleAndCopy({9, 9, 9});
    BvhBuildConfig config;
    config.shared.maxLeaf = 1;
    config.shared.cTraversal = 2.0f;
    config.shared.cIntersect = 3.0f;
    BvhAccelerator<BinaryBvh> accel(builderRecord("sahbvh"), config);
    const BuildStats stats = timedBuild(accel, soup.prims());
    ASSERT_EQ(*stats.nodes, 3u);
    const double rootArea = Bounds3({0, 0, 0}, {10, 10, 9}).halfArea();
    const double leafArea = Bounds3({0, 0, 0}, {1, 1, 0}).halfArea();
    EXPECT_NEAR(stats.sah->cost, 2.0 + 3.0 * 2.0 * leafArea / rootArea, 1e-9);
    EXPECT_EQ(stats.sah->cTraversal, 2.0);
    EXPECT_EQ(stats.sah->cIntersect, 3.0);
    EXPECT_EQ(*stats.maxDepth, 1);
    EXPECT_DOUBLE_EQ(*stats.avgLeafPrimitives, 1.0);
}

// With leaves charged by blocks of 2^shift (the wide layouts charge blocks of eight), splitting
// a block's worth of triangles or fewer never pays: C_trav + (A_L + A_R) / A > 1 block. Charged
// per triangle (the binary layout), the same builders do split such ranges.
TEST(Bvh, SahChargedByBlocksKeepsABlockOfTrianglesTogether) {
    const Soup soup = randomSoup(3000, 61);
    for (const BuilderRecord& kind : {builderRecord("sahbvh"), builderRecord("sweepbvh")}) {
        SCOPED_TRACE(kind.name);
        for (int shift : {0, 2, 3}) {
            BvhBuildConfig config = BvhBuildConfig{};
            config.shared.sahBlockShift = shift;
            const BinaryBvh bvh = buildBvh(kind, config, soup.prims());
            // Triangles below each node, children before parents (pairs follow their parent).
            std::vector<uint32_t> below(bvh.nodes.size(), 0);
            for (size_t i = bvh.nodes.size(); i-- > 0;) {
                const BvhNode& n = bvh.nodes[i];
                if (i == 1) continue;
                below[i] = n.isLeaf() ? n.count : below[n.index] + below[n.index + 1];
            }
            size_t smallInner = 0;
            const uint32_t block = shift == 0 ? 4u : 1u << shift;
            for (size_t i = 0; i < bvh.nodes.size(); ++i)
                smallInner += i != 1 && !bvh.nodes[i].isLeaf() && below[i] <= block;
            if (shift != 0) {
                EXPECT_EQ(smallInner, 0u);
            } else {
                EXPECT_GT(smallInner, 0u);
            }
        }
    }
}

}  // namespace
}  // namespace bvhlab
