// The kd-tree plugin's parts (accel/kdtree/): perfect splits' clipping, a tree whose leaves hold
// every point of every triangle, its termination and depth bound, its work counted in events
// (the O(N log N) build: counted, never timed), answers against brute force, and the plugin end
// to end (found by name, its figures in the JSON). `bvhlab check --accel kdtree` (ctest
// CheckKdTreePlugin) holds it to the conformance suite.
#include "accel/kdtree/kdtree_accelerator.h"
#include "accel/kdtree/kdtree_builder.h"
#include "accel/kdtree/kdtree_clip.h"
#include "tests/support/bvh_checks.h"
#include "tests/support/cli_run.h"
#include "tests/support/json_figures.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <random>

namespace bvhlab::test {
namespace {

using kdtree::KdNode;
using kdtree::KdTree;

TEST(KdTreeClip, ATriangleIsClippedToTheBoxItCrosses) {
    const Bounds3 box(Vec3(0.0f), Vec3(1.0f));
    // From (-1, 0.5) to (2, 0.5) and up to (0.5, 2): inside the box it spans x in [0, 1], y from
    // 0.5 to the sloping edges.
    const Triangle tri{Vec3(-1.0f, 0.5f, 0.5f), Vec3(2.0f, 0.5f, 0.5f), Vec3(0.5f, 2.0f, 0.5f)};
    const Bounds3 b = kdtree::clippedTriangleBounds(tri, box, 0.0);
    EXPECT_EQ(b.lower, Vec3(0.0f, 0.5f, 0.5f));
    EXPECT_EQ(b.upper, Vec3(1.0f, 1.0f, 0.5f));  // flat in z: the triangle's own plane
    // Its box overlaps the box's corner, the triangle does not: no part, dropped by a perfect split.
    const Triangle corner{Vec3(1.5f, 0.6f, 0.5f), Vec3(0.6f, 1.5f, 0.5f), Vec3(1.5f, 1.5f, 0.5f)};
    EXPECT_TRUE(kdtree::clippedTriangleBounds(corner, box, 0.0).isEmpty());
    // Touching a face: kept, flat against it.
    const Triangle touching{Vec3(1.0f, 0.2f, 0.2f), Vec3(2.0f, 0.8f, 0.2f), Vec3(2.0f, 0.2f, 0.8f)};
    const Bounds3 t = kdtree::clippedTriangleBounds(touching, box, 1e-9);
    ASSERT_FALSE(t.isEmpty());
    EXPECT_EQ(t.lower.x, 1.0f);
    EXPECT_EQ(t.upper.x, 1.0f);
}

// Descends to the leaves whose closed boxes hold `p` (both children where p lies in the plane).
void leavesHolding(const KdTree& tree, uint32_t index, const Vec3& p, std::vector<uint32_t>& out) {
    const KdNode& n = tree.nodes[index];
    if (n.isLeaf()) {
        out.push_back(index);
        return;
    }
    if (p[n.axis()] <= n.split()) leavesHolding(tree, index + 1, p, out);
    if (p[n.axis()] >= n.split()) leavesHolding(tree, n.aboveChild(), p, out);
}

TEST(KdTreeBuild, EveryPointOfATriangleIsInALeafReferencingIt) {
    const Soup soup = randomSoup(2000, 43, 10.0f, 2.0f);
    const KdTree tree = kdtree::buildKdTree(soup.prims(), {});
    ASSERT_GT(tree.leaves, 100u);
    EXPECT_GT(tree.emptyLeaves, 0u);
    EXPECT_LE(tree.deepestLeaf, tree.maxDepth);
    EXPECT_EQ(tree.maxDepth, kdtree::autoMaxDepth(2000));  // 8 + 1.3 log2 2000 = 22.3
    EXPECT_EQ(tree.maxDepth, 22);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> w(0.0f, 1.0f);
    for (uint32_t prim = 0; prim < soup.triangles.size(); ++prim) {
        const Triangle& t = soup.triangles[prim];
        for (int k = 0; k < 20; ++k) {
            float a = w(rng), b = w(rng);
            if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
            const Vec3 p = k == 0 ? t.v0 : t.v0 + a * (t.v1 - t.v0) + b * (t.v2 - t.v0);
            std::vector<uint32_t> leaves;
            leavesHolding(tree, 0, p, leaves);
            bool referenced = false;
            for (uint32_t leaf : leaves) {
                const KdNode& n = tree.nodes[leaf];
                for (uint32_t i = n.firstReference(); i < n.firstReference() + n.references(); ++i)
                    referenced |= tree.references[i] == prim;
            }
            ASSERT_TRUE(referenced) << "triangle " << prim << " not referenced where its point lies";
        }
    }
}

TEST(KdTreeBuild, OneTriangleIsALeafAndTheDepthKeyBoundsTheTree) {
    Soup one;
    one.add({Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 1.0f)});
    const KdTree leaf = kdtree::buildKdTree(one.prims(), {});
    ASSERT_EQ(leaf.nodes.size(), 1u);  // no split beats K_I * 1
    EXPECT_TRUE(leaf.nodes[0].isLeaf());
    const Soup soup = randomSoup(5000, 3);
    kdtree::KdTreeParameters shallow;
    shallow.maxDepth = 4;
    const KdTree tree = kdtree::buildKdTree(soup.prims(), shallow);
    EXPECT_EQ(tree.deepestLeaf, 4);
    EXPECT_LE(tree.nodes.size(), 31u);
}

TEST(KdTreeBuild, AnEmptySideEarnsTheBonus) {
    // A cluster in one corner of a long box (a second cluster far away): the empty space between
    // is cut off by planes with one empty side, fewer of them without the bonus.
    Soup soup = randomSoup(200, 5, 1.0f, 0.2f);
    for (const Triangle& t : randomSoup(200, 6, 1.0f, 0.2f).triangles)
        soup.add({t.v0 + Vec3(100.0f, 0.0f, 0.0f), t.v1 + Vec3(100.0f, 0.0f, 0.0f), t.v2 + Vec3(100.0f, 0.0f, 0.0f)});
    kdtree::KdTreeParameters noBonus;
    noBonus.emptyBonus = 0.0;
    const KdTree with = kdtree::buildKdTree(soup.prims(), {}), without = kdtree::buildKdTree(soup.prims(), noBonus);
    EXPECT_GT(with.emptyLeaves, without.emptyLeaves);
}

// The sweeps' work is N log N shaped: the events swept over all nodes per N log2 N stay about
// level as N grows 64-fold, at the same density. Counted, not timed. That the events are sorted
// once (at the root, and the straddlers' few new ones per node) a count cannot show; the build
// times over scene sizes in the kd-tree study of docs/builders.md, "Studies", do.
TEST(KdTreeBuild, TheEventsSweptGrowAsNLogN) {
    std::vector<double> perNLogN;
    for (size_t n : {1000u, 8000u, 64000u}) {
        // The same density at every size: the soup's extent grows with the cube root of n.
        const float extent = 10.0f * std::cbrt(float(n) / 1000.0f);
        const Soup soup = randomSoup(n, 11, extent, 1.0f);
        const KdTree tree = kdtree::buildKdTree(soup.prims(), {});
        perNLogN.push_back(double(tree.eventsSwept) / (double(n) * std::log2(double(n))));
    }
    EXPECT_LT(perNLogN[2], 1.5 * perNLogN[0]) << perNLogN[0] << " " << perNLogN[1] << " " << perNLogN[2];
    EXPECT_GT(perNLogN[2], 0.5 * perNLogN[0]) << perNLogN[0] << " " << perNLogN[1] << " " << perNLogN[2];
}

TEST(KdTreeAccelerator, AgreesWithBruteForce) {
    Soup soup = randomSoup(3000, 17);
    addLatticeSquares(soup, 4, 4);  // rays along the axes on the planes of the lattice
    kdtree::KdTreeAccelerator accel({});
    accel.build(soup.prims());
    expectAgreesWithNaive(accel, soup, 4000, 10.0f, 23);
}

TEST(KdTreeAccelerator, EmptySceneAndInvalidRaysMiss) {
    const Soup empty;
    kdtree::KdTreeAccelerator accel({});
    accel.build(empty.prims());
    QueryCounters counters;
    Hit hit;
    EXPECT_FALSE(accel.findNearest(Ray{}, hit, counters));
    EXPECT_FALSE(accel.isOccluded(Ray{}, counters));
    const Soup soup = randomSoup(100, 2);
    accel.build(soup.prims());
    Ray nan;
    nan.org.x = std::nanf("");
    EXPECT_FALSE(accel.findNearest(nan, hit, counters));
    EXPECT_FALSE(hit.found());
}

TEST(KdTreePlugin, FoundByNameItsFiguresInTheJson) {
    const auto out = scratchDir("kdtree_plugin") / "image";
    const Result r =
        run("render -DCamera::width=16 -DCamera::height=12 -DASDS::type=kdtree -DKdTree::maxDepth=12 --out " +
            out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("kdtree references:"), std::string::npos) << r.output;
    std::ifstream in(out.string() + ".json");
    const std::vector<nlohmann::json> found = figuresWith(nlohmann::json::parse(in), "references");
    ASSERT_FALSE(found.empty());
    const nlohmann::json& f = found.front();
    for (const char* name : {"empty_leaves", "references", "sah_kt_ki", "max_depth_key", "events_swept"})
        EXPECT_TRUE(f.contains(name)) << name;
    EXPECT_EQ(f["max_depth_key"]["value"].get<double>(), 12.0);
}

TEST(KdTreePlugin, AKeyOutOfItsRangeIsRefused) {
    const Result r =
        run("render -DCamera::width=8 -DCamera::height=8 -DASDS::type=kdtree -DKdTree::emptyBonus=2 --out " +
            (scratchDir("kdtree_plugin") / "bad").string());
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("KdTree::emptyBonus"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace bvhlab::test
