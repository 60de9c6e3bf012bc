// The ray-cone test of NFF's `c` (<bvhlab/cone.h>), float against its double reference and
// the double against an independent solution: known hits on cylinders and cones, from inside,
// through the open ends, parallel to the axis and to a generator line, interval ends, random and
// tangent rays at scales from 1e-3 to 1e4 and far from the origin, bounds, NFF's radii, degenerate
// cones and NaN rays.
#include "tests/support/quadric_agreement.h"
#include "tests/support/quiet_nan.h"
#include "tests/support/random_geometry.h"

#include <bvhlab/cone.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace bvhlab {
namespace {

using namespace test;  // the shared helpers of the primitives' tests

using test::kNaN;

// Independent of cone.h: the quadratic F(t) = a t^2 + 2 halfB t + c, F = |p_xy|^2 - R(z)^2 along
// the ray, in world space (no frame; distance from the axis by projection), the textbook roots in
// long double. Returns the nearest t in the ray's interval on the surface between the end planes,
// or NaN. `grazing` says whether float may decide either way: as the sphere's band, where the ray
// comes within kBand S of the surface, S the scale of float's rounding in the test (the origin's
// distance from the base plus the cone's extent). Unlike a sphere's, a cone's near-tangent rays
// are not the only ill-conditioned ones: a ray along a generator line stays near the surface far
// from any tangent, so a hit is grazing also when the ray is still within the band one t
// tolerance of the agreement (1e-4 max(|t|, size/|d|)) before or after it, as float's t may move
// by more. A root within the band of an end plane or of the interval's start is grazing too.
// kBand = 1e-5 (the sphere's): outside it float's hits lay at most 7.8e-7 S off the double's
// along the normal in these tests (13x margin).
constexpr long double kBand = 1e-5L;
double referenceHit(const Ray& ray, const Cone& cone, double size, bool* grazing = nullptr) {
    using L = long double;
    using LV = glm::vec<3, L>;
    const LV base(widen(cone.base)), apex(widen(cone.apex));
    const L height = glm::length(apex - base);
    const LV w = (apex - base) / height;
    const L r0 = std::abs(L(cone.baseRadius)), k = (std::abs(L(cone.apexRadius)) - r0) / height;
    const LV f = LV(widen(ray.org)) - base, d(widen(ray.dir));
    const L fw = glm::dot(f, w), dw = glm::dot(d, w), rf = r0 + k * fw;
    const L a = glm::dot(d, d) - dw * dw - k * k * dw * dw;
    const L halfB = glm::dot(f, d) - fw * dw - k * dw * rf;
    const L c = glm::dot(f, f) - fw * fw - rf * rf;
    const L disc = halfB * halfB - a * c;
    const L scale = glm::length(f) + height + r0 + std::abs(k) * height, band = kBand * scale;
    const L margin = band / glm::length(d), slant = std::sqrt(1 + k * k);
    const auto inSlab = [&](L t) {
        const L s = fw + t * dw;
        return t >= ray.tmin - margin && t <= ray.tmax + margin && s >= -band && s <= height + band;
    };
    // In the plane through the axis, the two generator lines rho = +-R(s) at slope k.
    const auto distanceFromSurface = [&](L t) {
        const LV p = f + t * d;
        const L s = glm::dot(p, w);
        return std::abs(glm::length(p - s * w) - std::abs(r0 + k * s)) / slant;
    };
    // Near a tangent, whether or not the ray hits: where |F| is least on the ray's part in the slab
    // and the interval (F's extremum -halfB/a, clamped to that part). The distance from the surface
    // is |F| / ((rho + |R|) slant): where it is under the band, |rho - |R|| < band slant and |R| <
    // max|R| + |k| band, so |F| is under the bound below.
    L tLow = L(ray.tmin) - margin, tHigh = L(ray.tmax) + margin;
    if (dw != 0) {
        const L tBase = (-band - fw) / dw, tApex = (height + band - fw) / dw;
        tLow = std::max(tLow, std::min(tBase, tApex));
        tHigh = std::min(tHigh, std::max(tBase, tApex));
    } else if (fw < -band || fw > height + band) {
        tHigh = tLow - 1;  // beside the slab: no part in it
    }
    const L maxRadius = std::max(r0, std::abs(L(cone.apexRadius)));
    const L bound = band * slant * (2 * maxRadius + 3 * band * slant);
    const L tangent = a != 0 && tLow <= tHigh ? std::clamp(-halfB / a, tLow, tHigh) : tLow;  // clamp needs lo <= hi
    bool nearEdge = tLow <= tHigh && std::abs((a * tangent + 2 * halfB) * tangent + c) < bound;
    double nearest = std::numeric_limits<double>::quiet_NaN();
    if (disc >= 0 && a != 0) {
        L roots[2] = {(-halfB - std::sqrt(disc)) / a, (-halfB + std::sqrt(disc)) / a};
        if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
        for (const L t : roots) {
            // A shallow hit: the ray still within the band one t tolerance before or after it. Or
            // one near a true cone's tip: moved by the band, the normal turns by up to band / rho,
            // and the agreement allows it 1 - cos = 1e-4, an angle of sqrt(2e-4).
            const L s = fw + t * dw, tolerance = 1e-4L * std::max(std::abs(t), L(size) / glm::length(d));
            const bool shallow =
                std::min(distanceFromSurface(t - tolerance), distanceFromSurface(t + tolerance)) < band;
            const bool nearTip = std::abs(r0 + k * s) * std::sqrt(2e-4L) < band;
            nearEdge = nearEdge || (inSlab(t) && (shallow || nearTip)) ||
                       std::min(std::abs(s), std::abs(s - height)) < band ||
                       std::abs(t - L(ray.tmin)) * glm::length(d) < band;
            if (std::isnan(nearest) && t >= ray.tmin && t <= ray.tmax && s >= 0 && s <= height) nearest = double(t);
        }
    }
    if (grazing) *grazing = nearEdge;
    return nearest;
}

// A cylinder and a true cone along z, moved off the origin: R = 1 for 0 <= z <= 4, and
// R(z) = 2 - z/2 narrowing to the apex at z = 4.
const Vec3 kOffset(1, 2, 3);
const Cone kCylinder{kOffset, 1.0f, kOffset + Vec3(0, 0, 4), 1.0f};
const Cone kCone{kOffset, 2.0f, kOffset + Vec3(0, 0, 4), 0.0f};

void expectHit(const Cone& cone, const Vec3& org, const Vec3& dir, float t, const Vec3& normal) {
    for (const bool doublePrecision : {false, true}) {
        QuadricHitT<double> h{};
        if (doublePrecision) {
            ASSERT_TRUE(hits<double>(Ray(kOffset + org, dir), cone, &h)) << "double";
        } else {
            QuadricHitT<float> hf{};
            ASSERT_TRUE(hits<float>(Ray(kOffset + org, dir), cone, &hf)) << "float";
            h = {hf.t, hf.normal};
        }
        EXPECT_NEAR(h.t, t, 1e-5 * std::max(1.0f, t)) << (doublePrecision ? "double" : "float");
        EXPECT_NEAR(glm::dot(h.normal, glm::normalize(DVec3(normal))), 1.0, 1e-6)
            << (doublePrecision ? "double" : "float");
    }
}

void expectMiss(const Cone& cone, const Vec3& org, const Vec3& dir) {
    const Ray ray = Ray(kOffset + org, dir, -kInfinity, kInfinity);
    EXPECT_FALSE(hits<float>(ray, cone)) << org.x << "," << org.y << "," << org.z;
    EXPECT_FALSE(hits<double>(ray, cone)) << org.x << "," << org.y << "," << org.z;
}

TEST(Cone, KnownHitsOnACylinder) {
    for (const float z : {0.5f, 2.0f, 3.5f}) {
        expectHit(kCylinder, {-10, 0, z}, {1, 0, 0}, 9.0f, {-1, 0, 0});
        expectHit(kCylinder, {0, 10, z}, {0, -2, 0}, 4.5f, {0, 1, 0});  // t in units of dir
        expectHit(kCylinder, {0, 0, z}, {1, 0, 0}, 1.0f, {1, 0, 0});    // from the axis: the inner side
    }
    // Oblique: from (-5, 0.6, 1) along (1, 0, 0.25), the wall x = -0.8 at t = 4.2.
    expectHit(kCylinder, {-5, 0.6f, 1}, {1, 0, 0.25f}, 4.2f, {-0.8f, 0.6f, 0});
}

TEST(Cone, KnownHitsOnATrueCone) {
    // R(z) = 2 - z/2: from x = -10 at height z, t = 10 - R(z); the normal leans up, (-2, 0, 1).
    for (const float z : {0.5f, 2.0f, 3.5f})
        expectHit(kCone, {-10, 0, z}, {1, 0, 0}, 10.0f - (2.0f - z / 2), {-2, 0, 1});
    // From inside, on the axis at z = 2: the inner side at R = 1.
    expectHit(kCone, {0, 0, 2}, {0, 1, 0}, 1.0f, {0, 2, 1});
    // Down the axis from above: the apex itself, with the axis for a normal.
    expectHit(kCone, {0, 0, 6}, {0, 0, -1}, 2.0f, {0, 0, 1});
    // Parallel to the axis inside: the surface where R(z) = 1, z = 2.
    expectHit(kCone, {1, 0, -1}, {0, 0, 1}, 3.0f, {2, 0, 1});
    // Parallel to a generator line (the quadratic is linear): x = 1 - t, z = -1 + 2t meets
    // x = -R(z) = t - 2.5 once, at t = 1.75.
    expectHit(kCone, {1, 0, -1}, {-1, 0, 2}, 1.75f, {-2, 0, 1});
}

TEST(Cone, RaysParallelToACylindersAxisMiss) {
    // Inside and outside, either way: they never meet the lateral surface.
    for (const Vec3& org : {Vec3(0, 0, -1), Vec3(0.5f, -0.3f, 2), Vec3(1.5f, 0, -1), Vec3(0, -3, 5)}) {
        expectMiss(kCylinder, org, {0, 0, 1});
        expectMiss(kCylinder, org, {0, 0, -3});
    }
}

TEST(Cone, RaysThroughTheOpenEnds) {
    // In through the base, out through the top: nothing to hit.
    expectMiss(kCylinder, {0, 0, -1}, {0.1f, 0, 1});
    // In through an open end onto the inner wall (the normal points along the ray).
    expectHit(kCylinder, {0, 0, -1}, {0.25f, 0, 1}, 4.0f, {1, 0, 0});
    expectHit(kCylinder, {0, 0, 5}, {0.5f, 0, -1}, 2.0f, {1, 0, 0});
    // The infinite cylinder's outer side lies above the top (z = 4.2 at t = 2): in through the
    // top instead, onto the inner wall at t = 4.
    expectHit(kCylinder, {-3, 0, 6}, {1, 0, -0.9f}, 4.0f, {1, 0, 0});
    // Beside the ends, where only the infinite surfaces are.
    expectMiss(kCylinder, {-5, 0, 4.5f}, {1, 0, 0});
    expectMiss(kCylinder, {-5, 0, -0.5f}, {1, 0, 0});
    expectMiss(kCone, {-5, 0, 4.5f}, {1, 0, 0});  // the other nappe, above the apex
}

TEST(Cone, IntervalEndsAreInclusive) {
    // From x = -10 through the cylinder at height 2: walls at t = 9 and t = 11.
    const Ray ray = Ray(kOffset + Vec3(-10, 0, 2), {1, 0, 0});
    QuadricHitT<float> h{};
    ASSERT_TRUE(hits<float>(ray, kCylinder, &h));
    const float t0 = h.t;
    ASSERT_TRUE(hits<float>(Ray(ray.org, ray.dir, std::nextafter(t0, kInfinity), kInfinity), kCylinder, &h));
    const float t1 = h.t;
    EXPECT_NEAR(t0, 9.0f, 1e-5f);
    EXPECT_NEAR(t1, 11.0f, 1e-5f);
    EXPECT_GT(h.normal.x, 0.99f);  // the far wall, from inside
    for (const float t : {t0, t1}) {
        EXPECT_TRUE(hits(Ray(ray.org, ray.dir, t, t), kCylinder));
        EXPECT_FALSE(
            hits(Ray(ray.org, ray.dir, std::nextafter(t, kInfinity), std::nextafter(t, kInfinity)), kCylinder));
        EXPECT_FALSE(
            hits(Ray(ray.org, ray.dir, std::nextafter(t, -kInfinity), std::nextafter(t, -kInfinity)), kCylinder));
    }
    EXPECT_FALSE(hits(Ray(ray.org, ray.dir, 0.0f, std::nextafter(t0, -kInfinity)), kCylinder));
    EXPECT_FALSE(hits(Ray(ray.org, ray.dir, std::nextafter(t1, kInfinity), kInfinity), kCylinder));
    // Behind the origin: a hit only once the interval admits negative t.
    EXPECT_FALSE(hits(Ray(ray.org, -ray.dir), kCylinder));
    ASSERT_TRUE(hits<float>(Ray(ray.org, -ray.dir, -kInfinity, kInfinity), kCylinder, &h));
    EXPECT_NEAR(h.t, -11.0f, 1e-5f);
}

// Random cones (a third cylinders, a third true cones, either end the wider) of size `size`
// around `offset`.
Cone randomCone(std::mt19937& rng, double size, const DVec3& offset) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const DVec3 base = offset + randomUnit(rng) * size;
    const DVec3 apex = base + randomUnit(rng) * size * (0.3 + 2.0 * U(rng));
    const double r0 = size * (0.2 + U(rng)), r1 = size * (0.2 + U(rng));
    const int kind = int(rng() % 3);
    return {Vec3(base), float(r0), Vec3(apex), float(kind == 0 ? r0 : kind == 1 ? 0.0 : r1)};
}

