// Float against the double reference of a ray-quadric test (<bvhlab/sphere.h>, <bvhlab/cone.h>),
// ray by ray. Where both hit, t must agree to 1e-4 relative to max(|t|, size/|dir|): the
// 1e-4*max(1,|t|) of hitsAgree for a primitive of unit size, the same standard for huge and tiny
// ones. Hit against miss is allowed only for rays the caller's independent geometry marks as
// grazing (within a narrow band of a tangent or of a rim); such rays are counted.
#pragma once

#include "tests/support/random_geometry.h"

#include <bvhlab/cone.h>
#include <bvhlab/quadric.h>
#include <bvhlab/ray.h>
#include <bvhlab/sphere.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <random>

namespace bvhlab::test {

struct QuadricAgreement {
    int rays = 0, bothHit = 0, bothMissed = 0;
    int grazing = 0, grazingDisagreements = 0;  // rays in the band, and those of them that disagree
    double maxRelativeError = 0.0, maxGrazingRelativeError = 0.0;

    // Returns whether the float test hit.
    template <typename Intersect>
    bool compare(const Intersect& intersect, const Ray& ray, double size, bool isGrazing) {
        QuadricHitT<float> hf{};
        QuadricHitT<double> hd{};
        const bool f = intersect(ray, double(ray.tmin), double(ray.tmax), hf);
        const bool d = intersect(ray, double(ray.tmin), double(ray.tmax), hd);
        ++rays;
        grazing += isGrazing;
        if (f != d) {
            if (isGrazing) {
                ++grazingDisagreements;
            } else if (++ungrazedDisagreements <= 3) {
                ADD_FAILURE() << "float " << (f ? "hit" : "missed") << ", double " << (d ? "hit" : "missed")
                              << " away from the grazing band: org (" << ray.org.x << ", " << ray.org.y << ", "
                              << ray.org.z << ") dir (" << ray.dir.x << ", " << ray.dir.y << ", " << ray.dir.z << ")";
            }
        }
        if (f) {
            EXPECT_TRUE(std::isfinite(hf.t) && isFinite(hf.normal)) << "a NaN or infinite hit";
            EXPECT_NEAR(glm::length(hf.normal), 1.0f, 1e-5f);
        }
        if (!f || !d) {
            bothMissed += !f && !d;
            return f;
        }
        ++bothHit;
        // Near a tangent t itself is ill-conditioned (it moves with the square root of the miss
        // distance): its error there is recorded, not bounded.
        const double error =
            std::abs(double(hf.t) - hd.t) / std::max(std::abs(hd.t), size / glm::length(DVec3(ray.dir)));
        if (isGrazing) {
            maxGrazingRelativeError = std::max(maxGrazingRelativeError, error);
            return f;
        }
        maxRelativeError = std::max(maxRelativeError, error);
        EXPECT_LE(error, 1e-4) << "float t " << hf.t << ", double t " << hd.t;
        EXPECT_GT(glm::dot(DVec3(hf.normal), hd.normal), 1.0 - 1e-4) << "normals differ";
        return f;
    }

