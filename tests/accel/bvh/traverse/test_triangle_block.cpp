// The wide layouts' leaf test (traverse/triangle_block_test.h) answers as the shared scalar
// watertight test, lane for lane and bit for bit: random rays, rays aimed at vertices and edge
// points (where rounding decides), axis-parallel rays, and the padding lanes of short leaves.
#include "accel/bvh/traverse/traversal.h"
#include "accel/bvh/traverse/triangle_block_test.h"
#include "accel/verify/verify_rng.h"
#include "framework/core/triangle_moller_trumbore.h"

#include <gtest/gtest.h>

#include <bit>
#include <vector>

namespace bvhlab {
namespace {

constexpr int kLanes = TriangleBlock::kLanes;
constexpr int kAllLanes = (1 << kLanes) - 1;

// A fan of triangles around a shared vertex, so that rays at the vertex and along the shared
// edges probe the cases the exact edge functions exist for.
std::vector<Triangle> fanAround(verify::VerifyRng& rng, Vec3 centre, int count) {
    std::vector<Triangle> fan;
    const Vec3 u(1.0f, 0.3f, -0.2f), v(-0.1f, 0.4f, 1.0f);
    for (int i = 0; i < count; ++i) {
        const float a0 = 6.2831853f * float(i) / float(count), a1 = 6.2831853f * float(i + 1) / float(count);
        const float r = float(rng.uniform(0.5, 2.0));
        fan.push_back({centre, centre + r * (std::cos(a0) * u + std::sin(a0) * v),
                       centre + r * (std::cos(a1) * u + std::sin(a1) * v)});
    }
    return fan;
}

std::vector<Ray> probeRays(verify::VerifyRng& rng, const std::vector<Triangle>& tris, int count) {
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        const Triangle& tri = tris[rng.index(tris.size())];
        Vec3 target;
        switch (i % 4) {
            case 0:
                target = tri.v0;
                break;  // a vertex
            case 1:
                target = tri.v1 + float(rng.uniform()) * (tri.v2 - tri.v1);
                break;  // an edge point
            case 2:
                target = tri.v0 + float(rng.uniform()) * (tri.v1 - tri.v0);
                break;
            default:
                target =
                    (tri.v0 + tri.v1 + tri.v2) * (1.0f / 3.0f) + Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), 0.0f);
        }
        Ray ray;
        ray.org = target + Vec3(rng.unitVector()) * float(rng.logUniform(0.1, 100.0));
        ray.dir = target - ray.org;
        if (i % 16 == 5) ray.dir = Vec3(0.0f, 0.0f, ray.dir.z);  // axis-parallel
        if (i % 8 == 3) ray.tmax = float(rng.uniform(0.5, 1.5));
        rays.push_back(ray);
    }
    return rays;
}

TriangleBlock blockOf(const std::vector<Triangle>& tris, size_t first, int lanes) {
    TriangleBlockLeaves leaves;
    std::vector<uint32_t> prims(lanes);
    leaves.appendLeaf(&tris[first], prims.data(), uint32_t(lanes));
    return leaves.blocks[0];
}

// Both block tests against their scalar forms: the watertight test (robust) and
// Moeller-Trumbore (BVH::robust=false).
template <bool Robust>
void expectLanesAnswerAsScalar(uint64_t seed) {
    verify::VerifyRng rng(seed);
    std::vector<Triangle> tris = fanAround(rng, Vec3(0.3f, -1.7f, 2.9f), 8);
    for (int i = 0; i < 8; ++i)
        tris.push_back(
            {rng.inBox({Vec3(-3), Vec3(3)}), rng.inBox({Vec3(-3), Vec3(3)}), rng.inBox({Vec3(-3), Vec3(3)})});
    size_t hits = 0;
    for (const Ray& ray : probeRays(rng, tris, 4000)) {
        const ShearedRay sheared(ray);
        const BlockTriangleTest<Robust> test(ray);
        for (size_t first = 0; first + kLanes <= tris.size(); first += kLanes) {
            const BlockHits block = test.intersect(blockOf(tris, first, kLanes), ray.tmin, ray.tmax);
            for (int lane = 0; lane < kLanes; ++lane) {
                TriangleHitT<float> h{};  // set only on a hit; {} keeps GCC from warning
                const bool hit = Robust
                                     ? intersectTriangle(sheared, tris[first + lane], ray.tmin, ray.tmax, h)
                                     : intersectTriangleMollerTrumbore(ray, tris[first + lane], ray.tmin, ray.tmax, h);
                ASSERT_EQ(bool(block.mask >> lane & 1), hit) << "triangle " << first + lane;
                if (!hit) continue;
                ++hits;
                const TriangleHitT<float> laneHit = hitInLane(block, lane);
                EXPECT_EQ(std::bit_cast<uint32_t>(laneHit.t), std::bit_cast<uint32_t>(h.t));
                EXPECT_EQ(std::bit_cast<uint32_t>(laneHit.u), std::bit_cast<uint32_t>(h.u));
                EXPECT_EQ(std::bit_cast<uint32_t>(laneHit.v), std::bit_cast<uint32_t>(h.v));
            }
        }
    }
    EXPECT_GT(hits, 1000u);  // the probes do reach the triangles
}

