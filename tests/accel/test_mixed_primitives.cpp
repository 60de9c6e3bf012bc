// Scenes that mix triangles, spheres and cones (NFF's native primitives): the counters by kind,
// and rays leaving a quadric. Every registered accelerator's closest and any hits on them against
// a double-precision brute force are the conformance suite's mixed-primitives check
// (accel/verify/conformance.h, tests/accel/verify/test_conformance.cpp).
#include "accel/naive/naive_accelerator.h"
#include "accel/registry.h"
#include "accel/verify/conformance.h"
#include "accel/verify/generated_scenes.h"
#include "accel/verify/verify_keys.h"
#include "framework/core/timed_build.h"
#include "framework/scene/surface_point.h"
#include "tests/support/random_geometry.h"

#include <gtest/gtest.h>

#include <random>

namespace bvhlab {
namespace {

using test::randomPointWithin;
using test::randomUnit;

// Counters by kind: what naive tests per query is known exactly.
TEST(MixedPrimitives, NaiveCountsEveryKind) {
    const Scene scene = verify::makeMixedScene(3);
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    QueryCounters counters;
    Hit hit;
    naive.findNearest({Vec3(50), Vec3(1)}, hit, counters);
    EXPECT_EQ(counters.intersectionTests, 900u);
    EXPECT_EQ(counters.sphereTests, 300u);
    EXPECT_EQ(counters.coneTests, 300u);
    EXPECT_EQ(counters.triangleTests(), 300u);
}

// The BVHs count quadric tests by kind too, and test far fewer than naive.
TEST(MixedPrimitives, BvhCountsQuadricTestsByKind) {
    const Scene scene = verify::makeMixedScene(5);
    const auto accel = createAccelerator("sahbvh8", Env(verify::verifyKeys()));
    const BuildStats stats = timedBuild(*accel, scene.primitives());
    EXPECT_EQ(stats.primitives, scene.validPrimitives.size());
    ASSERT_TRUE(stats.leaves && stats.nodes && stats.sah);
    QueryCounters counters;
    size_t hits = 0;
    for (const Sphere& s : std::span(scene.spheres).first(100)) {
        Hit hit;
        hits += accel->findNearest({Vec3(40), s.centre - Vec3(40)}, hit, counters);
    }
    EXPECT_GE(hits, 95u);  // aimed at the centres (the degenerate one is the last of 301)
    EXPECT_GT(counters.sphereTests, 0u);
    EXPECT_GT(counters.coneTests + counters.triangleTests(), 0u);
    EXPECT_LT(counters.intersectionTests, 100u * 900u / 10u);
}

// A ray leaving a sphere or a cone outward from its surface (surfaceAt's origin) never finds
// that primitive again: both are convex seen from outside.
TEST(MixedPrimitives, RaysLeavingAQuadricOutwardDoNotHitItAgain) {
    const Scene scene = verify::makeMixedScene(9);
    const PrimitiveSet prims = scene.primitives();
    NaiveAccelerator naive;
    naive.build(prims);
    std::mt19937 rng(1);
    size_t leaving = 0;
    for (uint32_t prim : prims.validQuadrics()) {
        const QuadricShape shape = prims.quadric(prim);
        const Vec3 centre(shape.sphere() ? shape.sphere()->centre : shape.cone()->centroid());
        for (int i = 0; i < 20; ++i) {
            // Aim from outside at the primitive's centre region; keep hits on it from outside.
            const Vec3 org = centre + Vec3(25.0 * randomUnit(rng));
            const Ray ray{org, centre + Vec3(randomPointWithin(rng, 0.2)) - org};
            PrimitiveSet only = prims;
            only.valid = std::span(&prim, 1);
            NaiveAccelerator single;
            single.build(only);
            QueryCounters counters;
            Hit hit;
            if (!single.findNearest(ray, hit, counters)) continue;
            const SurfacePoint surface = surfaceAt(scene, ray, hit);
            if (!surface.outside) continue;
            for (int k = 0; k < 5; ++k) {
                Vec3 dir(randomUnit(rng));
                if (glm::dot(dir, surface.geometricNormal) < 0.0f) dir = -dir;
                Hit again;
                ++leaving;
                ASSERT_FALSE(single.findNearest({surface.originAbove(), dir}, again, counters))
                    << "primitive " << prim << " found again at t " << again.t;
            }
        }
    }
    EXPECT_GT(leaving, 5000u);
}

}  // namespace
}  // namespace bvhlab