// A ray from inside or up to 40 sizes away from a random point of the axis, aimed within 1.5
// sizes of the axis, its direction of random length: about half hit.
Ray randomRayTowards(std::mt19937& rng, const Cone& cone, double size) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const DVec3 onAxis = widen(cone.base) + U(rng) * (widen(cone.apex) - widen(cone.base));
    const double distance = size * (rng() % 8 == 0 ? 0.3 * U(rng) : std::pow(40.0, U(rng)));
    const Vec3 org = Vec3(onAxis + randomUnit(rng) * distance);
    const DVec3 target = onAxis + randomPointWithin(rng, size * 1.5);
    return Ray(org, Vec3((target - widen(org)) * std::exp(U(rng) * 4 - 2)));
}

test::QuadricAgreement shootRandomRaysAtCones(uint32_t seed, int count, double minSize, double maxSize,
                                              double maxOffset) {
    const auto compareOne = [](std::mt19937& rng, double size, const DVec3& offset, test::QuadricAgreement& agreement) {
        const Cone cone = randomCone(rng, size, offset);
        const Ray ray = randomRayTowards(rng, cone, size);
        bool grazing = false;
        referenceHit(ray, cone, size, &grazing);
        agreement.compare(intersectorOf(cone), ray, size, grazing);
    };
    return test::agreementOnRandomRays(seed, count, minSize, maxSize, maxOffset, compareOne);
}

