// The shared watertight ray-triangle test (<bvhlab/triangle.h>), float and double: known hits
// with their t/u/v, misses, windings, exact edge and vertex points, parallel rays, interval ends.
#include <bvhlab/triangle.h>
#include <glm/glm.hpp>
#include "framework/scene/scene.h"
#include "tests/support/random_geometry.h"
#include "tests/support/triangle_hits.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace bvhlab::test {
namespace {

TEST(Triangle, KnownHitAlongAxis) {
    for (const bool doublePrecision : {false, true}) {
        SCOPED_TRACE(doublePrecision ? "double" : "float");
        const Ray ray = Ray({1.5f, 2.0f, 0.0f}, {0, 0, 1});
        double t, u, v;
        if (doublePrecision) {
            TriangleHitT<double> h{};
            ASSERT_TRUE(hits<double>(ray, kTri, &h));
            t = h.t, u = h.u, v = h.v;
        } else {
            TriangleHitT<float> h{};
            ASSERT_TRUE(hits<float>(ray, kTri, &h));
            t = h.t, u = h.u, v = h.v;
        }
        EXPECT_NEAR(t, 5.0, 1e-6);
        EXPECT_NEAR(u, 0.25, 1e-6);  // weight of v1
        EXPECT_NEAR(v, 0.25, 1e-6);  // weight of v2
    }
    // Other points: the convention p = (1-u-v) v0 + u v1 + v v2.
    TriangleHitT<float> h{};
    ASSERT_TRUE(hits<float>(Ray({2.5f, 1.5f, -1.0f}, {0, 0, 1}), kTri, &h));
    EXPECT_NEAR(h.t, 6.0f, 1e-5f);
    EXPECT_NEAR(h.u, 0.75f, 1e-6f);
    EXPECT_NEAR(h.v, 0.125f, 1e-6f);
    ASSERT_TRUE(hits<float>(Ray({1.0f, 4.0f, 9.0f}, {0, 0, -1}), kTri, &h));  // from the other side
    EXPECT_NEAR(h.t, 4.0f, 1e-5f);
    EXPECT_NEAR(h.u, 0.0f, 1e-6f);
    EXPECT_NEAR(h.v, 0.75f, 1e-6f);
}

TEST(Triangle, KnownHitObliqueAndUnnormalisedDirection) {
    // Hit point (2, 2, 5): u = 0.5, v = 0.25. Direction (1, 2, 4) scaled: t is in units of dir.
    const Vec3 p(2, 2, 5);
    for (const float scale : {1.0f, 0.125f, 3.0f}) {
        const Vec3 dir = Vec3(1, 2, 4) * scale;
        const Ray ray = Ray(p - 2.0f * dir, dir);
        TriangleHitT<float> h{};
        ASSERT_TRUE(hits<float>(ray, kTri, &h)) << scale;
        EXPECT_NEAR(h.t, 2.0f, 2e-6f) << scale;
        EXPECT_NEAR(h.u, 0.5f, 1e-6f);
        EXPECT_NEAR(h.v, 0.25f, 1e-6f);
    }
}

TEST(Triangle, RandomHitsReturnTheirParameters) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    int checked = 0;
    for (int i = 0; i < 20000; ++i) {
        const double scale = std::exp(U(rng) * 12.0 - 6.0);  // 2.5e-3 .. 400
        const glm::dvec3 c = randomUnit(rng) * scale * 3.0;
        const Triangle tri{Vec3(c + randomUnit(rng) * scale), Vec3(c + randomUnit(rng) * scale),
                           Vec3(c + randomUnit(rng) * scale)};
        const glm::dvec3 n = glm::normalize(glm::cross(glm::dvec3(tri.v1 - tri.v0), glm::dvec3(tri.v2 - tri.v0)));
        double u = U(rng), v = U(rng);
        if (u + v > 1) u = 1 - u, v = 1 - v;
        if (std::min({u, v, 1 - u - v}) < 0.02) continue;  // keep away from edges
        const glm::dvec3 dir = randomUnit(rng);
        if (std::abs(glm::dot(dir, n)) < 0.1) continue;  // and from grazing incidence
        const double t0 = scale * std::exp(U(rng) * 4.0 - 1.0);
        const glm::dvec3 target = pointAt(tri, u, v);
        const Ray ray = Ray(Vec3(target - t0 * dir), Vec3(dir));
        TriangleHitT<float> hf{};
        TriangleHitT<double> hd{};
        ASSERT_TRUE(hits<float>(ray, tri, &hf)) << i;
        ASSERT_TRUE(hits<double>(ray, tri, &hd)) << i;
        // Rounding the origin to float moves the ray by ~1e-7 of |org|: tolerances follow.
        const double tol = 1e-5 * (glm::length(widen(ray.org)) + scale);
        EXPECT_NEAR(hf.t, t0, tol / 0.1) << i;
        EXPECT_NEAR(hd.t, t0, tol / 0.1) << i;
        // The returned u, v give the point the ray reaches at t.
        const glm::dvec3 hitPoint = widen(ray.org) + double(hf.t) * widen(ray.dir);
        EXPECT_LT(glm::length(pointAt(tri, hf.u, hf.v) - hitPoint), 10 * tol) << i;
        EXPECT_NEAR(hf.u, u, 1e-3) << i;
        EXPECT_NEAR(hf.v, v, 1e-3) << i;
        ++checked;
    }
    EXPECT_GT(checked, 5000);
}

