// Both queries of the BVH traversal against brute force: random rays, rays along box faces, flat
// boxes, negative tmin, invalid rays, the counters, and the wide layouts; the non-robust baseline
// away from edges.
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/layout/wide_bvh.h"
#include "accel/naive/naive_accelerator.h"
#include "framework/core/timed_build.h"
#include "tests/support/bvh_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace bvhlab {
namespace {

using test::addLatticeSquares;
using test::allBuilders;
using test::buildAndCheck;
using test::expectAgreesWithNaive;
using test::randomSoup;
using test::Soup;
using test::triangleAndCopy;

// BVH::robust=false (Moeller-Trumbore, plain boxes) is not watertight at edges, but away from
// them it must give the same answers: it is a baseline for timing, not a different ray tracer.
TEST(Bvh, NonRobustTraversalAgreesAwayFromEdges) {
    const Soup soup = randomSoup(3000, 5);
    TraversalConfig traversal;
    traversal.robust = false;
    BvhAccelerator<BinaryBvh> accel(builderRecord("sahbvh"), BvhBuildConfig{}, traversal);
    buildAndCheck(accel, soup);
    expectAgreesWithNaive(accel, soup, 3000, 2.0f, 11);
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
        for (const Ray& ray : test::axisRaysThroughLattice(4)) {
            Hit expected, actual;
            QueryCounters counters;
            const bool found = naive.findNearest(ray, expected, counters);
            hits += found;
            EXPECT_EQ(found, accel.findNearest(ray, actual, counters))
                << kind.name << " from " << ray.org.x << ", " << ray.org.y << ", " << ray.org.z << " along "
                << ray.dir.x << ", " << ray.dir.y << ", " << ray.dir.z;
            EXPECT_TRUE(hitsAgree(expected, actual));
            EXPECT_EQ(naive.isOccluded(ray, counters), accel.isOccluded(ray, counters));
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
        BvhAccelerator<BinaryBvh> accel(kind, BvhBuildConfig{});
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
    BvhAccelerator<BinaryBvh> accel(builderRecord("sahbvh"), BvhBuildConfig{});
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
    BvhAccelerator<BinaryBvh> accel(builderRecord("sahbvh"), BvhBuildConfig{});
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

// The width is a template parameter: 4 (sahbvh4) and 8 are the same skeleton, robust or not.
TEST(WideBvh, FourAndEightWideAgreeWithNaive) {
    const Soup soup = randomSoup(3000, 53);
    for (bool robust : {true, false}) {
        SCOPED_TRACE(robust ? "robust" : "not robust");
        TraversalConfig traversal;
        traversal.robust = robust;
        BvhAccelerator<WideBvh<4>> four(builderRecord("sahbvh"), BvhBuildConfig{}, traversal);
        BvhAccelerator<WideBvh<8>> eight(builderRecord("sahbvh"), BvhBuildConfig{}, traversal);
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