TEST(Cone, ReferenceMatchesAnIndependentSolution) {
    std::mt19937 rng(41);
    int hitsCompared = 0, missesCompared = 0;
    for (int i = 0; i < 50000; ++i) {
        const Cone cone = randomCone(rng, 1.0, DVec3(0.0));
        const Ray ray = randomRayTowards(rng, cone, 1.0);
        bool grazing = false;
        const double expected = referenceHit(ray, cone, 1.0, &grazing);
        if (grazing) continue;
        QuadricHitT<double> h{};
        ASSERT_EQ(hits<double>(ray, cone, &h), !std::isnan(expected)) << i;
        if (std::isnan(expected)) {
            ++missesCompared;
            continue;
        }
        EXPECT_NEAR(h.t, expected, 1e-9 * std::max(1.0, std::abs(expected))) << i;
        ++hitsCompared;
    }
    EXPECT_GT(hitsCompared, 10000);
    EXPECT_GT(missesCompared, 10000);
}

// At most 2% grazing: unlike the sphere's, the band takes in shallow hits (at 20 sizes, the
// sine of the incidence under ~0.1), 1.6% to 1.8% of these rays.
constexpr int kMaxGrazing = 4000;

TEST(Cone, FloatAgreesWithDoubleOnRandomRays) {
    shootRandomRaysAtCones(42, 200000, 0.5, 2.0, 4.0).expectCounts("unit cones", 60000, 40000, kMaxGrazing);
}

