// The BVH accelerators' structure (tdbvh, sahbvh, sweepbvh): tree invariants on random and
// adversarial scenes, the depth bound, leaf rules, SAH quality of the binning against the
// sweep, the SAH statistic itself, SIMD and scalar builds agreeing bit for bit, and a quick
// check of both queries against brute force. Hit agreement on whole scenes is tested, for
// every registered accelerator, in the cross-accelerator suite.
#include "accel/bvh/builder_table.h"
#include "accel/bvh/builders/bounds_accumulator.h"
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/bvh_env.h"
#include "accel/bvh/layout/end_point_overlap.h"
#include "accel/bvh/layout/wide_bvh.h"
#include "accel/naive/naive_accelerator.h"
#include "accel/registry.h"
#include "accel/verify/verify_keys.h"
#include "framework/core/timed_build.h"
#include "framework/scene/scene.h"
#include "tests/support/bvh_checks.h"
#include "tests/support/triangle_soup.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <set>

namespace bvhlab {
namespace {

// The builders of the table that build with the shared recursion or as ploc (sbvh: test_sbvh.cpp).
std::vector<BuilderRecord> allBuilders() {
    return {builderRecord("tdbvh"), builderRecord("sahbvh"), builderRecord("sweepbvh"), builderRecord("ploc")};
}

using test::checkTree;
using test::expectAgreesWithNaive;
using test::randomSoup;
using test::Soup;
using test::TreeFacts;

// The unit right triangle at the origin and a copy moved by `shift`: the smallest two-leaf tree.
Soup triangleAndCopy(Vec3 shift) {
    const Triangle unit{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    Soup soup;
    soup.add(unit);
    soup.add({unit.v0 + shift, unit.v1 + shift, unit.v2 + shift});
    return soup;
}

// Sizes from 1e-6 to 1e3 (log-uniform), positions over a 1e3 cube.
Soup mixedScaleSoup(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-500.0f, 500.0f), unit(-1.0f, 1.0f), exponent(-6.0f, 3.0f);
    Soup soup;
    while (soup.triangles.size() < n) {
        const float size = std::pow(10.0f, exponent(rng));
        const Vec3 p(pos(rng), pos(rng), pos(rng));
        const Triangle t{p, p + size * Vec3(unit(rng), unit(rng), unit(rng)), p + size * Vec3(unit(rng), unit(rng), unit(rng))};
        if (!isDegenerate(t)) soup.add(t);
    }
    return soup;
}

BvhBuildConfig defaultConfig() { return BvhBuildConfig{}; }

// Builds, checks the tree and that BuildStats reports what the walk found.
TreeFacts buildAndCheck(BvhAccelerator<BinaryBvh>& accel, const Soup& soup) {
    const BuildStats stats = timedBuild(accel, soup.prims());
    const TreeFacts facts = checkTree(accel.bvh(), soup);
    EXPECT_EQ(stats.primitives, soup.valid.size());
    EXPECT_EQ(stats.nodes.value_or(0), facts.nodes);
    EXPECT_EQ(stats.leaves.value_or(0), facts.leaves);
    EXPECT_EQ(stats.maxLeafPrimitives.value_or(0), facts.maxLeaf);
    EXPECT_EQ(stats.maxDepth.value_or(-1), facts.maxDepth);
    EXPECT_EQ(stats.bytes.value_or(0), accel.bvh().bytes());
    EXPECT_TRUE(stats.sah.has_value());
    return facts;
}

TEST(Bvh, NodeIsThirtyTwoBytes) {
    EXPECT_EQ(sizeof(BvhNode), 32u);
    EXPECT_EQ(sizeof(PrimRef), 32u);
}

TEST(Bvh, InvariantsOnRandomScenes) {
    const Soup soup = randomSoup(3000, 1);
    for (const BuilderRecord& kind : allBuilders()) {
        for (bool simd : {true, false}) {
            SCOPED_TRACE(kind.name + (simd ? " simd" : " scalar"));
            BvhBuildConfig config;
            config.shared.simd = simd;
            BvhAccelerator<BinaryBvh> accel(kind, config);
            buildAndCheck(accel, soup);
        }
    }
    // The other settings of each builder.
    BvhBuildConfig allAxes;
    allAxes.binnedSah.allAxes = true;
    allAxes.binnedSah.bins = 7;
    BvhBuildConfig nodeBox;
    nodeBox.spatialMedian.splitBox = MedianSplitBox::NodeBox;
    BvhBuildConfig manyBins;
    manyBins.binnedSah.bins = 256;
    for (const auto& [kind, config] : {std::pair{builderRecord("sahbvh"), allAxes}, std::pair{builderRecord("tdbvh"), nodeBox},
                                       std::pair{builderRecord("sahbvh"), manyBins}}) {
        BvhAccelerator<BinaryBvh> accel(kind, config);
        buildAndCheck(accel, soup);
    }
}

// BVH::robust=false (Moeller-Trumbore, plain boxes) is not watertight at edges, but away from
// them it must give the same answers: it is a baseline for timing, not a different ray tracer.
TEST(Bvh, NonRobustTraversalAgreesAwayFromEdges) {
    const Soup soup = randomSoup(3000, 5);
    TraversalConfig traversal;
    traversal.robust = false;
    BvhAccelerator<BinaryBvh> accel(builderRecord("sahbvh"), defaultConfig(), traversal);
    buildAndCheck(accel, soup);
    expectAgreesWithNaive(accel, soup, 3000, 2.0f, 11);
}

TEST(Bvh, TinyScenes) {
    for (size_t n : {0, 1, 2, 3}) {
        const Soup soup = randomSoup(n, 7 + uint32_t(n));
        for (const BuilderRecord& kind : allBuilders()) {
            SCOPED_TRACE(kind.name + " with " + std::to_string(n) + " triangles");
            BvhBuildConfig config;
            config.shared.maxLeaf = 1;
            config.shared.sahTermination = false;
            BvhAccelerator<BinaryBvh> accel(kind, config);
            const TreeFacts facts = buildAndCheck(accel, soup);
            EXPECT_EQ(facts.leaves, n);
            // A ray at each triangle's centroid finds it (or one equally near).
            for (uint32_t prim : soup.valid) {
                const Triangle& t = soup.triangles[prim];
                Ray ray;
                ray.org = t.centroid() + 5.0f * glm::normalize(t.geometricNormal());
                ray.dir = t.centroid() - ray.org;
                Hit hit;
                QueryCounters counters;
                ASSERT_TRUE(accel.findNearest(ray, hit, counters));
                EXPECT_LE(hit.t, 1.0001f);
                EXPECT_TRUE(accel.isOccluded(ray, counters));
                EXPECT_EQ(counters.queries, 2u);
                EXPECT_GE(counters.traversalSteps, 2u);
            }
            // Nothing to hit.
            Ray away;
            away.org = {-100, -100, -100};
            away.dir = {-1, 0, 0};
            Hit hit;
            QueryCounters counters;
            EXPECT_FALSE(accel.findNearest(away, hit, counters));
            EXPECT_FALSE(hit.found());
            EXPECT_FALSE(accel.isOccluded(away, counters));
        }
    }
}

TEST(Bvh, DegeneratePrimitivesAreNotBuiltOver) {
    // Valid lists only some triangles: the others never appear in leaves; hits report the
    // primitive index of the full list.
    Soup soup = randomSoup(50, 3);
    soup.valid = {4, 9, 10, 31, 49};
    for (const BuilderRecord& kind : allBuilders()) {
        BvhAccelerator<BinaryBvh> accel(kind, defaultConfig());
        buildAndCheck(accel, soup);
        expectAgreesWithNaive(accel, soup, 300, 10.0f, 5);
    }
}

// A BVH promises its bounds through BuildStats (what `bvhlab stress` holds it to): a depth
// below kBvhMaxDepth and leaves of at most max(maxLeaf, leafCap) primitives, and keeps them,
// here on coincident triangles, where no split separates anything.
TEST(Bvh, ReportsTheBoundsItPromisesAndKeepsThem) {
    Soup soup = randomSoup(10, 3);
    for (int i = 0; i < 3000; ++i) soup.add(soup.triangles[0]);
    BvhBuildConfig config = defaultConfig();
    config.shared.leafCap = 5;
    for (const BuilderRecord& kind : allBuilders()) {
        BvhAccelerator<BinaryBvh> accel(kind, config);
        buildAndCheck(accel, soup);
        const BuildStats stats = timedBuild(accel, soup.prims());
        ASSERT_TRUE(stats.leafBound && stats.depthBound);
        EXPECT_EQ(*stats.leafBound, 5u);
        EXPECT_EQ(*stats.depthBound, kBvhMaxDepth);
        EXPECT_LE(*stats.maxLeafPrimitives, *stats.leafBound);
        EXPECT_LT(*stats.maxDepth, *stats.depthBound);
    }
}

TEST(Bvh, WideStatisticsAreTheBinaryTreesOutsideTheBuild) {
    // build() only builds; statistics() reports the binary tree the wide layout was collapsed
    // from (kept outside T_B): its counts, SAH and EPO as fillTreeStats and endPointOverlap give
    // them, with the memory of the wide layout alone. Asked twice, the same figures; after the
    // next build, the new tree's.
    const Soup soup = randomSoup(5000, 17), other = randomSoup(700, 18);
    BvhBuildConfig config = defaultConfig();
    config.shared.sahBlockShift = 3;  // how the 8-wide accelerator builds its binary tree: leaves in blocks of 8
    for (const BuilderRecord& kind : allBuilders()) {
        SCOPED_TRACE(kind.name);
        BvhAccelerator<WideBvh<8>> wide(kind, defaultConfig());
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

TEST(Bvh, HundredThousandCoincidentTriangles) {
    Soup soup;
    for (int i = 0; i < 100000; ++i) soup.add({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    for (const BuilderRecord& kind : allBuilders()) {
        SCOPED_TRACE(kind.name);
        BvhAccelerator<BinaryBvh> accel(kind, defaultConfig());
        const BuildStats stats = timedBuild(accel, soup.prims());
        EXPECT_LT(stats.buildMs, 2000.0);
        const TreeFacts facts = checkTree(accel.bvh(), soup);
        // Split by index into halves: depth log2(100000 / leafCap) + 1.
        EXPECT_LE(facts.maxDepth, 14);
        EXPECT_LE(facts.maxLeaf, size_t(defaultConfig().shared.leafCap));

        Ray ray;
        ray.org = {0.25f, 0.25f, 1.0f};
        ray.dir = {0, 0, -1};
        Hit hit;
        QueryCounters counters;
        ASSERT_TRUE(accel.findNearest(ray, hit, counters));
        EXPECT_FLOAT_EQ(hit.t, 1.0f);
    }
    // With leafCap 1 every leaf holds one primitive even here.
    BvhBuildConfig strict;
    strict.shared.maxLeaf = 1;
    strict.shared.leafCap = 1;
    strict.shared.sahTermination = false;
    BvhAccelerator<BinaryBvh> accel(builderRecord("sahbvh"), strict);
    accel.build(soup.prims());
    EXPECT_EQ(checkTree(accel.bvh(), soup).maxLeaf, 1u);
}

TEST(Bvh, CentresOnALineOnAPlaneAndClustered) {
    Soup line, plane, clusters;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 100.0f);
    for (int i = 0; i < 4000; ++i) {
        const float x = u(rng), y = u(rng);
        line.add({{x - 1, -1, 0}, {x + 1, -1, 0}, {x, 2, 0}});        // centres on the x axis
        plane.add({{x - 1, y - 1, 0}, {x + 1, y - 1, 0}, {x, y + 2, 0}});  // centres in z = 0
        const float c = float(i % 8) * 10.0f;                          // 8 points, 500 each
        clusters.add({{c - 1, -1, 0}, {c + 1, -1, 0}, {c, 2, 0}});
    }
    for (const Soup* soup : {&line, &plane, &clusters}) {
        for (const BuilderRecord& kind : allBuilders()) {
            for (MedianSplitBox box : {MedianSplitBox::CentroidBox, MedianSplitBox::NodeBox}) {
                if (kind.name != "tdbvh" && box == MedianSplitBox::NodeBox) continue;
                BvhBuildConfig config;
                config.spatialMedian.splitBox = box;
                BvhAccelerator<BinaryBvh> accel(kind, config);
                buildAndCheck(accel, *soup);
                expectAgreesWithNaive(accel, *soup, 200, 100.0f, 13);
            }
        }
    }
}

TEST(Bvh, DepthStaysBoundedOnGeometricSpacing) {
    // Centres at x = 1.5^i: the middle of the centre box separates only the last one, so a
    // spatial median would build a chain of depth N; the builders must stop short of 64.
    Soup soup;
    for (int i = 0; i < 200; ++i) {
        const float x = std::pow(1.5f, float(i) - 100.0f);
        soup.add({{x, 0, 0}, {x * 1.01f, 0, 0}, {x, 1e-3f, 1e-3f}});
    }
    for (const BuilderRecord& kind : allBuilders()) {
        for (MedianSplitBox box : {MedianSplitBox::CentroidBox, MedianSplitBox::NodeBox}) {
            SCOPED_TRACE(kind.name);
            BvhBuildConfig config;
            config.shared.maxLeaf = 1;
            config.shared.sahTermination = false;
            config.spatialMedian.splitBox = box;
            BvhAccelerator<BinaryBvh> accel(kind, config);
            const TreeFacts facts = buildAndCheck(accel, soup);
            EXPECT_EQ(facts.leaves, soup.valid.size());
            EXPECT_LT(facts.maxDepth, kBvhMaxDepth);
            if (kind.name == "tdbvh" && box == MedianSplitBox::CentroidBox) {
                EXPECT_GE(facts.maxDepth, 40) << "the chain this test is about did not occur";
            }
        }
    }
}

TEST(Bvh, SizesFromMicrometresToKilometres) {
    const Soup soup = mixedScaleSoup(3000, 17);
    for (const BuilderRecord& kind : allBuilders()) {
        BvhAccelerator<BinaryBvh> accel(kind, defaultConfig());
        buildAndCheck(accel, soup);
        expectAgreesWithNaive(accel, soup, 1000, 1000.0f, 19);
    }
}

TEST(Bvh, AgreesWithNaiveOnRandomRays) {
    const Soup soup = randomSoup(2000, 23);
    for (const BuilderRecord& kind : allBuilders()) {
        for (int maxLeaf : {1, 4}) {
            BvhBuildConfig config;
            config.shared.maxLeaf = maxLeaf;
            BvhAccelerator<BinaryBvh> accel(kind, config);
            accel.build(soup.prims());
            expectAgreesWithNaive(accel, soup, 3000, 10.0f, 29);
        }
    }
}

TEST(Bvh, AxisParallelRaysAlongBoxFaces) {
    // Unit squares facing each axis on the lattice planes 0..4: rays along an axis start on
    // the planes of node boxes, so slab distances are 0 * inf = NaN and must be ignored rather
    // than turned into misses, also on the outer faces where no other box takes over; -0
    // direction components must behave like +0.
    Soup soup;
    test::addLatticeSquares(soup, 4, 4);
    NaiveAccelerator naive;
    naive.build(soup.prims());
    for (const BuilderRecord& kind : allBuilders()) {
        BvhBuildConfig config;
        config.shared.maxLeaf = 1;
        BvhAccelerator<BinaryBvh> accel(kind, config);
        accel.build(soup.prims());
        int hits = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            for (float a : {0.0f, 0.5f, 1.0f, 4.0f})
                for (float b : {0.0f, 0.25f, 2.0f, 4.0f})
                    for (float sign : {1.0f, -1.0f}) {
                        Ray ray;
                        ray.org[axis] = sign > 0 ? -1.0f : 6.0f;
                        ray.org[u] = a, ray.org[v] = b;
                        ray.dir = Vec3(sign < 0 ? -0.0f : 0.0f);
                        ray.dir[axis] = sign;
                        Hit expected, actual;
                        QueryCounters counters;
                        const bool found = naive.findNearest(ray, expected, counters);
                        hits += found;
                        EXPECT_EQ(found, accel.findNearest(ray, actual, counters))
                            << kind.name << " axis " << axis << " at " << a << ", " << b << " sign " << sign;
                        EXPECT_TRUE(hitsAgree(expected, actual));
                        EXPECT_EQ(naive.isOccluded(ray, counters), accel.isOccluded(ray, counters));
                    }
        }
        EXPECT_EQ(hits, 3 * 4 * 4 * 2);  // every ray hits a square facing it, edges included
    }
}

TEST(Bvh, FlatBoxesBehindTheOrigin) {
    // Axis-aligned triangles have flat boxes: near and far distances are equal, and a margin
    // that shrinks the interval for negative distances (pbrt's far * (1 + 2 gamma)) misses
    // them when the interval reaches below 0.
    Soup soup;
    for (int i = 0; i < 50; ++i) {
        const float y = float(i) * 0.37f;
        soup.add({{-4, y, -4}, {4, y, 4}, {4, y, -4}});
        soup.add({{-4, y, -4}, {-4, y, 4}, {4, y, 4}});
    }
    NaiveAccelerator naive;
    naive.build(soup.prims());
    std::mt19937 rng(53);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (const BuilderRecord& kind : allBuilders()) {
        BvhAccelerator<BinaryBvh> accel(kind, defaultConfig());
        accel.build(soup.prims());
        int hits = 0;
        for (int i = 0; i < 500; ++i) {
            Ray ray;
            ray.org = {3.0f * u(rng), 20.0f + 5.0f * u(rng), 3.0f * u(rng)};
            ray.dir = {0.1f * u(rng), 1.0f, 0.1f * u(rng)};  // pointing away from every triangle
            ray.tmin = -40.0f;
            ray.tmax = i % 2 ? kInfinity : -1.0f;
            Hit expected, actual;
            QueryCounters counters;
            const bool found = naive.findNearest(ray, expected, counters);
            hits += found;
            ASSERT_EQ(found, accel.findNearest(ray, actual, counters)) << kind.name << " ray " << i;
            EXPECT_TRUE(hitsAgree(expected, actual));
            EXPECT_EQ(naive.isOccluded(ray, counters), accel.isOccluded(ray, counters));
        }
        EXPECT_GT(hits, 400);
    }
}

// An axis-parallel ray beside a box has a far distance of -inf on that axis. The interval
// reaching below 0 must cull such boxes as the ordinary one does: with nothing behind the
// origin, tmin = -0.5 visits exactly the nodes that tmin = 0 visits.
TEST(Bvh, NegativeTminCullsAxisParallelRaysLikeTminZero) {
    const Soup soup = randomSoup(3000, 29);  // in [-1, 11]^3
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> across(0.0f, 10.0f);
    BvhAccelerator<BinaryBvh> accel(builderRecord("sahbvh"), defaultConfig());
    accel.build(soup.prims());
    for (int i = 0; i < 300; ++i) {
        const int axis = i % 3;
        Ray ray;
        ray.org = {across(rng), across(rng), across(rng)};
        ray.org[axis] = -2.0f;  // every triangle lies ahead, beyond t = 1
        ray.dir = Vec3(0.0f);
        ray.dir[axis] = 1.0f;
        QueryCounters fromZero, fromBelow;
        Hit a, b;
        const bool hitA = accel.findNearest(ray, a, fromZero);
        ray.tmin = -0.5f;
        const bool hitB = accel.findNearest(ray, b, fromBelow);
        ASSERT_EQ(hitA, hitB) << "ray " << i;
        EXPECT_EQ(fromZero.traversalSteps, fromBelow.traversalSteps) << "ray " << i;
    }
}

TEST(Bvh, InvalidRaysMissAndCountAQuery) {
    const Soup soup = randomSoup(100, 31);
    BvhAccelerator<BinaryBvh> accel(builderRecord("sahbvh"), defaultConfig());
    accel.build(soup.prims());
    Ray zero;
    zero.dir = Vec3(0.0f);
    Ray nan;
    nan.org.x = std::nanf("");
    Ray empty;
    empty.tmin = 2.0f;
    empty.tmax = 1.0f;
    for (const Ray& ray : {zero, nan, empty}) {
        QueryCounters counters;
        Hit hit;
        EXPECT_FALSE(accel.findNearest(ray, hit, counters));
        EXPECT_FALSE(accel.isOccluded(ray, counters));
        EXPECT_EQ(counters.queries, 2u);
        EXPECT_EQ(counters.intersectionTests, 0u);
    }
}

double sahOf(const BuilderRecord& kind, const BvhBuildConfig& config, const Soup& soup) {
    BvhAccelerator<BinaryBvh> accel(kind, config);
    return timedBuild(accel, soup.prims()).sah->cost;
}

TEST(Bvh, BinnedSahIsCloseToTheSweep) {
    const Soup soup = randomSoup(4000, 37, 10.0f, 0.5f);
    const double binned = sahOf(builderRecord("sahbvh"), defaultConfig(), soup);
    const double sweep = sahOf(builderRecord("sweepbvh"), defaultConfig(), soup);
    const double median = sahOf(builderRecord("tdbvh"), defaultConfig(), soup);
    EXPECT_LE(sweep, binned * 1.001);
    EXPECT_LE(binned, sweep * 1.03);
    EXPECT_LT(sweep, median);
    // More bins on every axis come closer.
    BvhBuildConfig fine;
    fine.binnedSah.bins = 64;
    fine.binnedSah.allAxes = true;
    EXPECT_LE(sahOf(builderRecord("sahbvh"), fine, soup), sweep * 1.015);
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

TEST(Bvh, CountersCountVisitsAndTests) {
    // Traversal steps: the root, then every node entered. A ray missing the scene box costs
    // one step and no test; a ray through one leaf of a 2-leaf tree costs root + leaf.
    const Soup soup = triangleAndCopy({0, 0, 5});
    BvhBuildConfig config;
    config.shared.maxLeaf = 1;
    config.shared.sahTermination = false;
    BvhAccelerator<BinaryBvh> accel(builderRecord("sahbvh"), config);
    accel.build(soup.prims());
    QueryCounters counters;
    Hit hit;
    Ray miss;
    miss.org = {5, 5, -1};
    EXPECT_FALSE(accel.findNearest(miss, hit, counters));
    EXPECT_EQ(counters.traversalSteps, 1u);
    EXPECT_EQ(counters.intersectionTests, 0u);

    counters = {};
    Ray along;
    along.org = {0.2f, 0.2f, -1.0f};
    along.dir = {0, 0, 1};
    ASSERT_TRUE(accel.findNearest(along, hit, counters));
    EXPECT_EQ(hit.primitive, 0u);
    // Both leaves are entered; the far one is dropped once the near hit is closer than its box.
    EXPECT_EQ(counters.traversalSteps, 2u);
    EXPECT_EQ(counters.intersectionTests, 1u);

    counters = {};
    along.tmin = 2.0f;
    ASSERT_TRUE(accel.findNearest(along, hit, counters));
    EXPECT_EQ(hit.primitive, 1u);
    EXPECT_EQ(counters.traversalSteps, 2u);
    EXPECT_EQ(counters.intersectionTests, 1u);
}

TEST(Bvh, RegisteredWithTheirEnvKeys) {
    const EnvRegistry& registry = verify::verifyKeys();
    for (const char* name : {"tdbvh", "sahbvh", "sahbvh4", "sahbvh8", "sweepbvh", "ploc", "ploc8"}) {
        const auto& infos = acceleratorInfos();
        const auto it = std::find_if(infos.begin(), infos.end(), [&](const AcceleratorInfo& i) { return i.name == name; });
        ASSERT_NE(it, infos.end()) << name;
        for (const std::string& key : it->envKeys) EXPECT_NE(registry.find(key), nullptr) << key;
    }
    Env env(verify::verifyKeys());
    env.set(keys::BVH::bins, "8", "test");
    env.set(keys::BVH::maxLeaf, "3", "test");
    env.set(keys::BVH::tdbvhSplit, "nodebox", "test");
    env.set(keys::BVH::optimize, "insertion", "test");
    env.set(keys::BVH::optimizeIterations, "5", "test");
    const BvhBuildConfig config = bvhSettingsFromEnv(env).build;
    EXPECT_EQ(config.optimize, BvhOptimize::Insertion);
    EXPECT_EQ(config.insertion.iterations, 5);
    EXPECT_EQ(config.binnedSah.bins, 8);
    EXPECT_EQ(config.shared.maxLeaf, 3);
    EXPECT_EQ(config.spatialMedian.splitBox, MedianSplitBox::NodeBox);
    const auto accel = createAccelerator("sahbvh", env);
    EXPECT_STREQ(accel->name(), "sahbvh");
    EXPECT_TRUE(accel->hasCounters());
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
    BinaryBvh binary = buildBvh(builderRecord("sahbvh"), defaultConfig(), soup.prims());
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
                    const Triangle tri = wide.blocks[p / TriangleBlock::kLanes].triangle(int(p % TriangleBlock::kLanes));
                    if (p >= first + count) {
                        const uint32_t last = first + count - 1;
                        const Triangle repeated = wide.blocks[last / TriangleBlock::kLanes].triangle(int(last % TriangleBlock::kLanes));
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

// The build runs the subtrees below a size as parallel jobs: the tree is the same, node for
// node and bit for bit, at 1, 2 and all threads, and it is the tree of one sequential
// depth-first build up to the order of its nodes (same node count, leaves and SAH).
TEST(Bvh, SameTreeWhateverTheThreadCount) {
    const Soup soup = randomSoup(60000, 67);
    for (const BuilderRecord& kind : {builderRecord("tdbvh"), builderRecord("sahbvh")}) {
        SCOPED_TRACE(kind.name);
        std::vector<BinaryBvh> trees;
        for (int threads : {1, 2, 0}) {
            BvhBuildConfig config = defaultConfig();
            config.shared.threads = threads;
            trees.push_back(buildBvh(kind, config, soup.prims()));
        }
        for (size_t t = 1; t < trees.size(); ++t) {
            ASSERT_EQ(trees[t].nodes.size(), trees[0].nodes.size());
            EXPECT_EQ(std::memcmp(trees[t].nodes.data(), trees[0].nodes.data(), trees[0].nodes.size() * sizeof(BvhNode)), 0);
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
        depthFirst.nodes = kind.splitRule(defaultConfig())->build(refs, {0, uint32_t(refs.size()), acc.bounds(), acc.centroidBounds()});
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

// The collapse writes large subtrees in parallel, each at a place fixed beforehand: the wide
// tree is the same, byte for byte, whatever the thread count (its subtrees are large enough here
// to be emitted as tasks).
TEST(Bvh, SameWideTreeWhateverTheThreadCount) {
    const Soup soup = randomSoup(60000, 69);
    BvhBuildConfig config = defaultConfig();
    config.shared.sahBlockShift = 3;
    const BinaryBvh binary = buildBvh(builderRecord("sahbvh"), config, soup.prims());
    const CollapseCosts costs{1.0f, 1.0f, uint32_t(config.shared.leafCap)};
    std::vector<WideBvh<8>> trees;
    for (int threads : {1, 2}) {
        tbb::task_arena arena(threads);
        arena.execute([&] { trees.push_back(collapseToWide<8>(binary, costs)); });
    }
    trees.push_back(collapseToWide<8>(binary, costs));  // outside any arena: all threads
    ASSERT_GT(trees[0].blocks.size(), 8 * 512u);  // the root's lanes reach wide_bvh.cpp's kParallelBlocks
    for (size_t t = 1; t < trees.size(); ++t) {
        ASSERT_EQ(trees[t].nodes.size(), trees[0].nodes.size());
        ASSERT_EQ(trees[t].blocks.size(), trees[0].blocks.size());
        EXPECT_EQ(std::memcmp(trees[t].nodes.data(), trees[0].nodes.data(), trees[0].nodes.size() * sizeof(WideNode<8>)), 0);
        EXPECT_EQ(std::memcmp(trees[t].blocks.data(), trees[0].blocks.data(), trees[0].blocks.size() * sizeof(TriangleBlock)), 0);
        EXPECT_EQ(trees[t].primIndices, trees[0].primIndices);
    }
}

// With leaves charged by blocks of 2^shift (the wide layouts charge blocks of eight), splitting
// a block's worth of triangles or fewer never pays: C_trav + (A_L + A_R) / A > 1 block. Charged
// per triangle (the binary layout), the same builders do split such ranges.
TEST(Bvh, SahChargedByBlocksKeepsABlockOfTrianglesTogether) {
    const Soup soup = randomSoup(3000, 61);
    for (const BuilderRecord& kind : {builderRecord("sahbvh"), builderRecord("sweepbvh")}) {
        SCOPED_TRACE(kind.name);
        for (int shift : {0, 2, 3}) {
            BvhBuildConfig config = defaultConfig();
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
            for (size_t i = 0; i < bvh.nodes.size(); ++i) smallInner += i != 1 && !bvh.nodes[i].isLeaf() && below[i] <= block;
            if (shift != 0) {
                EXPECT_EQ(smallInner, 0u);
            } else {
                EXPECT_GT(smallInner, 0u);
            }
        }
    }
}

// The width is a template parameter: 4 (sahbvh4) and 8 are the same skeleton, robust or not.
TEST(WideBvh, FourAndEightWideAgreeWithNaive) {
    const Soup soup = randomSoup(3000, 53);
    for (bool robust : {true, false}) {
        SCOPED_TRACE(robust ? "robust" : "not robust");
        TraversalConfig traversal;
        traversal.robust = robust;
        BvhAccelerator<WideBvh<4>> four(builderRecord("sahbvh"), defaultConfig(), traversal);
        BvhAccelerator<WideBvh<8>> eight(builderRecord("sahbvh"), defaultConfig(), traversal);
        four.build(soup.prims());
        const BuildStats stats = timedBuild(eight, soup.prims());
        EXPECT_STREQ(four.name(), "sahbvh4");
        EXPECT_STREQ(eight.name(), "sahbvh8");
        EXPECT_EQ(*stats.bytes, eight.bvh().bytes());
        expectAgreesWithNaive(four, soup, 2000, 2.0f, 59);
        expectAgreesWithNaive(eight, soup, 2000, 2.0f, 59);
    }
}

}  // namespace
}  // namespace bvhlab

namespace bvhlab {
namespace {

// A split rule that breaks the hook's contract: it hands back an empty left half.
class EmptyHalfSplitRule : public BvhSplitRule {
public:
    using BvhSplitRule::BvhSplitRule;

protected:
    std::optional<Split> trySplit(const BuildRange& range, bool) override {
        return Split{{range.begin, range.begin, {}, {}}, range};
    }
};

}  // namespace

// An empty half would become a node of count 0, which reads as an inner node: the recursion
// refuses it instead of building a tree that traverses garbage.
TEST(Bvh, RecursionRefusesASplitWithAnEmptyHalf) {
    std::vector<PrimRef> refs(8);
    BuildRange root{0, 8, {}, {}};
    for (uint32_t i = 0; i < 8; ++i) {
        refs[i] = {{float(i), 0.0f, 0.0f}, i, {float(i) + 0.5f, 1.0f, 1.0f}, 0};
        root.bounds.extend(Bounds3{{float(i), 0.0f, 0.0f}, {float(i) + 0.5f, 1.0f, 1.0f}});
        root.centroidBounds.extend(Vec3(float(i) + 0.25f, 0.5f, 0.5f));
    }
    BuildConfig config;
    config.maxLeaf = 1;
    EmptyHalfSplitRule builder(config);
    EXPECT_THROW(builder.build(refs, root), std::logic_error);
}

}  // namespace bvhlab

namespace bvhlab {
namespace {

// ploc is deterministic: the neighbour search, the merges and the leaf forming run over fixed
// chunks, ties broken by a total order on pairs, so the tree is the same at 1, 2 and all threads.
TEST(Ploc, SameTreeWhateverTheThreadCount) {
    const Soup soup = randomSoup(60000, 71);
    std::vector<BinaryBvh> trees;
    for (int threads : {1, 2, 0}) {
        BvhBuildConfig config = defaultConfig();
        config.shared.threads = threads;
        trees.push_back(buildBvh(builderRecord("ploc"), config, soup.prims()));
    }
    for (size_t t = 1; t < trees.size(); ++t) {
        ASSERT_EQ(trees[t].nodes.size(), trees[0].nodes.size());
        EXPECT_EQ(std::memcmp(trees[t].nodes.data(), trees[0].nodes.data(), trees[0].nodes.size() * sizeof(BvhNode)), 0);
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
    BvhAccelerator<BinaryBvh> ploc(builderRecord("ploc"), defaultConfig()), sah(builderRecord("sahbvh"), defaultConfig());
    const double plocSah = timedBuild(ploc, soup.prims()).sah->cost, binnedSah = timedBuild(sah, soup.prims()).sah->cost;
    EXPECT_LT(plocSah, 1.15 * binnedSah);
    const TreeFacts facts = checkTree(ploc.bvh(), soup);
    EXPECT_GT(facts.maxLeaf, 2u);
    EXPECT_LE(facts.maxLeaf, size_t(defaultConfig().shared.leafCap));
}

}  // namespace
}  // namespace bvhlab
