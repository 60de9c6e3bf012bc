// The ray-triangle test is watertight: no ray slips between two triangles along a shared edge
// or around a shared vertex, because its edge functions have the exact sign.
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

// Two triangles sharing the edge a-b, the other vertices c and d on opposite sides. With
// `consistent` the shared edge runs a->b in one and b->a in the other (a consistently wound
// mesh); otherwise a->b in both.
struct EdgePair {
    Triangle first, second;
    Vec3 a, b, c, d;
};

// A ray through a point of the shared edge (away from its ends), from a far origin, for which
// the two triangles lie on opposite sides of the edge as seen along the ray and neither is
// nearly edge-on: it must hit at least one of them.
struct WatertightCounts {
    int rays = 0, leaksFloat = 0, leaksDouble = 0;
};

WatertightCounts shootThroughSharedEdges(bool consistent, uint32_t seed, int pairs, int raysPerPair) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    WatertightCounts counts;
    for (int k = 0; k < pairs; ++k) {
        const double scale = std::exp(U(rng) * 10.0 - 5.0);
        const glm::dvec3 offset = randomUnit(rng) * scale * 10.0 * U(rng);
        const Vec3 a = Vec3(offset + randomUnit(rng) * scale), b = Vec3(offset + randomUnit(rng) * scale),
                   c = Vec3(offset + randomUnit(rng) * scale), d = Vec3(offset + randomUnit(rng) * scale);
        const Triangle t1{a, b, c};
        const Triangle t2 = consistent ? Triangle{b, a, d} : Triangle{a, b, d};
        const glm::dvec3 A(a), B(b), C(c), Dd(d);
        const glm::dvec3 n1 = glm::normalize(glm::cross(B - A, C - A)), n2 = glm::normalize(glm::cross(B - A, Dd - A));
        // Reasonably shaped triangles: no slivers (the ends of the edge are then well defined).
        auto minAngleSin = [](const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r) {
            const double area2 = glm::length(glm::cross(q - p, r - p));
            const double l0 = glm::length(q - p), l1 = glm::length(r - q), l2 = glm::length(p - r);
            return std::min({area2 / (l0 * l2), area2 / (l0 * l1), area2 / (l1 * l2)});
        };
        if (minAngleSin(A, B, C) < 0.2 || minAngleSin(A, B, Dd) < 0.2) continue;
        for (int i = 0; i < raysPerPair; ++i) {
            const float s = float(0.02 + 0.96 * U(rng));
            const Vec3 p = a + s * (b - a);
            const double dist = scale * std::exp(U(rng) * 7.0 - 1.0);  // 0.4 .. 400 triangle sizes
            const Vec3 org = Vec3(glm::dvec3(p) + randomUnit(rng) * dist);
            const Ray ray = Ray(org, p - org);
            const glm::dvec3 dir = glm::normalize(glm::dvec3(ray.dir));
            if (std::abs(glm::dot(dir, n1)) < 0.05 || std::abs(glm::dot(dir, n2)) < 0.05) continue;
            // Seen along the ray, c and d must be on opposite sides of the edge line.
            const glm::dvec3 side = glm::cross(B - A, dir);
            if (glm::dot(side, C - A) * glm::dot(side, Dd - A) >= 0) continue;
            ++counts.rays;
            if (!hitsF(ray, t1) && !hitsF(ray, t2)) {
                ++counts.leaksFloat;
                if (counts.leaksFloat <= 3)
                    ADD_FAILURE() << "float leak between two triangles sharing an edge: org=(" << org.x << ", " << org.y
                                  << ", " << org.z << ") through (" << p.x << ", " << p.y << ", " << p.z
                                  << "), edge s=" << s << (consistent ? " (consistent winding)" : " (same direction)");
            }
            if (!hitsD(ray, t1) && !hitsD(ray, t2)) ++counts.leaksDouble;
        }
    }
    return counts;
}

TEST(Triangle, WatertightAlongSharedEdgesConsistentWinding) {
    const WatertightCounts c = shootThroughSharedEdges(true, 11, 3000, 200);
    EXPECT_GT(c.rays, 100000);
    EXPECT_EQ(c.leaksFloat, 0) << "of " << c.rays << " rays";
    EXPECT_EQ(c.leaksDouble, 0) << "of " << c.rays << " rays";
}

