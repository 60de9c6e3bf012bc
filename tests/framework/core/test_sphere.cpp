// The ray-sphere test (<bvhlab/sphere.h>), float against its double reference and the double
// against an independent solution: known hits along the axes, rays from inside, interval ends,
// random and tangent rays at scales from 1e-3 to 1e4 and far from the origin, bounds, NFF's
// negative radius, degenerate spheres and NaN rays.
#include "tests/support/quadric_agreement.h"
#include "tests/support/quiet_nan.h"
#include "tests/support/random_geometry.h"

#include <bvhlab/sphere.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace bvhlab {
namespace {

using namespace test;  // the shared helpers of the primitives' tests

using test::kNaN;

// Independent of sphere.h (long double, the line's distance from the centre by a cross product):
// how far the ray's line passes from the sphere's surface, relative to the origin's distance
// from the centre, the scale of float's rounding in the test.
double grazingDistance(const Ray& ray, const Sphere& sphere) {
    using L = long double;
    const glm::vec<3, L> f = glm::vec<3, L>(widen(ray.org)) - glm::vec<3, L>(widen(sphere.centre));
    const glm::vec<3, L> d(widen(ray.dir));
    const L line = glm::length(glm::cross(f, d)) / glm::length(d);
    return double(std::abs(line - L(std::abs(sphere.radius))) / std::max(glm::length(f), L(std::abs(sphere.radius))));
}
constexpr double kGrazingBand = 1e-5;

const Sphere kSphere{{1, 2, 3}, 2};

TEST(Sphere, KnownHitsAlongTheAxes) {
    // From 10 away along each axis, either way, with unit and scaled directions: t = (10 - r)/|dir|,
    // the normal facing the ray.
    for (const bool doublePrecision : {false, true}) {
        SCOPED_TRACE(doublePrecision ? "double" : "float");
        for (int axis = 0; axis < 3; ++axis)
            for (const float sign : {1.0f, -1.0f})
                for (const float scale : {1.0f, 0.25f, 4.0f}) {
                    Vec3 dir(0.0f);
                    dir[axis] = sign * scale;
                    const Ray ray = Ray(kSphere.centre - (10.0f / scale) * dir, dir);
                    QuadricHitT<double> h{};
                    if (doublePrecision) {
                        ASSERT_TRUE(hits<double>(ray, kSphere, &h));
                    } else {
                        QuadricHitT<float> hf{};
                        ASSERT_TRUE(hits<float>(ray, kSphere, &hf));
                        h = {hf.t, hf.normal};
                    }
                    EXPECT_NEAR(h.t, 8.0 / scale, 1e-6 / scale) << axis << " " << sign << " " << scale;
                    EXPECT_NEAR(glm::dot(h.normal, -glm::dvec3(dir) / double(scale)), 1.0, 1e-7);
                }
    }
    // Off the axis: the ray y = 1 in the sphere's plane z = 3 meets x^2 + 1 = 4 at x = 1 - sqrt(3).
    QuadricHitT<float> h{};
    ASSERT_TRUE(hits<float>(Ray({-5, 3, 3}, {1, 0, 0}), kSphere, &h));
    EXPECT_NEAR(h.t, 6.0f - std::sqrt(3.0f), 1e-5f);
    EXPECT_NEAR(h.normal.x, -std::sqrt(3.0f) / 2.0f, 1e-6f);
    EXPECT_NEAR(h.normal.y, 0.5f, 1e-6f);
}

TEST(Sphere, RaysStartingInsideHitTheFarSide) {
    for (const Vec3& start : {kSphere.centre, kSphere.centre + Vec3(0.5f, -1.0f, 0.25f)}) {
        for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(0, -2, 0), Vec3(0.3f, 0.4f, -1.2f)}) {
            QuadricHitT<double> h{};
            ASSERT_TRUE(hits<double>(Ray(start, dir), kSphere, &h));
            // The exit point: on the surface, ahead of the ray, the normal along the ray.
            const DVec3 p = widen(start) + h.t * widen(dir);
            EXPECT_NEAR(glm::length(p - widen(kSphere.centre)), 2.0, 1e-12);
            EXPECT_GT(h.t, 0.0);
            EXPECT_GT(glm::dot(h.normal, widen(dir)), 0.0);
            QuadricHitT<float> hf{};
            ASSERT_TRUE(hits<float>(Ray(start, dir), kSphere, &hf));
            EXPECT_NEAR(hf.t, h.t, 1e-5 * h.t);
        }
    }
    QuadricHitT<float> h{};
    ASSERT_TRUE(hits<float>(Ray(kSphere.centre, {0, 0, 1}), kSphere, &h));
    EXPECT_FLOAT_EQ(h.t, 2.0f);
    EXPECT_EQ(h.normal, Vec3(0, 0, 1));
}

