// The stress suite's rays for every registered accelerator (the fixture: stress_fixture.h): rays
// starting on a surface, axis-parallel rays in the planes of faces, negative tmin, very short and
// very long rays. Embree's numbers are printed and recorded, not failed.
#include "accel/naive/naive_accelerator.h"
#include "accel/verify/oracle.h"
#include "accel/verify/ray_generators.h"
#include "accel/verify/verify_rng.h"
#include "framework/core/ray_offset.h"
#include "tests/accel/verify/stress_fixture.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

namespace bvhlab::verify {
namespace {

// --- rays starting on a surface ---------------------------------------------------------------

// Points on random triangles of a closed mesh, with the outward normal there (`centre` lies
// inside; the meshes here are star-shaped around it at each face).
struct SurfacePoint {
    uint32_t prim;
    Vec3 p;
    Vec3 outward;
};

std::vector<SurfacePoint> surfacePoints(const Scene& scene, const Vec3& centre, size_t n, uint64_t seed) {
    VerifyRng rng(seed);
    std::vector<SurfacePoint> points;
    while (points.size() < n) {
        const uint32_t prim = scene.validPrimitives[rng.index(scene.validPrimitives.size())];
        const Triangle& t = scene.triangles[prim];
        float u = float(rng.uniform()), v = float(rng.uniform());
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        // As the renderer computes it: from barycentrics, in float.
        const Vec3 p = (1.0f - u - v) * t.v0 + u * t.v1 + v * t.v2;
        Vec3 n = glm::normalize(t.geometricNormal());
        if (glm::dot(n, t.centroid() - centre) < 0) n = -n;
        points.push_back({prim, p, n});
    }
    return points;
}

// A direction on the side of `n` at more than ~3 degrees from the plane.
Vec3 directionAlong(VerifyRng& rng, const Vec3& n) {
    for (;;) {
        const DVec3 d = rng.unitVector();
        const double c = glm::dot(d, DVec3(n));
        if (std::abs(c) > 0.05) return Vec3(c > 0 ? d : -d);
    }
}

TEST_P(Stress, RaysStartingOnASurface) {
    struct Case {
        Scene scene;
        Vec3 centre;
        bool convex;
    };
    static const std::vector<Case> cases = [] {
        std::vector<Case> list;
        list.push_back({makeIcosphereMesh(4), Vec3(0.3f, -0.2f, 0.1f), true});
        list.push_back({makeSubdividedCubeMesh(16), Vec3(-0.1f, 0.35f, 1.15f), true});
        return list;
    }();
    for (const Case& c : cases) {
        if (isNaive() && c.scene.triangleCount() > kNaiveMaxTriangles) continue;
        SCOPED_TRACE(c.scene.name);
        const auto accel = build(c.scene);
        VerifyRng rng(99);
        size_t selfHitsLeaving = 0, missesEntering = 0, selfHitsEntering = 0, occludedLeaving = 0;
        std::vector<std::string> examples;
        const std::vector<SurfacePoint> points = surfacePoints(c.scene, c.centre, 3000, 21);
        QueryCounters counters;
        for (const SurfacePoint& s : points) {
            // Leaving a convex solid from its surface (origin offset outward): nothing to hit.
            const Ray out{offsetRayOrigin(s.p, s.outward, c.scene.triangles[s.prim]), directionAlong(rng, s.outward),
                          0.0f, kInfinity};
            Hit h;
            if (accel->findNearest(out, h, counters)) {
                ++selfHitsLeaving;
                if (examples.size() < 3)
                    examples.push_back("leaving " + verify::describe(out) + " hit " + verify::describe(h));
            }
            if (accel->isOccluded(out, counters)) ++occludedLeaving;
            // Entering it (origin offset inward): the far side, never the start.
            const Ray in{offsetRayOrigin(s.p, -s.outward, c.scene.triangles[s.prim]), directionAlong(rng, -s.outward),
                         0.0f, kInfinity};
            Hit h2;
            if (!accel->findNearest(in, h2, counters)) {
                ++missesEntering;
                if (examples.size() < 3) examples.push_back("entering " + verify::describe(in) + " missed");
            } else if (h2.primitive == s.prim) {
                ++selfHitsEntering;
                if (examples.size() < 3)
                    examples.push_back("entering " + verify::describe(in) + " hit its start " + verify::describe(h2));
            }
        }
        expectZero("hits leaving " + c.scene.name, selfHitsLeaving, points.size(), examples);
        expectZero("occluded leaving " + c.scene.name, occludedLeaving, points.size());
        expectZero("misses entering " + c.scene.name, missesEntering, points.size(), examples);
        expectZero("start hit entering " + c.scene.name, selfHitsEntering, points.size(), examples);
    }
}

// --- axis-parallel rays in the planes of faces -------------------------------------------------

TEST_P(Stress, AxisParallelRaysInThePlanesOfFaces) {
    // Flat leaf boxes and origins exactly on slab planes: 0 * inf in the box test.
    static const Scene cube = makeSubdividedCubeMesh(16);
    const Bounds3 b = cube.bounds;
    VerifyRng rng(7);
    std::vector<Ray> rays;
    std::vector<double> expectedT;
    for (int i = 0; i < 3000; ++i) {
        const int k = int(rng.index(3));                // travel axis
        const int j = (k + 1 + int(rng.index(2))) % 3;  // axis whose face plane holds the ray
        const int m = 3 - k - j;                        // the remaining axis
        const bool positive = rng.uniform() < 0.5;
        Ray r;
        r.org[k] = positive ? b.lower[k] - 1.0f : b.upper[k] + 1.0f;
        r.org[j] = rng.uniform() < 0.5 ? b.lower[j] : b.upper[j];
        const double s = rng.uniform();
        // A grid line, a cube edge (the ray then runs along an edge of the cube) or anywhere between.
        r.org[m] =
            s < 0.2 ? (rng.uniform() < 0.5 ? b.lower[m] : b.upper[m])
            : s < 0.5
                ? float(double(b.lower[m]) + (double(b.upper[m]) - double(b.lower[m])) * double(rng.index(17)) / 16.0)
                : float(rng.uniform(b.lower[m], b.upper[m]));
        r.dir = Vec3(0.0f);
        r.dir[k] = positive ? 1.0f : -1.0f;
        if (rng.uniform() < 0.5) r.dir[j] = -0.0f;  // the sign of a zero picks the slab
        if (rng.uniform() < 0.5) r.dir[m] = -0.0f;
        rays.push_back(r);
        expectedT.push_back(std::abs(double(positive ? b.lower[k] : b.upper[k]) - double(r.org[k])));
    }
    const auto accel = build(cube);
    size_t misses = 0, wrongT = 0, occlusionMisses = 0;
    std::vector<std::string> examples;
    QueryCounters counters;
    for (size_t i = 0; i < rays.size(); ++i) {
        Hit h;
        if (!accel->findNearest(rays[i], h, counters)) {
            ++misses;
            if (examples.size() < 3) examples.push_back(verify::describe(rays[i]) + " missed");
        } else if (std::abs(double(h.t) - expectedT[i]) > 1e-6 * expectedT[i]) {
            ++wrongT;
            if (examples.size() < 3) examples.push_back(verify::describe(rays[i]) + " hit " + verify::describe(h));
        }
        if (!accel->isOccluded(rays[i], counters)) ++occlusionMisses;
    }
    expectZero("axis-parallel rays in face planes missing the cube", misses, rays.size(), examples);
    expectZero("axis-parallel rays in face planes hitting at the wrong t", wrongT, rays.size(), examples);
    expectZero("axis-parallel rays in face planes not occluded", occlusionMisses, rays.size());
}

// --- rays looking behind their origin ------------------------------------------------------------

TEST_P(Stress, NegativeTminSeesBehindTheOrigin) {
    // An interval reaching below t = 0 on flat boxes (the faces of an axis-aligned cube): the
    // far side of a box behind the origin has a negative distance, which a box test that only
    // scales far distances up would shrink instead of widening.
    static const Scene cube = makeSubdividedCubeMesh(16);
    if (isNaive()) GTEST_SKIP() << "naive is the reference here";
    NaiveAccelerator naive;
    naive.build(cube.primitives());
    const auto accel = build(cube);
    VerifyRng rng(57);
    size_t differ = 0, rays = 0;
    std::vector<std::string> examples;
    QueryCounters counters;
    for (int i = 0; i < 3000; ++i) {
        Ray r;
        r.org = Vec3(DVec3(cube.bounds.center()) +
                     0.45 * DVec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)) *
                         DVec3(cube.bounds.diagonal()));
        r.dir = Vec3(rng.unitVector());
        if (i % 3 == 0) r.dir[int(rng.index(3))] = 0.0f;  // and axis-parallel in one or two axes
        if (i % 9 == 0) r.dir[int(rng.index(3))] = 0.0f;
        if (r.dir == Vec3(0.0f)) continue;
        switch (i % 3) {
            case 0:
                r.tmin = -100.0f, r.tmax = -1e-3f;
                break;  // only behind
            case 1:
                r.tmin = -kInfinity, r.tmax = kInfinity;
                break;
            default:
                r.tmin = -0.5f, r.tmax = 0.25f;
                break;
        }
        ++rays;
        Hit a, b;
        const bool found = accel->findNearest(r, a, counters);
        naive.findNearest(r, b, counters);
        if (found != b.found() || !hitsAgree(a, b) || accel->isOccluded(r, counters) != b.found()) {
            ++differ;
            if (examples.size() < 3)
                examples.push_back(verify::describe(r) + ": " + verify::describe(a) + " vs naive " +
                                   verify::describe(b));
        }
    }
    expectZero("answers with negative tmin unlike naive", differ, rays, examples);
}