TEST(TriangleBlock, LanesAnswerAsTheScalarWatertightTest) { expectLanesAnswerAsScalar<true>(11); }

TEST(TriangleBlock, LanesAnswerAsScalarMollerTrumbore) { expectLanesAnswerAsScalar<false>(14); }

// A leaf of 1-7 triangles pads its block with repeats of its last triangle: they hit exactly
// where that triangle does, and the block's closest lane is the triangle's own.
TEST(TriangleBlock, PaddingLanesRepeatTheLastTriangle) {
    verify::VerifyRng rng(12);
    const std::vector<Triangle> tris = fanAround(rng, Vec3(1.0f, 2.0f, 3.0f), kLanes - 1);
    size_t hits = 0;
    for (int lanes = 1; lanes < kLanes; ++lanes) {
        const TriangleBlock block = blockOf(tris, 0, lanes);
        const Triangle& last = tris[lanes - 1];
        const Vec3 centre = (last.v0 + last.v1 + last.v2) / 3.0f;
        for (int i = 0; i < 200; ++i) {
            Ray ray;
            ray.org = centre + Vec3(rng.unitVector()) * 3.0f;
            ray.dir = centre - ray.org;
            for (const BlockHits& h : {BlockTriangleTest<true>(ray).intersect(block, 0.0f, kInfinity),
                                       BlockTriangleTest<false>(ray).intersect(block, 0.0f, kInfinity)}) {
                const bool lastHit = (h.mask >> (lanes - 1) & 1) != 0;
                EXPECT_EQ(h.mask >> lanes, lastHit ? kAllLanes >> lanes : 0) << lanes << " lanes";
                if (h.mask == 0) continue;
                ++hits;
                EXPECT_LT(closestLane(h), lanes);
            }
        }
    }
    EXPECT_GT(hits, 1000u);
}

// A leaf of blocks counts and chooses as the binary layout's loop over the same triangles.
TEST(TriangleBlock, LeafCountsAndChoosesAsTheScalarLoop) {
    verify::VerifyRng rng(13);
    std::vector<Triangle> tris = fanAround(rng, Vec3(0.0f), 2 * kLanes - 1);
    tris.push_back(tris[2]);                                     // a duplicate: equal t in two lanes
    for (uint32_t count : {1u, 3u, 4u, 5u, 8u, 9u, 13u, 16u}) {  // one block, and two
        TriangleBlockLeaves leaves;
        std::vector<uint32_t> prims(count);
        const uint32_t leaf = wide_child::leaf(leaves.appendLeaf(tris.data(), prims.data(), count), blocksFor(count));
        for (const Ray& ray : probeRays(rng, std::vector<Triangle>(tris.begin(), tris.begin() + count), 300)) {
            const LeafTriangleTest<true> scalar(ray);
            const BlockTriangleTest<true> block(ray);
            ClosestHitQuery nearA(ray), nearB(ray);
            uint64_t testsA = 0, testsB = 0;
            testLeaf(nearA, scalar, tris.data(), 0, count, ray.tmin, testsA);
            testLeafBlocks<true>(nearB, block, leaves, leaf, ray.tmin, testsB);
            EXPECT_EQ(nearB.found, nearA.found);
            EXPECT_EQ(testsB, testsA);
            AnyHitQuery anyA(ray), anyB(ray);
            testsA = testsB = 0;
            EXPECT_EQ(testLeafBlocks<true>(anyB, block, leaves, leaf, ray.tmin, testsB),
                      testLeaf(anyA, scalar, tris.data(), 0, count, ray.tmin, testsA));
            EXPECT_EQ(anyB.occluded, anyA.occluded);
            EXPECT_EQ(testsB, testsA) << "any hit counts up to the occluder";
        }
    }
}

}  // namespace
}  // namespace bvhlab