TEST(Sphere, MissesAndHitsBehindTheOrigin) {
    // Beside it, pointing away, and wholly behind: a hit only once tmin lets in negative t.
    EXPECT_FALSE(hits<float>(Ray({-5, 4.01f, 3}, {1, 0, 0}), kSphere));
    EXPECT_FALSE(hits<double>(Ray({-5, 4.01f, 3}, {1, 0, 0}), kSphere));
    EXPECT_FALSE(hits<float>(Ray({-5, 2, 3}, {-1, 0, 0}), kSphere));
    EXPECT_FALSE(hits<double>(Ray({-5, 2, 3}, {-1, 0, 0}), kSphere));
    QuadricHitT<float> h{};
    ASSERT_TRUE(hits<float>(Ray({-5, 2, 3}, {-1, 0, 0}, -kInfinity, kInfinity), kSphere, &h));
    EXPECT_FLOAT_EQ(h.t, -8.0f);
}

TEST(Sphere, IntervalEndsAreInclusiveForBothRoots) {
    std::mt19937 rng(31);
    int checked = 0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 org = Vec3(widen(kSphere.centre) + randomUnit(rng) * 6.0);
        const Vec3 dir = Vec3(widen(kSphere.centre) + randomUnit(rng) * 1.5 - widen(org));
        QuadricHitT<float> nearHit{}, farHit{};
        ASSERT_TRUE(hits<float>(Ray(org, dir), kSphere, &nearHit)) << i;
        const float t0 = nearHit.t;
        ASSERT_TRUE(hits<float>(Ray(org, dir, std::nextafter(t0, kInfinity), kInfinity), kSphere, &farHit)) << i;
        const float t1 = farHit.t;  // the far root, once the interval starts past the near one
        ASSERT_GT(t1, t0) << i;
        EXPECT_GT(glm::dot(farHit.normal, dir), 0.0f) << i;
        for (const float t : {t0, t1}) {
            EXPECT_TRUE(hits<float>(Ray(org, dir, t, t), kSphere)) << i;
            EXPECT_FALSE(
                hits<float>(Ray(org, dir, std::nextafter(t, kInfinity), std::nextafter(t, kInfinity)), kSphere))
                << i;
            EXPECT_FALSE(
                hits<float>(Ray(org, dir, std::nextafter(t, -kInfinity), std::nextafter(t, -kInfinity)), kSphere))
                << i;
        }
        EXPECT_FALSE(hits<float>(Ray(org, dir, 0.0f, std::nextafter(t0, -kInfinity)), kSphere)) << i;
        EXPECT_FALSE(hits<float>(Ray(org, dir, std::nextafter(t1, kInfinity), kInfinity), kSphere)) << i;
        ++checked;
    }
    EXPECT_EQ(checked, 2000);
}