TEST(Cone, FloatAgreesWithDoubleAtHugeAndTinyScalesFarFromTheOrigin) {
    for (const double offset : {0.0, 1e5}) {
        shootRandomRaysAtCones(43, 200000, 1e-3, 1e4, offset)
            .expectCounts(
                offset == 0.0 ? "cones of 1e-3 to 1e4 at the origin" : "cones of 1e-3 to 1e4 up to 1e5 from the origin",
                60000, 40000, kMaxGrazing);
    }
}

TEST(Cone, TangentRaysAgreeOutsideANarrowBand) {
    // Rays in the tangent plane at a random point of the lateral surface, moved off it along the
    // normal by miss sizes: never a NaN; float and double differ only within the band.
    test::expectTangentRaysAgree(44, [](std::mt19937& rng, double size, double miss, test::QuadricAgreement& a) {
        std::uniform_real_distribution<double> U(0.0, 1.0);
        const Cone cone = randomCone(rng, size, randomPointWithin(rng, size * 100.0));
        const DVec3 base = widen(cone.base), axis = widen(cone.apex) - base;
        const DVec3 w = glm::normalize(axis), across = glm::normalize(glm::cross(w, randomUnit(rng)));
        const double s = 0.05 + 0.9 * U(rng);
        const double radius = double(cone.baseRadius) + s * double(cone.apexRadius - cone.baseRadius);
        const DVec3 normal = glm::normalize(across * glm::length(axis) - w * double(cone.apexRadius - cone.baseRadius));
        const DVec3 touch = base + s * axis + radius * across + miss * size * normal;
        const DVec3 dir = glm::normalize(glm::cross(normal, randomUnit(rng)));
        const Ray ray = Ray(Vec3(touch - dir * size * (2.0 + 20.0 * U(rng))), Vec3(dir));
        bool grazing = false;
        referenceHit(ray, cone, size, &grazing);
        a.compare(intersectorOf(cone), ray, size, grazing);
    });
}

