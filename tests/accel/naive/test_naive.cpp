// NaiveAccelerator: exact answers on known scenes (t, primitive index in load order past
// degenerate triangles, u/v), its counters (N_IT, queries, early exit of isOccluded), and
// counters merged across threads.
#include "accel/naive/naive_accelerator.h"
#include "accel/registry.h"
#include "accel/verify/comparison.h"
#include "accel/verify/generated_scenes.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/verify_keys.h"
#include "framework/core/timed_build.h"
#include "framework/scene/procedural.h"
#include "tests/support/quiet_nan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>

namespace bvhlab {
namespace {

using verify::sceneFromTriangles;

using test::kNaN;

// Four degenerate triangles (a point, an exact segment, a NaN vertex, an infinite vertex), then
// the quad (0,0,4)-(2,0,4)-(2,2,4)-(0,2,4) as primitives 4 and 5, then a degenerate one.
Scene quadBehindDegenerates() {
    Scene scene;
    scene.name = "quad";
    scene.positions = {{1, 1, 1},         {0, 0, 2}, {1, 1, 2}, {2, 2, 2}, {0, 0, kNaN},
                       {kInfinity, 0, 0}, {0, 0, 4}, {2, 0, 4}, {2, 2, 4}, {0, 2, 4}};
    scene.indices = {{0, 0, 0}, {1, 2, 3}, {4, 6, 7}, {5, 7, 8}, {6, 7, 8}, {6, 8, 9}, {1, 3, 2}};
    scene.finalize();
    return scene;
}

TEST(Naive, QuadBehindDegenerateTriangles) {
    const Scene scene = quadBehindDegenerates();
    ASSERT_EQ(scene.triangleCount(), 7u);
    ASSERT_EQ(scene.validPrimitives, (std::vector<uint32_t>{4, 5}));
    EXPECT_EQ(scene.report.degenerateTriangles, 5u);

    NaiveAccelerator naive;
    const BuildStats stats = timedBuild(naive, scene.primitives());
    EXPECT_EQ(stats.primitives, 2u);
    EXPECT_EQ(stats.nodes, 1u);
    EXPECT_EQ(stats.leaves, 1u);

    QueryCounters counters;
    Hit hit;
    // (1.5, 0.5): below the diagonal (0,0)-(2,2), in triangle 4 = (0,0),(2,0),(2,2).
    ASSERT_TRUE(naive.findNearest(Ray({1.5f, 0.5f, 0.0f}, {0, 0, 1}), hit, counters));
    EXPECT_EQ(hit.primitive, 4u);
    EXPECT_FLOAT_EQ(hit.t, 4.0f);
    // (1.5, 0.5) = (1-u-v)(0,0) + u (2,0) + v (2,2): v = 0.25, u = 0.5.
    EXPECT_NEAR(hit.u, 0.5f, 1e-6f);
    EXPECT_NEAR(hit.v, 0.25f, 1e-6f);

    // (0.5, 1.5): triangle 5 = (0,0),(2,2),(0,2): u = 0.25 (of (2,2)), v = 0.5 (of (0,2)).
    ASSERT_TRUE(naive.findNearest(Ray({0.5f, 1.5f, 8.0f}, {0, 0, -2}), hit, counters));
    EXPECT_EQ(hit.primitive, 5u);
    EXPECT_FLOAT_EQ(hit.t, 2.0f);  // t in units of dir
    EXPECT_NEAR(hit.u, 0.25f, 1e-6f);
    EXPECT_NEAR(hit.v, 0.5f, 1e-6f);

    // Straight through the degenerate ones (the point (1,1,1), the segment at z = 2) onto the
    // diagonal: only 4 or 5 may be reported, at t = 4.
    ASSERT_TRUE(naive.findNearest(Ray({1, 1, 0}, {0, 0, 1}), hit, counters));
    EXPECT_TRUE(hit.primitive == 4u || hit.primitive == 5u) << hit.primitive;
    EXPECT_FLOAT_EQ(hit.t, 4.0f);

    // A miss leaves `hit` alone.
    const Hit before{-1.0f, 77u, 0.5f, 0.5f};
    hit = before;
    EXPECT_FALSE(naive.findNearest(Ray({3, 3, 0}, {0, 0, 1}), hit, counters));
    EXPECT_EQ(hit.t, before.t);
    EXPECT_EQ(hit.primitive, before.primitive);

    // Interval: [0, 3.9] misses, [4, 4] hits, tmin just past 4 misses.
    EXPECT_FALSE(naive.findNearest(Ray({1.5f, 0.5f, 0}, {0, 0, 1}, 0.0f, 3.9f), hit, counters));
    EXPECT_TRUE(naive.findNearest(Ray({1.5f, 0.5f, 0}, {0, 0, 1}, 4.0f, 4.0f), hit, counters));
    EXPECT_FALSE(naive.findNearest(Ray({1.5f, 0.5f, 0}, {0, 0, 1}, std::nextafter(4.0f, 5.0f)), hit, counters));
    EXPECT_TRUE(naive.isOccluded(Ray({1.5f, 0.5f, 0}, {0, 0, 1}, 4.0f, 4.0f), counters));
    EXPECT_FALSE(naive.isOccluded(Ray({1.5f, 0.5f, 0}, {0, 0, 1}, 0.0f, 3.9f), counters));
}

TEST(Naive, NearestOfSeveralLayersWhateverTheOrder) {
    // Five parallel quads at z = 1..5 loaded in a shuffled order: the nearest is the one at
    // z = 1 whichever index it has, and tmin selects the layers behind.
    const float order[] = {3, 5, 1, 4, 2};
    Scene scene;
    for (const float z : order) addQuad(scene, Vec3(-1, -1, z), Vec3(2, 0, 0), Vec3(0, 2, 0), 0);
    scene.finalize();
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    QueryCounters counters;
    for (const float tmin : {0.0f, 1.5f, 2.0f, 3.25f, 4.5f}) {
        Hit hit;
        ASSERT_TRUE(naive.findNearest(Ray({0.3f, -0.2f, 0}, {0, 0, 1}, tmin), hit, counters)) << tmin;
        const float expected = std::ceil(tmin == 0.0f ? 1.0f : tmin);
        EXPECT_FLOAT_EQ(hit.t, expected) << tmin;
        const size_t quad = size_t(std::find(std::begin(order), std::end(order), expected) - std::begin(order));
        EXPECT_EQ(hit.primitive / 2, quad) << tmin;
    }
    Hit hit;
    EXPECT_FALSE(naive.findNearest(Ray({0.3f, -0.2f, 0}, {0, 0, 1}, 5.5f), hit, counters));
}

TEST(Naive, CountersPerQuery) {
    const Scene scene = quadBehindDegenerates();  // 7 triangles, 2 valid
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    QueryCounters counters;
    Hit hit;
    naive.findNearest(Ray({1.5f, 0.5f, 0}, {0, 0, 1}), hit, counters);  // hit
    EXPECT_EQ(counters.queries, 1u);
    EXPECT_EQ(counters.intersectionTests, 2u);                    // valid triangles only
    naive.findNearest(Ray({5, 5, 0}, {0, 0, 1}), hit, counters);  // miss
    EXPECT_EQ(counters.queries, 2u);
    EXPECT_EQ(counters.intersectionTests, 4u);
    naive.isOccluded(Ray({5, 5, 0}, {0, 0, 1}), counters);  // miss: tests everything
    EXPECT_EQ(counters.queries, 3u);
    EXPECT_EQ(counters.intersectionTests, 6u);
    EXPECT_EQ(counters.traversalSteps, 3u);  // one "node" per query
}

TEST(Naive, InvalidRaysCountAQueryAndNoWork) {
    const Scene scene = quadBehindDegenerates();
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    Ray nan = Ray({1.5f, 0.5f, 0}, {0, 0, 1});
    nan.org.y = kNaN;
    const Ray empty = Ray({1.5f, 0.5f, 0}, {0, 0, 1}, 5.0f, 4.0f);
    const Ray zeroDir = Ray({1.5f, 0.5f, 0}, {0, 0, 0});
    for (const Ray& ray : {nan, empty, zeroDir}) {
        QueryCounters counters;
        Hit hit;
        EXPECT_FALSE(naive.findNearest(ray, hit, counters));
        EXPECT_FALSE(hit.found());
        EXPECT_FALSE(naive.isOccluded(ray, counters));
        EXPECT_EQ(counters.queries, 2u);
        EXPECT_EQ(counters.intersectionTests, 0u);
        // findNearest and isOccluded treat a rejected ray alike: no traversal step.
        EXPECT_EQ(counters.traversalSteps, 0u);
    }
}

TEST(Naive, IsOccludedStopsAtTheFirstHit) {
    // 100 parallel quads (200 triangles) at z = 1..100 in load order. A ray through all of them
    // is blocked by the very first triangle tested; isOccluded must stop there, while
    // findNearest tests all of them.
    Scene scene;
    for (int i = 0; i < 100; ++i) addQuad(scene, Vec3(0, 0, float(i + 1)), Vec3(1, 0, 0), Vec3(0, 1, 0), 0);
    scene.finalize();
    NaiveAccelerator naive;
    naive.build(scene.primitives());

    // (0.7, 0.2) lies in the first triangle of each quad: primitive 0 blocks.
    QueryCounters occ;
    EXPECT_TRUE(naive.isOccluded(Ray({0.7f, 0.2f, 0}, {0, 0, 1}), occ));
    EXPECT_EQ(occ.intersectionTests, 1u);
    // (0.2, 0.7) lies in the second: stops after two tests.
    occ = {};
    EXPECT_TRUE(naive.isOccluded(Ray({0.2f, 0.7f, 0}, {0, 0, 1}), occ));
    EXPECT_EQ(occ.intersectionTests, 2u);
    // Only the last quad within the interval [99.5, 200]: the blocker is primitive 198.
    occ = {};
    EXPECT_TRUE(naive.isOccluded(Ray({0.7f, 0.2f, 0}, {0, 0, 1}, 99.5f, 200.0f), occ));
    EXPECT_EQ(occ.intersectionTests, 199u);
    // Not occluded: everything tested.
    occ = {};
    EXPECT_FALSE(naive.isOccluded(Ray({1.7f, 0.2f, 0}, {0, 0, 1}), occ));
    EXPECT_EQ(occ.intersectionTests, 200u);

    QueryCounters nearest;
    Hit hit;
    EXPECT_TRUE(naive.findNearest(Ray({0.7f, 0.2f, 0}, {0, 0, 1}), hit, nearest));
    EXPECT_EQ(nearest.intersectionTests, 200u);
    EXPECT_EQ(hit.primitive, 0u);
    EXPECT_FLOAT_EQ(hit.t, 1.0f);
}

TEST(Naive, EmptyAndUnbuilt) {
    NaiveAccelerator unbuilt;
    QueryCounters counters;
    Hit hit;
    EXPECT_FALSE(unbuilt.findNearest(Ray({0, 0, 0}, {0, 0, 1}), hit, counters));
    EXPECT_FALSE(unbuilt.isOccluded(Ray({0, 0, 0}, {0, 0, 1}), counters));

    const Scene empty = sceneFromTriangles({}, "empty");
    NaiveAccelerator naive;
    EXPECT_EQ(timedBuild(naive, empty.primitives()).primitives, 0u);
    counters = {};
    EXPECT_FALSE(naive.findNearest(Ray({0, 0, 0}, {0, 0, 1}), hit, counters));
    EXPECT_EQ(counters.intersectionTests, 0u);
    EXPECT_EQ(counters.queries, 1u);
}

TEST(Naive, RebuildReplacesTheScene) {
    const Scene a = sceneFromTriangles({{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}}, "a");
    const Scene b = sceneFromTriangles({{{0, 0, 3}, {1, 0, 3}, {0, 1, 3}}, {{0, 0, 2}, {1, 0, 2}, {0, 1, 2}}}, "b");
    NaiveAccelerator naive;
    naive.build(a.primitives());
    QueryCounters counters;
    Hit hit;
    ASSERT_TRUE(naive.findNearest(Ray({0.2f, 0.2f, 0}, {0, 0, 1}), hit, counters));
    EXPECT_FLOAT_EQ(hit.t, 1.0f);
    naive.build(b.primitives());
    ASSERT_TRUE(naive.findNearest(Ray({0.2f, 0.2f, 0}, {0, 0, 1}), hit, counters));
    EXPECT_FLOAT_EQ(hit.t, 2.0f);
    EXPECT_EQ(hit.primitive, 1u);
}

TEST(Naive, CreatedByTheRegistry) {
    const auto accel = createAccelerator("naive", Env(verify::verifyKeys()));
    ASSERT_NE(accel, nullptr);
    EXPECT_STREQ(accel->name(), "naive");
    EXPECT_TRUE(accel->hasCounters());
}

TEST(Naive, CountersMergedAcrossThreads) {
    const Scene scene = makeDefaultScene();
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    const size_t valid = scene.validPrimitives.size();
    const std::vector<Ray> rays =
        verify::generateRays(verify::RayKind::Outside, scene.primitives(), scene.bounds, 800, 5);

    // Single-threaded reference.
    QueryCounters single;
    std::vector<Hit> expected(rays.size());
    std::vector<char> expectedOcc(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
        naive.findNearest(rays[i], expected[i], single);
        expectedOcc[i] = naive.isOccluded(rays[i], single);
    }
    ASSERT_EQ(single.queries, 2 * rays.size());
    // findNearest tests every valid triangle; isOccluded at most that, fewer when blocked early.
    EXPECT_GT(single.intersectionTests, rays.size() * valid);
    EXPECT_LT(single.intersectionTests, 2 * rays.size() * valid);

    // Four threads, interleaved rays, one QueryCounters each, merged with +=.
    constexpr int kThreads = 4;
    std::vector<QueryCounters> perThread(kThreads);
    std::vector<Hit> got(rays.size());
    std::vector<char> gotOcc(rays.size());
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            for (size_t i = size_t(t); i < rays.size(); i += kThreads) {
                naive.findNearest(rays[i], got[i], perThread[size_t(t)]);
                gotOcc[i] = naive.isOccluded(rays[i], perThread[size_t(t)]);
            }
        });
    for (std::thread& th : threads) th.join();
    QueryCounters merged;
    for (const QueryCounters& c : perThread) {
        EXPECT_GT(c.queries, 0u);
        merged += c;
    }
    EXPECT_EQ(merged.queries, single.queries);
    EXPECT_EQ(merged.intersectionTests, single.intersectionTests);
    EXPECT_EQ(merged.traversalSteps, single.traversalSteps);
    for (size_t i = 0; i < rays.size(); ++i) {
        EXPECT_EQ(got[i].primitive, expected[i].primitive) << i;
        EXPECT_EQ(got[i].t, expected[i].t) << i;
        EXPECT_EQ(gotOcc[i], expectedOcc[i]) << i;
    }

    // += adds every field (and returns *this for chaining).
    QueryCounters a{.queries = 1, .intersectionTests = 2, .traversalSteps = 3},
        b{.queries = 10, .intersectionTests = 20, .traversalSteps = 30};
    (a += b) += b;
    EXPECT_EQ(a.queries, 21u);
    EXPECT_EQ(a.intersectionTests, 42u);
    EXPECT_EQ(a.traversalSteps, 63u);
}

TEST(Naive, AgreesWithTheDoubleOracleOnTheDefaultScene) {
    const Scene scene = makeDefaultScene();
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    const verify::Oracle oracle(scene.primitives());
    const std::vector<Ray> rays =
        verify::generateRays(verify::RayKind::Outside, scene.primitives(), scene.bounds, 1500, 9);
    const verify::ComparisonReport report = verify::compareWithNaive(naive, naive, oracle, rays);
    EXPECT_EQ(report.failures(), 0u) << report.summary();
    EXPECT_EQ(report.disagreements, 0u);
    // Random rays from outside: the hits match the oracle's (not merely "not wrong").
    EXPECT_LE(report.accelVsOracle, 2u) << report.summary();
    EXPECT_GT(report.accelHits, 300u);
}

}  // namespace
}  // namespace bvhlab