TEST(Sphere, ReferenceMatchesAnIndependentSolution) {
    // The double instance against the textbook roots in long double, away from tangents.
    std::mt19937 rng(32);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    int compared = 0;
    for (int i = 0; i < 20000; ++i) {
        const Sphere sphere{Vec3(randomUnit(rng) * 3.0), float(0.5 + U(rng))};
        const Ray ray = Ray(Vec3(randomUnit(rng) * 8.0), Vec3(randomUnit(rng) * std::exp(U(rng) * 4 - 2)));
        if (grazingDistance(ray, sphere) < 1e-3) continue;
        using L = long double;
        const glm::vec<3, L> f = glm::vec<3, L>(widen(ray.org)) - glm::vec<3, L>(widen(sphere.centre));
        const glm::vec<3, L> d(widen(ray.dir));
        const L a = glm::dot(d, d), b = 2 * glm::dot(f, d), c = glm::dot(f, f) - L(sphere.radius) * L(sphere.radius);
        const L disc = b * b - 4 * a * c;
        QuadricHitT<double> h{};
        const bool hit = hits<double>(ray, sphere, &h);
        const L expected = disc < 0                                ? L(-1)
                           : (-b - std::sqrt(disc)) / (2 * a) >= 0 ? (-b - std::sqrt(disc)) / (2 * a)
                                                                   : (-b + std::sqrt(disc)) / (2 * a);
        ASSERT_EQ(hit, expected >= 0) << i;
        if (hit) {
            EXPECT_NEAR(h.t, double(expected), 1e-12 * std::max(1.0, h.t)) << i;
        }
        ++compared;
    }
    EXPECT_GT(compared, 15000);
}

// Random spheres of size `size` around `offset`, rays from 1.5 to 40 radii away (or from
// inside) aimed near them: about half hit.
test::QuadricAgreement shootRandomRaysAtSpheres(uint32_t seed, int count, double minSize, double maxSize,
                                                double maxOffset) {
    const auto compareOne = [](std::mt19937& rng, double size, const DVec3& offset, test::QuadricAgreement& agreement) {
        std::uniform_real_distribution<double> U(0.0, 1.0);
        const Sphere sphere{Vec3(offset + randomUnit(rng) * size), float(size * (0.5 + U(rng)))};
        const DVec3 c = widen(sphere.centre);
        const double distance = rng() % 8 == 0 ? 0.9 * U(rng) : 1.5 * std::pow(40.0 / 1.5, U(rng));
        const Vec3 org = Vec3(c + randomUnit(rng) * distance * double(sphere.radius));
        const DVec3 target = c + randomUnit(rng) * 1.4 * double(sphere.radius);
        const Ray ray = Ray(org, Vec3((target - widen(org)) * std::exp(U(rng) * 4 - 2)));
        agreement.compare(intersectorOf(sphere), ray, double(sphere.radius),
                          grazingDistance(ray, sphere) < kGrazingBand);
    };
    return test::agreementOnRandomRays(seed, count, minSize, maxSize, maxOffset, compareOne);
}

TEST(Sphere, FloatAgreesWithDoubleOnRandomRays) {
    shootRandomRaysAtSpheres(33, 200000, 0.5, 2.0, 4.0).expectCounts("unit spheres", 60000, 60000, 200);
}

TEST(Sphere, FloatAgreesWithDoubleAtHugeAndTinyScalesFarFromTheOrigin) {
    shootRandomRaysAtSpheres(34, 200000, 1e-3, 1e4, 0.0)
        .expectCounts("spheres of 1e-3 to 1e4 at the origin", 60000, 60000, 200);
    shootRandomRaysAtSpheres(35, 200000, 1e-3, 1e4, 1e5)
        .expectCounts("spheres of 1e-3 to 1e4 up to 1e5 from the origin", 60000, 60000, 200);
}

TEST(Sphere, TangentRaysAgreeOutsideANarrowBand) {
    // Rays passing the surface at miss radii: never a NaN, and float and double disagree only
    // within the band, in which all of them are counted.
    test::expectTangentRaysAgree(36, [](std::mt19937& rng, double size, double miss, test::QuadricAgreement& a) {
        std::uniform_real_distribution<double> U(0.0, 1.0);
        const Sphere sphere{Vec3(randomPointWithin(rng, size * 100.0)), float(size)};
        const DVec3 dir = randomUnit(rng);
        const DVec3 across = glm::normalize(glm::cross(dir, randomUnit(rng)));
        const DVec3 tangentPoint = widen(sphere.centre) + across * double(sphere.radius) * (1.0 + miss);
        const Ray ray = Ray(Vec3(tangentPoint - dir * double(sphere.radius) * (2.0 + 20.0 * U(rng))), Vec3(dir));
        a.compare(intersectorOf(sphere), ray, double(sphere.radius), grazingDistance(ray, sphere) < kGrazingBand);
    });
}

