// Every registered accelerator on scenes that mix triangles, spheres and cones (NFF's native
// primitives), against a double-precision brute force over all three kinds: closest hits,
// any hits, the primitive index space, the counters by kind, and rays leaving a quadric.
//
// The reference is decided in double (intersectTriangle/Sphere/Cone<double>). A ray whose
// answer is ill-conditioned -- it grazes a sphere or cone, or passes within rounding of a
// triangle's edge -- is left out: its reference answer changes when the ray moves by a
// millionth of the scene, so a float answer on either side of it is right.
#include "accel/naive/naive_accelerator.h"
#include "accel/registry.h"
#include "apps/common/program_keys.h"
#include "framework/scene/surface_point.h"
#include "tests/support/random_geometry.h"

#include <gtest/gtest.h>

#include <random>

namespace bvhlab {
namespace {

using test::randomPointWithin;
using test::randomUnit;

// Triangles, spheres (a few inside-visible, negative radius) and cones (cylinders, true cones,
// truncated ones) scattered in a box of side 20, and a few degenerate ones of each kind.
Scene makeMixedScene(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    const auto point = [&] { return Vec3(randomPointWithin(rng, 10.0)); };
    Scene scene;
    scene.name = "mixed";
    for (int i = 0; i < 300; ++i) {
        const Vec3 c = point();
        const float size = 0.2f + 2.0f * U(rng);
        const auto base = uint32_t(scene.positions.size());
        for (int k = 0; k < 3; ++k) scene.positions.push_back(c + size * Vec3(randomUnit(rng)));
        scene.indices.push_back({base, base + 1, base + 2});
    }
    scene.indices.push_back({0, 0, 0});  // degenerate
    for (int i = 0; i < 300; ++i) {
        const float r = 0.05f + 1.5f * U(rng);
        scene.spheres.push_back({point(), i % 10 == 0 ? -r : r});
    }
    scene.spheres.push_back({point(), 0.0f});  // degenerate
    for (int i = 0; i < 300; ++i) {
        const Vec3 base = point();
        const Vec3 apex = base + (0.3f + 3.0f * U(rng)) * Vec3(randomUnit(rng));
        const float r0 = 0.05f + U(rng), kind = U(rng);
        const float r1 = kind < 0.3f ? r0 : (kind < 0.6f ? 0.0f : r0 * U(rng));  // cylinder, cone, truncated
        scene.cones.push_back({base, r0, apex, r1});
    }
    scene.cones.push_back({point(), 1.0f, point(), -1.0f});  // degenerate: radii of opposite signs
    scene.finalize();
    return scene;
}

struct Reference {
    double t = std::numeric_limits<double>::infinity();
    uint32_t primitive = kInvalidPrimitive;
    bool found() const { return primitive != kInvalidPrimitive; }
};

Reference nearestInDouble(const PrimitiveSet& prims, const Ray& ray) {
    Reference best;
    const ShearedRayT<double> sheared(ray);
    const auto consider = [&](double t, uint32_t prim) {
        if (t < best.t) best = {t, prim};
    };
    for (uint32_t prim : prims.validTriangles()) {
        TriangleHitT<double> h;
        if (intersectTriangle<double>(sheared, prims.triangles[prim], ray.tmin, ray.tmax, h)) consider(h.t, prim);
    }
    for (uint32_t prim : prims.validQuadrics()) {
        QuadricHitT<double> h;
        if (intersectQuadric<double>(ray, prims.quadric(prim), ray.tmin, ray.tmax, h)) consider(h.t, prim);
    }
    return best;
}

bool sameAnswer(const Reference& a, const Reference& b) {
    if (a.found() != b.found()) return false;
    return !a.found() || std::abs(a.t - b.t) <= 1e-4 * std::max(1.0, std::abs(a.t));
}

// A ray whose reference answer stays the same when its origin moves by 1e-5 along each axis.
bool wellConditioned(const PrimitiveSet& prims, const Ray& ray, const Reference& answer) {
    for (int axis = 0; axis < 3; ++axis)
        for (const float step : {-1e-5f, 1e-5f}) {
            Ray moved = ray;
            moved.org[axis] += step;
            if (!sameAnswer(nearestInDouble(prims, moved), answer)) return false;
        }
    return true;
}

std::vector<Ray> mixedRays(const Scene& scene, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    std::vector<Ray> rays;
    const auto outside = [&] { return Vec3(30.0 * randomUnit(rng)); };
    for (int i = 0; i < 400; ++i) {  // from outside at random points of the scene
        const Vec3 org = outside();
        rays.push_back({org, Vec3(randomPointWithin(rng, 10.0)) - org});
    }
    for (int i = 0; i < 400; ++i) {  // at spheres, some passing just beside them
        const Sphere& s = scene.spheres[i % 300];
        const Vec3 org = outside();
        rays.push_back({org, s.centre + 1.2f * std::abs(s.radius) * Vec3(randomPointWithin(rng, 1.0)) - org});
    }
    for (int i = 0; i < 400; ++i) {  // at cones, around their axis
        const Cone& c = scene.cones[i % 300];
        const Vec3 org = outside();
        const Vec3 onAxis = c.base + U(rng) * (c.apex - c.base);
        rays.push_back({org, onAxis + 1.2f * std::abs(c.baseRadius) * Vec3(randomPointWithin(rng, 1.0)) - org});
    }
    for (int i = 0; i < 300; ++i) {  // from inside spheres
        const Sphere& s = scene.spheres[i % 300];
        rays.push_back({s.centre + 0.5f * std::abs(s.radius) * Vec3(randomPointWithin(rng, 1.0)), Vec3(randomUnit(rng))});
    }
    for (int i = 0; i < 200; ++i) {  // short intervals, inside and behind the origin
        Ray r{outside(), Vec3(randomUnit(rng)), -20.0f * U(rng), 40.0f * U(rng)};
        rays.push_back(r);
    }
    return rays;
}

class MixedPrimitives : public testing::TestWithParam<std::string> {};

TEST_P(MixedPrimitives, AgreeWithTheDoubleReference) {
    const Scene scene = makeMixedScene(7);
    const PrimitiveSet prims = scene.primitives();
    ASSERT_EQ(scene.report.degenerateTriangles, 1u);
    ASSERT_EQ(scene.report.degenerateSpheres, 1u);
    ASSERT_EQ(scene.report.degenerateCones, 1u);
    const auto accel = createAccelerator(GetParam(), Env(programKeys()));
    const BuildStats stats = accel->build(prims);
    EXPECT_EQ(stats.primitives, prims.valid.size());

    size_t checked = 0, hitsByKind[3] = {0, 0, 0};
    for (const Ray& ray : mixedRays(scene, 11)) {
        const Reference reference = nearestInDouble(prims, ray);
        if (!wellConditioned(prims, ray, reference)) continue;
        ++checked;
        QueryCounters counters;
        Hit hit;
        const bool found = accel->findNearest(ray, hit, counters);
        ASSERT_EQ(found, reference.found()) << GetParam() << ": ray " << checked << " reference t " << reference.t;
        ASSERT_EQ(accel->isOccluded(ray, counters), reference.found()) << GetParam();
        EXPECT_EQ(counters.queries, 2u);
        if (!found) continue;
        EXPECT_NEAR(hit.t, reference.t, 1e-4 * std::max(1.0, reference.t)) << GetParam();
        ++hitsByKind[int(prims.kind(hit.primitive))];
        // The primitive named is hit there (a tie may name another one at the same t).
        if (hit.primitive != reference.primitive) {
            Ray at = ray;
            at.tmin = hit.t - 1e-3f * std::max(1.0f, hit.t), at.tmax = hit.t + 1e-3f * std::max(1.0f, hit.t);
            PrimitiveSet only = prims;
            const uint32_t one[] = {hit.primitive};
            only.valid = one;
            EXPECT_TRUE(nearestInDouble(only, at).found()) << GetParam() << ": primitive " << hit.primitive;
        }
    }
    EXPECT_GT(checked, 1500u);
    for (int kind = 0; kind < 3; ++kind) EXPECT_GT(hitsByKind[kind], 50u) << "kind " << kind;
}

// Counters by kind: what naive tests per query is known exactly.
TEST(MixedPrimitives, NaiveCountsEveryKind) {
    const Scene scene = makeMixedScene(3);
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
    const Scene scene = makeMixedScene(5);
    const auto accel = createAccelerator("sahbvh8", Env(programKeys()));
    const BuildStats stats = accel->build(scene.primitives());
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
    const Scene scene = makeMixedScene(9);
    const PrimitiveSet prims = scene.primitives();
    NaiveAccelerator naive;
    naive.build(prims);
    std::mt19937 rng(1);
    size_t leaving = 0;
    for (uint32_t prim : prims.validQuadrics()) {
        const Vec3 centre(prims.quadric(prim).index() == 0 ? std::get<Sphere>(prims.quadric(prim)).centre
                                                           : std::get<Cone>(prims.quadric(prim)).centroid());
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

std::vector<std::string> registeredAccelerators() {
    std::vector<std::string> names;
    for (const AcceleratorInfo& info : acceleratorInfos()) names.push_back(info.name);
    return names;
}

INSTANTIATE_TEST_SUITE_P(Registered, MixedPrimitives, testing::ValuesIn(registeredAccelerators()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace bvhlab