// --- very short and very long rays, NaN ---------------------------------------------------------

TEST_P(Stress, VeryShortAndVeryLongRays) {
    static const Scene scene = makeClosedTrioScene(3, 8, 32, 16);
    const auto accel = build(scene);
    VerifyRng rng(31);
    const double radius = 0.5 * glm::length(DVec3(scene.bounds.diagonal()));
    size_t shortWrong = 0, shortRays = 0;
    std::vector<std::string> examples;
    QueryCounters counters;
    // Short: from just in front of a point well inside a triangle, at 1e-3 .. 1e-1 of its size.
    // (t's absolute error is a few ulps of the triangle's distance from the origin, |v - org|,
    // over the cosine of incidence: ~1e-7 of the triangle's size, so t is known to 1e-4 here.)
    for (int i = 0; i < 2000; ++i) {
        const uint32_t prim = scene.validPrimitives[rng.index(scene.validPrimitives.size())];
        const Triangle& t = scene.triangles[prim];
        const DVec3 q = 0.4 * DVec3(t.v0) + 0.35 * DVec3(t.v1) + 0.25 * DVec3(t.v2);
        const DVec3 n = glm::normalize(DVec3(t.geometricNormal()));
        const DVec3 d = DVec3(directionAlong(rng, Vec3(n)));
        if (std::abs(glm::dot(d, n)) < 0.5) continue;
        const double edge = glm::length(DVec3(t.v1) - DVec3(t.v0));
        const Vec3 org(q - rng.logUniform(1e-3, 1e-1) * edge * d);
        const DVec3 dir = glm::normalize(q - DVec3(org));
        const double tPlane = glm::dot(DVec3(t.v0) - DVec3(org), n) / glm::dot(dir, n);
        if (!(tPlane > 0)) continue;
        ++shortRays;
        const Ray reaches{org, Vec3(dir), 0.0f, float(1.1 * tPlane)};
        const Ray stopsShort{org, Vec3(dir), 0.0f, float(0.9 * tPlane)};
        const Ray startsBeyond{org, Vec3(dir), float(1.1 * tPlane), kInfinity};
        Hit h;
        const bool hit = accel->findNearest(reaches, h, counters);
        bool wrong = !hit || h.primitive != prim || std::abs(double(h.t) - tPlane) > 1e-2 * tPlane;
        Hit h2;
        wrong |= accel->findNearest(stopsShort, h2, counters) || accel->isOccluded(stopsShort, counters);
        Hit h3;
        wrong |= accel->findNearest(startsBeyond, h3, counters) && h3.primitive == prim;
        if (wrong) {
            ++shortWrong;
            if (examples.size() < 3)
                examples.push_back(
                    fmt::format("{} toward prim {} at t {:.9g}", verify::describe(reaches), prim, tPlane));
        }
    }
    EXPECT_GT(shortRays, 500u);
    expectZero("wrong answers to very short rays", shortWrong, shortRays, examples);

    // Long: from 1e2 .. 1e6 times the scene's radius; the same answers as naive.
    NaiveAccelerator naive;
    naive.build(scene.primitives());
    size_t longDiffer = 0, naiveHits = 0;
    examples.clear();
    const std::vector<Ray> toward = raysTowardTriangles(scene, 1000, 41);
    for (const Ray& base : toward) {
        Ray r = base;
        const double far = radius * rng.logUniform(1e2, 1e6);
        r.org = Vec3(DVec3(base.org) - far * DVec3(base.dir));
        if (rng.uniform() < 0.3) r.tmax = 1e30f;
        Hit a, n;
        accel->findNearest(r, a, counters);
        naiveHits += naive.findNearest(r, n, counters);
        if (!hitsAgree(a, n)) {
            ++longDiffer;
            if (examples.size() < 3)
                examples.push_back(verify::describe(r) + ": " + verify::describe(a) + " vs naive " +
                                   verify::describe(n));
        }
    }
    EXPECT_GT(naiveHits, toward.size() / 2);
    expectZero("very long rays answered unlike naive", longDiffer, toward.size(), examples);

    // NaN anywhere, zero direction, empty intervals: misses, no crash.
    for (const Ray& r : verify::generateRays(verify::RayKind::Invalid, scene.primitives(), scene.bounds, 400, 43)) {
        Hit h;
        EXPECT_FALSE(accel->findNearest(r, h, counters)) << verify::describe(r);
        EXPECT_FALSE(accel->isOccluded(r, counters)) << verify::describe(r);
    }
}

}  // namespace
}  // namespace bvhlab::verify