TEST(Cone, BoundsHoldTheSurfaceTightly) {
    // The box of points sampled on both rims: inside the bounds, which exceed it by no more than
    // the sampling's shortfall and a few float steps.
    std::mt19937 rng(45);
    for (int i = 0; i < 5000; ++i) {
        const double size = randomScale(rng);
        const Cone cone = randomCone(rng, size, randomPointWithin(rng, size * 1e3));
        const Bounds3 b = cone.bounds();
        const DVec3 base = widen(cone.base), apex = widen(cone.apex);
        const DVec3 w = glm::normalize(apex - base), u = glm::normalize(glm::cross(w, randomUnit(rng))),
                    v = glm::cross(w, u);
        DVec3 lower(std::numeric_limits<double>::infinity()), upper(-std::numeric_limits<double>::infinity());
        for (int k = 0; k < 256; ++k) {
            const double phi = k * 2.0 * M_PI / 256;
            for (const DVec3 p : {base + double(cone.baseRadius) * (std::cos(phi) * u + std::sin(phi) * v),
                                  apex + double(cone.apexRadius) * (std::cos(phi) * u + std::sin(phi) * v)}) {
                lower = glm::min(lower, p);
                upper = glm::max(upper, p);
            }
        }
        const double magnitude = glm::length(base) + glm::length(apex) + size * 3.0;
        const double slack = 1e-3 * size * 2.0 + 4.0 * std::numeric_limits<float>::epsilon() * magnitude;
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_LE(double(b.lower[axis]), lower[axis]) << i;
            EXPECT_GE(double(b.upper[axis]), upper[axis]) << i;
            EXPECT_GE(double(b.lower[axis]), lower[axis] - slack) << i;
            EXPECT_LE(double(b.upper[axis]), upper[axis] + slack) << i;
        }
    }
    EXPECT_EQ(kCone.centroid(), kOffset + Vec3(0, 0, 2));
}