TEST(Triangle, Misses) {
    // Beside each edge and beyond each vertex, from both sides.
    const Vec3 outside[] = {{2.5f, 0.5f, 0}, {0.5f, 3, 0},    {2.5f, 3.5f, 0},
                            {3.5f, 0.9f, 0}, {0.9f, 5.5f, 0}, {-1, -1, 0}};
    for (const Vec3& p : outside) {
        EXPECT_FALSE(hitsF(Ray(p, {0, 0, 1}), kTri)) << p.x << " " << p.y;
        EXPECT_FALSE(hitsF(Ray(p + Vec3(0, 0, 10), {0, 0, -1}), kTri)) << p.x << " " << p.y;
        EXPECT_FALSE(hitsD(Ray(p, {0, 0, 1}), kTri));
    }
    // Behind the origin (t = -5) with the default interval, and hit with tmin = -inf.
    EXPECT_FALSE(hitsF(Ray({1.5f, 2, 10}, {0, 0, 1}), kTri));
    TriangleHitT<float> h{};
    ASSERT_TRUE(hits<float>(Ray({1.5f, 2, 10}, {0, 0, 1}, -kInfinity, kInfinity), kTri, &h));
    EXPECT_NEAR(h.t, -5.0f, 1e-5f);
    // Pointing away from the plane.
    EXPECT_FALSE(hitsF(Ray({1.5f, 2, 0}, {0, 0, -1}), kTri));
}

TEST(Triangle, BothWindingsHitWithSwappedWeights) {
    const Triangle reversed{kTri.v0, kTri.v2, kTri.v1};
    for (const Vec3& dir : {Vec3(0, 0, 1), Vec3(0.3f, -0.2f, 1), Vec3(0, 0, -1)}) {
        const Vec3 p(2.0f, 2.0f, 5.0f);  // u = 0.5, v = 0.25 on kTri
        const Ray ray = Ray(p - 3.0f * dir, dir);
        TriangleHitT<float> a{}, b{};
        ASSERT_TRUE(hits<float>(ray, kTri, &a));
        ASSERT_TRUE(hits<float>(ray, reversed, &b));
        EXPECT_FLOAT_EQ(a.t, b.t);
        EXPECT_NEAR(a.u, 0.5f, 1e-6f);
        EXPECT_NEAR(a.v, 0.25f, 1e-6f);
        EXPECT_NEAR(b.u, a.v, 1e-6f);  // v2 and v1 swap places
        EXPECT_NEAR(b.v, a.u, 1e-6f);
    }
}