    // Prints the counts and checks that the rays were a fair mix and the band stayed narrow.
    void expectCounts(const char* what, int minBothHit, int minBothMissed, int maxGrazing) const {
        std::printf(
            "[ NOTE     ] %s: %d rays, %d hit by both, %d missed by both; max relative t error %.3g; "
            "%d grazing, %d of them float and double disagree on, max relative t error there %.3g\n",
            what, rays, bothHit, bothMissed, maxRelativeError, grazing, grazingDisagreements, maxGrazingRelativeError);
        EXPECT_GE(bothHit, minBothHit) << what;
        EXPECT_GE(bothMissed, minBothMissed) << what;
        EXPECT_LE(grazing, maxGrazing) << what;
    }

private:
    int ungrazedDisagreements = 0;
};

// The ray-quadric tests under one name, for the helpers below.
template <typename Real>
bool intersectQuadric(const Ray& ray, const Sphere& sphere, Real tmin, Real tmax, QuadricHitT<Real>& out) {
    return intersectSphere(ray, sphere, tmin, tmax, out);
}
template <typename Real>
bool intersectQuadric(const Ray& ray, const Cone& cone, Real tmin, Real tmax, QuadricHitT<Real>& out) {
    return intersectCone(ray, cone, tmin, tmax, out);
}

// A primitive's float and double tests as one callable, the hit record's type choosing.
template <typename Primitive>
auto intersectorOf(const Primitive& primitive) {
    return [&primitive](const Ray& ray, double tmin, double tmax, auto& hit) {
        using Real = decltype(hit.t);
        return intersectQuadric<Real>(ray, primitive, Real(tmin), Real(tmax), hit);
    };
}

// The float or double test over the ray's own interval.
template <typename Real = float, typename Primitive>
bool hits(const Ray& ray, const Primitive& primitive, QuadricHitT<Real>* out = nullptr) {
    QuadricHitT<Real> h{};
    const bool hit = intersectorOf(primitive)(ray, double(ray.tmin), double(ray.tmax), h);
    if (hit && out) *out = h;
    return hit;
}

// `count` primitives of sizes log-uniform over [minSize, maxSize] within maxOffset of the origin:
// compareOne(rng, size, offset, agreement) makes one of `size` around `offset` and a ray, and
// compares the two tests on them.
template <typename CompareOne>
QuadricAgreement agreementOnRandomRays(uint32_t seed, int count, double minSize, double maxSize, double maxOffset,
                                       const CompareOne& compareOne) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    QuadricAgreement agreement;
    for (int i = 0; i < count; ++i) {
        const double size = minSize * std::pow(maxSize / minSize, U(rng));
        compareOne(rng, size, randomPointWithin(rng, maxOffset), agreement);
    }
    return agreement;
}

// 100000 rays passing the surfaces of primitives of 1e-3 to 1e4 at 1e-9 to 1e-2 sizes,
// alternately inside and out: compareOne(rng, size, miss, agreement) makes a primitive of `size`
// and a ray passing it at miss * size (inside if negative) and compares the two tests on them.
template <typename CompareOne>
void expectTangentRaysAgree(uint32_t seed, const CompareOne& compareOne) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    QuadricAgreement agreement;
    for (int i = 0; i < 100000; ++i) {
        const double size = randomScale(rng);
        const double miss = (i % 2 ? 1.0 : -1.0) * std::pow(10.0, -9 + 7 * U(rng));
        compareOne(rng, size, miss, agreement);
    }
    // Any number may be grazing, but float must round differently there: the band is not empty.
    agreement.expectCounts("tangent rays", 20000, 20000, 100000);
    EXPECT_GT(agreement.grazingDisagreements, 0) << "no disagreement in the band";
}

// A ray that hits, with a NaN put in each of its fields in turn, and with a zero direction:
// neither the float nor the double test may hit.
template <typename Intersect>
void expectNaNRaysMiss(const Intersect& intersect, const Ray& good) {
    QuadricHitT<float> hf{};
    QuadricHitT<double> hd{};
    ASSERT_TRUE(intersect(good, double(good.tmin), double(good.tmax), hf));
    for (int field = 0; field < 9; ++field) {
        Ray ray = good;
        float* fields[8] = {&ray.org.x, &ray.org.y, &ray.org.z, &ray.dir.x,
                            &ray.dir.y, &ray.dir.z, &ray.tmin,  &ray.tmax};
        if (field < 8)
            *fields[field] = std::numeric_limits<float>::quiet_NaN();
        else
            ray.dir = Vec3(0.0f);
        EXPECT_FALSE(intersect(ray, double(ray.tmin), double(ray.tmax), hf)) << "field " << field;
        EXPECT_FALSE(intersect(ray, double(ray.tmin), double(ray.tmax), hd)) << "field " << field;
    }
}

}  // namespace bvhlab::test
