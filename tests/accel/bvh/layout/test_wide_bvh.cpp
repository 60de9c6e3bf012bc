// The layouts: the binary node's size, the wide tree's statistics, the collapse from binary to
// 4- and 8-wide nodes keeping every triangle once, and the wide tree's independence of threads.
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/layout/end_point_overlap.h"
#include "accel/bvh/layout/wide_bvh.h"
#include "framework/core/timed_build.h"
#include "tests/support/bvh_checks.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <set>

namespace bvhlab {
namespace {

using test::allBuilders;
using test::randomSoup;
using test::Soup;

TEST(Bvh, NodeIsThirtyTwoBytes) {
    EXPECT_EQ(sizeof(BvhNode), 32u);
    EXPECT_EQ(sizeof(PrimRef), 32u);
}

TEST(Bvh, WideStatisticsAreTheBinaryTreesOutsideTheBuild) {
    // build() only builds; statistics() reports the binary tree the wide layout was collapsed
    // from (kept outside T_B): its counts, SAH and EPO as fillTreeStats and endPointOverlap give
    // them, with the memory of the wide layout alone. Asked twice, the same figures; after the
    // next build, the new tree's.
    const Soup soup = randomSoup(5000, 17), other = randomSoup(700, 18);
    BvhBuildConfig config = BvhBuildConfig{};
    config.shared.sahBlockShift = 3;  // how the 8-wide accelerator builds its binary tree: leaves in blocks of 8
    for (const BuilderRecord& kind : allBuilders()) {
        SCOPED_TRACE(kind.name);
        BvhAccelerator<WideBvh<8>> wide(kind, BvhBuildConfig{});
        for (const Soup* s : {&soup, &other}) {
            wide.build(s->prims());
            const BuildStats stats = wide.buildStats();
            const BinaryBvh binary = buildBvh(kind, config, s->prims());
            BuildStats expected;
            fillTreeStats(binary, config.shared.cTraversal, config.shared.cIntersect, expected);
            EXPECT_EQ(stats.primitives, s->valid.size());
            EXPECT_EQ(stats.nodes, expected.nodes);
            EXPECT_EQ(stats.leaves, expected.leaves);
            EXPECT_EQ(stats.maxDepth, expected.maxDepth);
            EXPECT_EQ(stats.leafSizes, expected.leafSizes);
            ASSERT_TRUE(stats.sah.has_value());
            EXPECT_EQ(stats.sah->cost, expected.sah->cost);
            ASSERT_TRUE(stats.epo.has_value());
            EXPECT_EQ(*stats.epo, endPointOverlap(binary.nodes, binary.leafTriangles, config.shared.cTraversal,
                                                  config.shared.cIntersect, config.shared.threads));
            EXPECT_EQ(stats.bytes, wide.bvh().bytes());
            EXPECT_EQ(wide.buildStats().epo, stats.epo);
            EXPECT_EQ(wide.buildStats().nodes, stats.nodes);
        }
    }
}

// The collapse keeps every triangle once: each wide leaf holds the triangles of one binary
// subtree (a binary leaf, or small ones merged, never more than the leaf cap) left to right,
// each lane naming its primitive and holding that primitive's triangle, in blocks of its own
// whose padding lanes are kInvalidPrimitive point triangles; merging only ever saves blocks.
// Inner lanes point at wide nodes (each with one parent), unused lanes are empty boxes, and no
// wide node has fewer than two lanes (or one: a root that is a single leaf).
template <int N>
void expectCollapseKeepsEveryTriangleOnce(size_t n, uint32_t seed) {
    using Leaf = std::vector<uint32_t>;  // primitives in lane order
    constexpr uint32_t kLeafCap = 16;
    const Soup soup = randomSoup(n, seed);
    BinaryBvh binary = buildBvh(builderRecord("sahbvh"), BvhBuildConfig{}, soup.prims());
    // Every binary subtree's primitives, left to right (children come after their parent).
    std::vector<Leaf> below(binary.nodes.size());
    size_t binaryBlocks = 0;
    for (size_t i = binary.nodes.size(); i-- > 0;) {
        const BvhNode& node = binary.nodes[i];
        if (i == 1) continue;
        if (node.isLeaf()) {
            below[i].assign(&binary.primIndices[node.index], &binary.primIndices[node.index] + node.count);
            binaryBlocks += blocksFor(node.count);
        } else {
            below[i] = below[node.index];
            below[i].insert(below[i].end(), below[node.index + 1].begin(), below[node.index + 1].end());
        }
    }
    const std::set<Leaf> subtrees(below.begin(), below.end());
    const bool rootIsLeaf = binary.nodes[0].isLeaf();
    const WideBvh<N> wide = collapseToWide<N>(std::move(binary), {1.0f, 1.0f, kLeafCap});
    ASSERT_LE(wide.blocks.size(), binaryBlocks);
    ASSERT_EQ(wide.primIndices.size(), wide.blocks.size() * TriangleBlock::kLanes);

    std::vector<int> seen(soup.triangles.size(), 0);
    std::vector<int> blockOwners(wide.blocks.size(), 0);
    std::vector<int> parents(wide.nodes.size(), 0);
    for (const WideNode<N>& node : wide.nodes) {
        int used = 0;
        for (int i = 0; i < N; ++i) {
            const bool empty = node.lower[0][i] > node.upper[0][i];
            if (empty) {
                EXPECT_EQ(node.child[i], 0u);
                continue;
            }
            ++used;
            if (wide_child::isLeaf(node.child[i])) {
                const uint32_t firstBlock = wide_child::firstBlock(node.child[i]);
                const uint32_t blocks = wide_child::blocks(node.child[i]);
                const uint32_t count = wide.trianglesIn(firstBlock, blocks);
                EXPECT_LE(count, kLeafCap);
                EXPECT_EQ(blocks, blocksFor(count));
                Leaf leaf;
                const uint32_t first = firstBlock * TriangleBlock::kLanes;
                ASSERT_LE(firstBlock + blocks, wide.blocks.size());
                for (uint32_t b = firstBlock; b < firstBlock + blocks; ++b) ++blockOwners[b];
                for (uint32_t p = first; p < first + blocks * TriangleBlock::kLanes; ++p) {
                    const Triangle tri =
                        wide.blocks[p / TriangleBlock::kLanes].triangle(int(p % TriangleBlock::kLanes));
                    if (p >= first + count) {
                        const uint32_t last = first + count - 1;
                        const Triangle repeated =
                            wide.blocks[last / TriangleBlock::kLanes].triangle(int(last % TriangleBlock::kLanes));
                        EXPECT_EQ(wide.primIndices[p], kInvalidPrimitive);
                        EXPECT_TRUE(tri.v0 == repeated.v0 && tri.v1 == repeated.v1 && tri.v2 == repeated.v2)
                            << "padding repeats the leaf's last triangle";
                        continue;
                    }
                    const uint32_t prim = wide.primIndices[p];
                    ASSERT_LT(prim, soup.triangles.size());
                    const Triangle& original = soup.triangles[prim];
                    EXPECT_TRUE(tri.v0 == original.v0 && tri.v1 == original.v1 && tri.v2 == original.v2)
                        << "lane " << p << " holds primitive " << prim << "'s triangle";
                    ++seen[prim];
                    leaf.push_back(prim);
                    const Bounds3 box = tri.bounds();
                    for (int a = 0; a < 3; ++a) {
                        EXPECT_LE(node.lower[a][i], box.lower[a]);
                        EXPECT_GE(node.upper[a][i], box.upper[a]);
                    }
                }
                EXPECT_EQ(subtrees.count(leaf), 1u) << "a wide leaf is one binary subtree, left to right";
            } else {
                ASSERT_LT(node.child[i], wide.nodes.size());
                ++parents[node.child[i]];
            }
        }
        EXPECT_GE(used, rootIsLeaf ? 1 : 2);
        for (int octant = 0; octant < 8; ++octant) {  // every lane once, the empty ones farthest
            int lanes = 0, position = 0;
            for (int p = 0; p < N; ++p) {
                const int lane = int(node.order[p] >> (3 * octant) & 7);
                lanes |= 1 << lane;
                if (node.lower[0][lane] > node.upper[0][lane]) {
                    EXPECT_EQ(p, position++) << "octant " << octant;
                }
            }
            EXPECT_EQ(lanes, (1 << N) - 1) << "octant " << octant;
        }
    }
    for (uint32_t prim : soup.valid) EXPECT_EQ(seen[prim], 1) << "primitive " << prim;
    for (int owners : blockOwners) EXPECT_EQ(owners, 1);
    EXPECT_EQ(parents[0], 0);
    for (size_t i = 1; i < parents.size(); ++i) EXPECT_EQ(parents[i], 1) << "wide node " << i;
    // The binary tree here charges single triangles (leaves of one to four): many of its small
    // sibling leaves share a block once merged.
    if (n >= 3000) {
        EXPECT_LT(wide.blocks.size(), binaryBlocks * 3 / 4);
    }
}

TEST(WideBvh, CollapseKeepsEveryTriangleOnce) {
    for (size_t n : {size_t(1), size_t(2), size_t(7), size_t(3000)}) {  // 1 and 2: the root is a leaf
        SCOPED_TRACE(n);
        expectCollapseKeepsEveryTriangleOnce<4>(n, 41 + uint32_t(n));
        expectCollapseKeepsEveryTriangleOnce<8>(n, 41 + uint32_t(n));
    }
}

// The collapse weighs a merged leaf against its parts by SAH: two leaves of 3 and 4 triangles
// over the same unit square cost two block tests wherever a ray hits one, so they become one
// leaf of one block (here the root's only lane); the same leaves 100 units apart are rarely
// both hit and stay two lanes. A merge never exceeds the leaf cap.
TEST(WideBvh, CollapseMergesSiblingLeavesWhenOneBlockPays) {
    const auto twoLeaves = [](Vec3 shift) {
        BinaryBvh bvh;
        for (uint32_t i = 0; i < 7; ++i) {
            const Vec3 s = i < 3 ? Vec3(0.0f) : shift;
            const float f = 0.1f * float(i);
            bvh.leafTriangles.push_back({s + Vec3(f, 0, 0), s + Vec3(1, f, 0), s + Vec3(0, 1, f)});
            bvh.primIndices.push_back(10 + i);
        }
        const auto boxOf = [&](uint32_t begin, uint32_t end) {
            Bounds3 b;
            for (uint32_t i = begin; i < end; ++i) b.extend(bvh.leafTriangles[i].bounds());
            return b;
        };
        bvh.nodes.resize(4);
        bvh.nodes[0].setBox(boxOf(0, 7)), bvh.nodes[0].index = 2, bvh.nodes[0].count = 0;
        bvh.nodes[1] = BvhNode{{0, 0, 0, 0, 0, 0}, 0, 0};
        bvh.nodes[2].setBox(boxOf(0, 3)), bvh.nodes[2].index = 0, bvh.nodes[2].count = 3;
        bvh.nodes[3].setBox(boxOf(3, 7)), bvh.nodes[3].index = 3, bvh.nodes[3].count = 4;
        return bvh;
    };
    const CollapseCosts costs{1.0f, 1.0f, 16};

    const WideBvh<8> merged = collapseToWide<8>(twoLeaves(Vec3(0.0f)), costs);
    ASSERT_EQ(merged.nodes.size(), 1u);
    EXPECT_EQ(merged.nodes[0].child[0], wide_child::leaf(0, 1));
    EXPECT_GT(merged.nodes[0].lower[0][1], merged.nodes[0].upper[0][1]) << "lane 1 is empty";
    ASSERT_EQ(merged.blocks.size(), 1u);
    for (uint32_t lane = 0; lane < 7; ++lane) EXPECT_EQ(merged.primIndices[lane], 10 + lane);
    EXPECT_EQ(merged.primIndices[7], kInvalidPrimitive);

    const WideBvh<8> apart = collapseToWide<8>(twoLeaves(Vec3(100.0f, 0.0f, 0.0f)), costs);
    ASSERT_EQ(apart.nodes.size(), 1u);
    EXPECT_EQ(apart.nodes[0].child[0], wide_child::leaf(0, 1));
    EXPECT_EQ(apart.nodes[0].child[1], wide_child::leaf(1, 1));
    EXPECT_EQ(apart.trianglesIn(0, 1), 3u);
    EXPECT_EQ(apart.trianglesIn(1, 1), 4u);
    EXPECT_EQ(apart.blocks.size(), 2u);

    const WideBvh<8> capped = collapseToWide<8>(twoLeaves(Vec3(0.0f)), {1.0f, 1.0f, 6});
    EXPECT_EQ(capped.trianglesIn(wide_child::firstBlock(capped.nodes[0].child[0]), 1), 3u);
    EXPECT_EQ(capped.trianglesIn(wide_child::firstBlock(capped.nodes[0].child[1]), 1), 4u);
}

// The collapse writes large subtrees in parallel, each at a place fixed beforehand: the wide
// tree is the same, byte for byte, whatever the thread count (its subtrees are large enough here
// to be emitted as tasks).
TEST(Bvh, SameWideTreeWhateverTheThreadCount) {
    const Soup soup = randomSoup(60000, 69);
    BvhBuildConfig config = BvhBuildConfig{};
    config.shared.sahBlockShift = 3;
    const BinaryBvh binary = buildBvh(builderRecord("sahbvh"), config, soup.prims());
    const CollapseCosts costs{1.0f, 1.0f, uint32_t(config.shared.leafCap)};
    std::vector<WideBvh<8>> trees;
    for (int threads : {1, 2}) {
        tbb::task_arena arena(threads);
        arena.execute([&] { trees.push_back(collapseToWide<8>(binary, costs)); });
    }
    trees.push_back(collapseToWide<8>(binary, costs));  // outside any arena: all threads
    ASSERT_GT(trees[0].blocks.size(), 8 * 512u);        // the root's lanes reach wide_bvh.cpp's kParallelBlocks
    for (size_t t = 1; t < trees.size(); ++t) {
        ASSERT_EQ(trees[t].nodes.size(), trees[0].nodes.size());
        ASSERT_EQ(trees[t].blocks.size(), trees[0].blocks.size());
        EXPECT_EQ(
            std::memcmp(trees[t].nodes.data(), trees[0].nodes.data(), trees[0].nodes.size() * sizeof(WideNode<8>)), 0);
        EXPECT_EQ(
            std::memcmp(trees[t].blocks.data(), trees[0].blocks.data(), trees[0].blocks.size() * sizeof(TriangleBlock)),
            0);
        EXPECT_EQ(trees[t].primIndices, trees[0].primIndices);
    }
}

}  // namespace
}  // namespace bvhlab