TEST(Triangle, ExactEdgeAndVertexPointsAreHits) {
    // Exactly representable points on edges and at vertices, reached by rays whose shear is
    // exact (axis-parallel, and diagonals with |dir| components equal): the edge functions
    // are then exactly 0 on the edge, and the point counts as inside.
    const Vec3 points[] = {kTri.v0, kTri.v1, kTri.v2, {2, 1, 5}, {1, 3, 5}, {2, 3, 5}, {1.5f, 4, 5}, {2.5f, 2, 5}};
    const Vec3 dirs[] = {{0, 0, 1}, {0, 0, -1}, {1, 1, 1}, {-1, 1, -1}, {1, -1, 1}, {0.5f, 0.5f, -1}};
    for (const Triangle& tri : {kTri, Triangle{kTri.v0, kTri.v2, kTri.v1}}) {
        for (const Vec3& p : points)
            for (const Vec3& d : dirs) {
                const Ray ray = Ray(p - 4.0f * d, d);
                TriangleHitT<float> h{};
                EXPECT_TRUE(hits<float>(ray, tri, &h))
                    << p.x << "," << p.y << " dir " << d.x << "," << d.y << "," << d.z;
                EXPECT_NEAR(h.t, 4.0f, 1e-5f);
                EXPECT_TRUE(hitsD(ray, tri));
            }
    }
}

TEST(Triangle, RaysParallelToThePlaneMiss) {
    // In the plane (exactly: every sheared coordinate perpendicular to the plane is 0) and
    // above it, along the plane in several directions.
    for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 0.5f, 0), Vec3(-1, 2, 0), Vec3(3, -1, 0)}) {
        for (const float z : {5.0f, 5.25f, 4.0f}) {
            const Vec3 through(1.5f, 2.0f, z);  // (inside the triangle for z = 5)
            const Ray ray = Ray(through - 10.0f * d, d, -kInfinity, kInfinity);
            EXPECT_FALSE(hitsF(ray, kTri)) << d.x << "," << d.y << " z=" << z;
            EXPECT_FALSE(hitsD(ray, kTri)) << d.x << "," << d.y << " z=" << z;
        }
    }
}

TEST(Triangle, IntervalEndsAreInclusive) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p(1.0f + 0.9f * (U(rng) + 1.0f), 1.0f + 0.9f * (U(rng) + 1.0f), 5.0f);  // often inside
        const Vec3 dir(U(rng), U(rng), 1.0f + U(rng) * 0.5f);
        const Ray base = Ray(p - 3.0f * dir, dir, -kInfinity, kInfinity);
        TriangleHitT<float> h{};
        if (!hits<float>(base, kTri, &h)) continue;
        const float t = h.t;                                              // t does not depend on the interval
        EXPECT_TRUE(hitsF(Ray(base.org, dir, t, t), kTri)) << i;          // [t, t]
        EXPECT_TRUE(hitsF(Ray(base.org, dir, t, kInfinity), kTri)) << i;  // tmin == t
        EXPECT_TRUE(hitsF(Ray(base.org, dir, 0.0f, t), kTri)) << i;       // tmax == t
        EXPECT_FALSE(hitsF(Ray(base.org, dir, std::nextafter(t, kInfinity), kInfinity), kTri)) << i;
        EXPECT_FALSE(hitsF(Ray(base.org, dir, 0.0f, std::nextafter(t, -kInfinity)), kTri)) << i;
        TriangleHitT<double> hd{};
        ASSERT_TRUE(hits<double>(base, kTri, &hd));
        const double td = hd.t;
        TriangleHitT<double> tmp{};
        const ShearedRayT<double> sd(base);
        EXPECT_TRUE(intersectTriangle<double>(sd, kTri, td, td, tmp));
        EXPECT_FALSE(intersectTriangle<double>(sd, kTri, std::nextafter(td, 1e300), 1e300, tmp));
        EXPECT_FALSE(intersectTriangle<double>(sd, kTri, 0.0, std::nextafter(td, -1e300), tmp));
    }
}

}  // namespace
}  // namespace bvhlab::test