TEST(Triangle, WatertightAlongSharedEdgesSameDirection) {
    const WatertightCounts c = shootThroughSharedEdges(false, 12, 3000, 200);
    EXPECT_GT(c.rays, 100000);
    EXPECT_EQ(c.leaksFloat, 0) << "of " << c.rays << " rays";
    EXPECT_EQ(c.leaksDouble, 0) << "of " << c.rays << " rays";
}

TEST(Triangle, WatertightAroundASharedVertex) {
    // A fan of 6 triangles around vertex 0 (consistently wound): rays through the vertex, and
    // through points on the spokes, from many directions within the fan's normal cone.
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    int rays = 0, leaks = 0;
    for (int k = 0; k < 300; ++k) {
        const double scale = std::exp(U(rng) * 8.0 - 4.0);
        const glm::dvec3 center = randomUnit(rng) * scale * 5.0 * U(rng);
        const glm::dvec3 axis = randomUnit(rng);
        const glm::dvec3 e1 = glm::normalize(glm::cross(axis, randomUnit(rng)));
        const glm::dvec3 e2 = glm::cross(axis, e1);
        std::vector<Vec3> rim;
        for (int i = 0; i < 6; ++i) {
            const double phi = (i + 0.3 * U(rng)) * 2.0 * M_PI / 6.0;
            rim.push_back(
                Vec3(center + scale * (std::cos(phi) * e1 + std::sin(phi) * e2 + 0.3 * (U(rng) - 0.5) * axis)));
        }
        const Vec3 apex = Vec3(center);
        std::vector<Triangle> fan;
        for (int i = 0; i < 6; ++i) fan.push_back({apex, rim[i], rim[(i + 1) % 6]});
        for (int i = 0; i < 100; ++i) {
            // Directions within 60 degrees of the axis, from either side.
            glm::dvec3 d = randomUnit(rng);
            if (std::abs(glm::dot(d, axis)) < 0.5) continue;
            const bool throughVertex = i % 2 == 0;
            const Vec3 p = throughVertex ? apex : apex + float(0.05 + 0.9 * U(rng)) * (rim[i % 6] - apex);
            const Vec3 org = Vec3(glm::dvec3(p) + d * scale * std::exp(U(rng) * 6.0 - 1.0));
            const Ray ray = Ray(org, p - org);
            bool hit = false;
            for (const Triangle& t : fan) hit = hit || hitsF(ray, t);
            ++rays;
            if (!hit) ++leaks;
        }
    }
    EXPECT_GT(rays, 10000);
    EXPECT_EQ(leaks, 0) << "of " << rays << " rays through a vertex or a spoke of a closed fan";
}

// edgeFunction's sign is the exact sign of a*b - c*d (products exact in double, so the double
// difference has it) on the cases that decide watertightness: differences near 0, where plain
// float products round to the wrong sign or to 0, tiny and huge magnitudes, and exact zeros.
TEST(Triangle, EdgeFunctionHasTheExactSign) {
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    std::uniform_real_distribution<float> E(-40.0f, 40.0f);
    int plainFloatWrong = 0;
    for (int i = 0; i < 200000; ++i) {
        const float scale = std::exp2(E(rng));
        const float a = U(rng) * scale, b = U(rng) * scale, c = U(rng) * scale;
        // d so that c*d is a*b to within rounding, nudged by a few ulps either way or not.
        float d = c != 0.0f ? float(double(a) * double(b) / double(c)) : U(rng);
        for (int k = int(rng() % 5) - 2; k != 0; k += k > 0 ? -1 : 1)
            d = std::nextafter(d, k > 0 ? kInfinity : -kInfinity);
        const double exact = double(a) * double(b) - double(c) * double(d);
        const float e = edgeFunction(a, b, c, d);
        ASSERT_EQ((e > 0) - (e < 0), (exact > 0) - (exact < 0)) << a << " " << b << " " << c << " " << d;
        const volatile float ab = a * b, cd = c * d;  // what plain float would decide
        const float plain = ab - cd;
        plainFloatWrong += (plain > 0) - (plain < 0) != (exact > 0) - (exact < 0);
    }
    EXPECT_GT(plainFloatWrong, 1000);  // the cases do need more than float
    EXPECT_EQ(edgeFunction(0.1f, 0.7f, 0.7f, 0.1f), 0.0f);
    EXPECT_EQ(edgeFunction(3.0f, 1.0f / 3.0f, 1.0f, 3.0f * (1.0f / 3.0f)), edgeFunction(3.0f, 1.0f / 3.0f, 1.0f, 1.0f));
}

}  // namespace
}  // namespace bvhlab::test
