// PLOC: deterministic over thread counts, chains of clusters rebuilt within the depth bound,
// coincident triangles paired, its SAH near the binned build's.
#include "accel/bvh/bvh_accelerator.h"
#include "framework/core/timed_build.h"
#include "tests/support/bvh_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace bvhlab {
namespace {

using test::buildAndCheck;
using test::checkTree;
using test::randomSoup;
using test::Soup;
using test::TreeFacts;

// ploc is deterministic: the neighbour search, the merges and the leaf forming run over fixed
// chunks, ties broken by a total order on pairs, so the tree is the same at 1, 2 and all threads.
TEST(Ploc, SameTreeWhateverTheThreadCount) {
    const Soup soup = randomSoup(60000, 71);
    std::vector<BinaryBvh> trees;
    for (int threads : {1, 2, 0}) {
        BvhBuildConfig config = BvhBuildConfig{};
        config.shared.threads = threads;
        trees.push_back(buildBvh(builderRecord("ploc"), config, soup.prims()));
    }
    for (size_t t = 1; t < trees.size(); ++t) {
        ASSERT_EQ(trees[t].nodes.size(), trees[0].nodes.size());
        EXPECT_EQ(std::memcmp(trees[t].nodes.data(), trees[0].nodes.data(), trees[0].nodes.size() * sizeof(BvhNode)),
                  0);
        EXPECT_EQ(trees[t].primIndices, trees[0].primIndices);
    }
}

// Boxes on a line, each 1.5 times further out and larger: each cluster's nearest neighbour is
// the cluster of all nearer ones, so the clustering is a chain N - 1 deep. The subtrees that
// would reach kBvhMaxDepth are rebuilt by binned SAH from depth 32: the tree keeps every
// primitive once and stays below the bound, and is deeper than 32 (the chain did occur).
TEST(Ploc, ChainOfClustersIsRebuiltWithinTheDepthBound) {
    Soup soup;
    for (int i = 0; i < 300; ++i) {
        const float x = std::pow(1.5f, float(i) - 150.0f);
        soup.add({{x, 0, 0}, {x * 1.2f, 0, 0}, {x, x * 0.2f, x * 0.2f}});
    }
    BvhBuildConfig config;
    config.shared.maxLeaf = 1;
    config.shared.sahTermination = false;
    BvhAccelerator<BinaryBvh> accel(builderRecord("ploc"), config);
    const TreeFacts facts = buildAndCheck(accel, soup);
    EXPECT_EQ(facts.leaves, soup.valid.size());
    EXPECT_LT(facts.maxDepth, kBvhMaxDepth);
    EXPECT_GT(facts.maxDepth, kBvhMaxDepth / 2) << "the chain this test is about did not occur";
}

// Equal boxes (all distances tie) pair up 0-1, 2-3, ... each iteration: a balanced tree, not a
// chain of one merge per iteration.
TEST(Ploc, CoincidentTrianglesPairUp) {
    Soup soup;
    for (int i = 0; i < 1024; ++i) soup.add({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    BvhBuildConfig config;
    config.shared.maxLeaf = 1;
    config.shared.sahTermination = false;
    BvhAccelerator<BinaryBvh> accel(builderRecord("ploc"), config);
    const TreeFacts facts = buildAndCheck(accel, soup);
    EXPECT_EQ(facts.maxDepth, 10);
}

// The clustering's tree with SAH-formed leaves is as good by SAH as the binned top-down build
// on a soup (within 15 %), and its leaves hold up to leafCap primitives.
TEST(Ploc, SahNearTheBinnedBuild) {
    const Soup soup = randomSoup(20000, 73);
    BvhAccelerator<BinaryBvh> ploc(builderRecord("ploc"), BvhBuildConfig{}),
        sah(builderRecord("sahbvh"), BvhBuildConfig{});
    const double plocSah = timedBuild(ploc, soup.prims()).sah->cost,
                 binnedSah = timedBuild(sah, soup.prims()).sah->cost;
    EXPECT_LT(plocSah, 1.15 * binnedSah);
    const TreeFacts facts = checkTree(ploc.bvh(), soup);
    EXPECT_GT(facts.maxLeaf, 2u);
    EXPECT_LE(facts.maxLeaf, size_t(BvhBuildConfig{}.shared.leafCap));
}

}  // namespace
}  // namespace bvhlab
