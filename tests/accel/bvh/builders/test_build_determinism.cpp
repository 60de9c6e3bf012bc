// A build is a function of the scene and the config alone: SIMD and scalar binning build the same
// tree, and so do 1, 2 and all threads.
#include "accel/bvh/builders/bounds_accumulator.h"
#include "accel/bvh/bvh_accelerator.h"
#include "tests/support/bvh_checks.h"

#include <gtest/gtest.h>

#include <cstring>

namespace bvhlab {
namespace {

using test::allBuilders;
using test::mixedScaleSoup;
using test::randomSoup;
using test::Soup;

TEST(Bvh, SimdAndScalarBuildTheSameTree) {
    const Soup soups[] = {randomSoup(5000, 43), mixedScaleSoup(3000, 47)};
    for (const Soup& soup : soups) {
        for (const BuilderRecord& kind : allBuilders()) {
            for (bool allAxes : {false, true}) {
                if (allAxes && kind.name != "sahbvh") continue;
                BvhBuildConfig config;
                config.binnedSah.allAxes = allAxes;
                BvhAccelerator<BinaryBvh> simd(kind, config);
                config.shared.simd = false;
                BvhAccelerator<BinaryBvh> scalar(kind, config);
                simd.build(soup.prims());
                scalar.build(soup.prims());
                const BinaryBvh &a = simd.bvh(), &b = scalar.bvh();
                ASSERT_EQ(a.nodes.size(), b.nodes.size()) << kind.name;
                EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BvhNode)), 0)
                    << kind.name << (allAxes ? " all axes" : "");
                EXPECT_EQ(a.primIndices, b.primIndices);
            }
        }
    }
}

// The build runs the subtrees below a size as parallel jobs: the tree is the same, node for
// node and bit for bit, at 1, 2 and all threads, and it is the tree of one sequential
// depth-first build up to the order of its nodes (same node count, leaves and SAH).
TEST(Bvh, SameTreeWhateverTheThreadCount) {
    const Soup soup = randomSoup(60000, 67);
    for (const BuilderRecord& kind : {builderRecord("tdbvh"), builderRecord("sahbvh")}) {
        SCOPED_TRACE(kind.name);
        std::vector<BinaryBvh> trees;
        for (int threads : {1, 2, 0}) {
            BvhBuildConfig config = BvhBuildConfig{};
            config.shared.threads = threads;
            trees.push_back(buildBvh(kind, config, soup.prims()));
        }
        for (size_t t = 1; t < trees.size(); ++t) {
            ASSERT_EQ(trees[t].nodes.size(), trees[0].nodes.size());
            EXPECT_EQ(
                std::memcmp(trees[t].nodes.data(), trees[0].nodes.data(), trees[0].nodes.size() * sizeof(BvhNode)), 0);
            EXPECT_EQ(trees[t].primIndices, trees[0].primIndices);
        }
        BuildStats parallel, sequential;
        fillTreeStats(trees[0], 1.0, 1.0, parallel);
        // One builder, nothing deferred: the depth-first tree.
        PrimitiveSet prims = soup.prims();
        std::vector<PrimRef> refs(prims.valid.size());
        BoundsAccumulator<simd::Scalar<4>> acc;
        for (size_t i = 0; i < refs.size(); ++i) {
            const Bounds3 b = prims.triangles[prims.valid[i]].bounds();
            refs[i] = PrimRef{{b.lower.x, b.lower.y, b.lower.z}, prims.valid[i], {b.upper.x, b.upper.y, b.upper.z}, 0};
            acc.add(refs[i]);
        }
        BinaryBvh depthFirst;
        depthFirst.nodes = kind.splitRule(BvhBuildConfig{})
                               ->build(refs, {0, uint32_t(refs.size()), acc.bounds(), acc.centroidBounds()});
        depthFirst.primIndices.resize(refs.size());
        for (size_t i = 0; i < refs.size(); ++i) depthFirst.primIndices[i] = refs[i].prim;
        depthFirst.leafTriangles.resize(refs.size());
        fillTreeStats(depthFirst, 1.0, 1.0, sequential);
        EXPECT_EQ(parallel.nodes, sequential.nodes);
        EXPECT_EQ(parallel.leaves, sequential.leaves);
        EXPECT_EQ(parallel.sah->cost, sequential.sah->cost);
        EXPECT_EQ(trees[0].primIndices, depthFirst.primIndices);
    }
}

}  // namespace
}  // namespace bvhlab