TEST(Sphere, BoundsHoldTheSurfaceTightly) {
    std::mt19937 rng(37);
    for (int i = 0; i < 20000; ++i) {
        const double size = randomScale(rng);
        const Sphere sphere{Vec3(randomPointWithin(rng, size * 1e3)), float(size) * (i % 2 ? 1.0f : -1.0f)};
        const Bounds3 b = sphere.bounds();
        for (int axis = 0; axis < 3; ++axis) {
            const double c = widen(sphere.centre)[axis], r = std::abs(double(sphere.radius));
            // Outside c - r and c + r, and by no more than a few float steps.
            EXPECT_LE(double(b.lower[axis]), c - r) << i;
            EXPECT_GE(double(b.upper[axis]), c + r) << i;
            const double step = 4.0 * std::numeric_limits<float>::epsilon() * (std::abs(c) + r);
            EXPECT_GE(double(b.lower[axis]), c - r - step) << i;
            EXPECT_LE(double(b.upper[axis]), c + r + step) << i;
        }
        EXPECT_EQ(sphere.centroid(), sphere.centre);
    }
}

TEST(Sphere, NegativeRadiusIsTheSameSurface) {
    // NFF's inside-only sphere: the geometry of |radius|.
    const Sphere inverted{kSphere.centre, -kSphere.radius};
    EXPECT_FALSE(isDegenerate(inverted));
    std::mt19937 rng(38);
    for (int i = 0; i < 1000; ++i) {
        const Ray ray = Ray(Vec3(randomUnit(rng) * 8.0), Vec3(randomUnit(rng)));
        QuadricHitT<float> a{}, b{};
        const bool hitA = hits<float>(ray, kSphere, &a), hitB = hits<float>(ray, inverted, &b);
        ASSERT_EQ(hitA, hitB) << i;
        if (hitA) {
            EXPECT_EQ(a.t, b.t);
            EXPECT_EQ(a.normal, b.normal);
        }
    }
}

TEST(Sphere, DegenerateSpheresAreNeverHit) {
    // A point, NaN and infinite data, and radii whose square leaves float's range: rays through
    // the centre from many directions, and from inside, all miss.
    const Vec3 c(1, 2, 3);
    const Sphere degenerate[] = {
        {c, 0.0f},
        {c, -0.0f},
        {c, kNaN},
        {c, kInfinity},
        {c, -kInfinity},
        {Vec3(1, kNaN, 3), 1.0f},
        {Vec3(kInfinity, 2, 3), 1.0f},
        {c, 1e-20f},
        {c, 1e20f},
        {c, -1e20f},
    };
    std::mt19937 rng(39);
    int tested = 0;
    for (const Sphere& sphere : degenerate) {
        EXPECT_TRUE(isDegenerate(sphere)) << &sphere - degenerate;
        for (int i = 0; i < 200; ++i) {
            const DVec3 d = randomUnit(rng);
            const Vec3 org = Vec3(widen(c) - d * (i % 2 ? 3.0 : 1e-3));
            const Ray ray = Ray(org, c - org, -kInfinity, kInfinity);
            EXPECT_FALSE(hits<float>(ray, sphere)) << "sphere #" << (&sphere - degenerate) << " ray " << i;
            EXPECT_FALSE(hits<double>(ray, sphere)) << "sphere #" << (&sphere - degenerate) << " ray " << i;
            ++tested;
        }
    }
    EXPECT_EQ(tested, 10 * 200);
    // Small and large spheres whose square stays a normal float are real.
    EXPECT_FALSE(isDegenerate(Sphere{c, 1e-15f}));
    EXPECT_FALSE(isDegenerate(Sphere{c, 1e15f}));
    QuadricHitT<float> h{};
    ASSERT_TRUE(hits<float>(Ray({0, 0, -1e-14f}, {0, 0, 1}), Sphere{Vec3(0.0f), 1e-15f}, &h));
    EXPECT_NEAR(h.t, 9e-15f, 1e-20f);
}

TEST(Sphere, NaNRaysNeverHit) { test::expectNaNRaysMiss(intersectorOf(kSphere), Ray({-5, 2.5f, 3}, {1, 0.01f, 0})); }

}  // namespace
}  // namespace bvhlab