TEST(Cone, BaseAndApexAndTheSignOfBothRadiiDoNotChangeTheSurface) {
    // NFF's wider base is a convention, and negative radii mark the inside-only cone: the same
    // surface, the same hits.
    std::mt19937 rng(46);
    for (int i = 0; i < 2000; ++i) {
        const Cone cone = randomCone(rng, 1.0, DVec3(0.0));
        const Cone swapped{cone.apex, cone.apexRadius, cone.base, cone.baseRadius};
        const Cone inverted{cone.base, -cone.baseRadius, cone.apex, -cone.apexRadius};
        EXPECT_FALSE(isDegenerate(inverted));
        const Ray ray = Ray(Vec3(randomUnit(rng) * 5.0), Vec3(randomUnit(rng)));
        QuadricHitT<float> h{}, hs{}, hi{};
        const bool hit = hits<float>(ray, cone, &h);
        ASSERT_EQ(hits<float>(ray, inverted, &hi), hit) << i;
        if (hit) {
            EXPECT_EQ(h.t, hi.t);
        }
        bool grazing = false;
        referenceHit(ray, cone, 1.0, &grazing);
        if (grazing) continue;
        ASSERT_EQ(hits<float>(ray, swapped, &hs), hit) << i;
        if (hit) {
            EXPECT_NEAR(h.t, hs.t, 1e-5 * std::max(1.0f, h.t));
        }
    }
}

TEST(Cone, DegenerateConesAreNeverHit) {
    const Vec3 p(1, 2, 3), q(1, 2, 7);
    const Cone degenerate[] = {
        {p, 1.0f, p, 1.0f},   // base and apex coincide
        {p, 0.0f, q, 0.0f},   // a segment
        {p, 1.0f, q, -1.0f},  // radii of opposite signs
        {p, -2.0f, q, 0.5f},
        {p, kNaN, q, 1.0f},
        {p, 1.0f, q, kInfinity},
        {Vec3(kNaN, 2, 3), 1.0f, q, 1.0f},
        {p, 1.0f, Vec3(0, -kInfinity, 0), 1.0f},
        {p, 1e20f, q, 1.0f},                      // a radius whose square overflows
        {p, 1.0f, p + Vec3(1e-20f, 0, 0), 1.0f},  // an axis whose square underflows
    };
    std::mt19937 rng(47);
    std::uniform_real_distribution<float> U01(0.0f, 1.0f);
    int tested = 0;
    for (const Cone& cone : degenerate) {
        EXPECT_TRUE(isDegenerate(cone)) << &cone - degenerate;
        for (int i = 0; i < 200; ++i) {
            // Through points of the axis and of the unit circle around it, from near and far.
            const Vec3 target = p + U01(rng) * (q - p) + (i % 2 ? Vec3(1, 0, 0) : Vec3(0.0f));
            const Vec3 org = Vec3(widen(target) - randomUnit(rng) * (i % 3 ? 5.0 : 1e-3));
            const Ray ray = Ray(org, target - org, -kInfinity, kInfinity);
            EXPECT_FALSE(hits<float>(ray, cone)) << "cone #" << (&cone - degenerate) << " ray " << i;
            EXPECT_FALSE(hits<double>(ray, cone)) << "cone #" << (&cone - degenerate) << " ray " << i;
            ++tested;
        }
    }
    EXPECT_EQ(tested, 10 * 200);
    // Both radii negative, or one 0 and the other negative: NFF's inside-only cone, not degenerate.
    EXPECT_FALSE(isDegenerate(Cone{p, -1.0f, q, -1.0f}));
    EXPECT_FALSE(isDegenerate(Cone{p, -1.0f, q, 0.0f}));
    EXPECT_TRUE(hits(Ray(p + Vec3(-5, 0, 2), {1, 0, 0}), Cone{p, -1.0f, q, 0.0f}));
}

TEST(Cone, NaNRaysNeverHit) {
    test::expectNaNRaysMiss(intersectorOf(kCone), Ray(kOffset + Vec3(-10, 0, 2), {1, 0.01f, 0}));
}

}  // namespace
}  // namespace bvhlab
