// Refitting (layout/refit.h) through BvhAccelerator::update: after the primitives moved, every
// box of the binary, 4- and 8-wide layouts holds exactly what is below it, the leaves hold the
// moved triangles, and the queries answer as a fresh build over the moved primitives does.
#include "accel/bvh/bvh_accelerator.h"
#include "accel/bvh/layout/refit.h"
#include "accel/naive/naive_accelerator.h"
#include "tests/support/bvh_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace bvhlab {
namespace {

using test::allBuilders;
using test::randomSoup;
using test::Soup;

// The soup moved as an animation moves it: the first half turned about z and shifted (a rigid
// part), one vertex in three of the rest pushed by up to `jitter`. Deterministic.
Soup moved(const Soup& soup, float shift, float jitter) {
    Soup out = soup;
    const float c = std::cos(0.4f), s = std::sin(0.4f);
    for (size_t i = 0; i < out.triangles.size(); ++i) {
        Triangle& t = out.triangles[i];
        Vec3* vertices[3] = {&t.v0, &t.v1, &t.v2};
        for (int k = 0; k < 3; ++k) {
            Vec3& v = *vertices[k];
            if (i < out.triangles.size() / 2)
                v = Vec3(c * v.x - s * v.y, s * v.x + c * v.y, v.z) + Vec3(shift, 0.5f * shift, -shift);
            else if ((i + k) % 3 == 0)
                v += jitter * Vec3(float(i % 7) / 7.0f - 0.5f, float(i % 5) / 5.0f - 0.5f, 0.3f);
        }
    }
    return out;
}

Bounds3 laneBox(const float (&lower)[3][8], const float (&upper)[3][8], int lane) {
    return {{lower[0][lane], lower[1][lane], lower[2][lane]}, {upper[0][lane], upper[1][lane], upper[2][lane]}};
}

// Walks a wide tree: each leaf lane's blocks hold the soup's triangles of its primitive indices
// (padding repeating the last), each lane's box is exactly the box of what it holds, and each
// node's order is the one its boxes give. Returns the node's box.
template <int N>
Bounds3 checkWideNode(const WideBvh<N>& bvh, const Soup& soup, uint32_t n) {
    const WideNode<N>& node = bvh.nodes[n];
    Bounds3 all;
    for (int i = 0; i < N; ++i) {
        const uint32_t child = node.child[i];
        if (child == 0) continue;
        Bounds3 expected;
        if (wide_child::isLeaf(child)) {
            const uint32_t first = wide_child::firstBlock(child);
            const Triangle* last = nullptr;
            for (uint32_t b = first; b < first + wide_child::blocks(child); ++b)
                for (int lane = 0; lane < TriangleBlock::kLanes; ++lane) {
                    const uint32_t prim = bvh.primIndices[size_t(b) * TriangleBlock::kLanes + lane];
                    if (prim != kInvalidPrimitive) {
                        last = &soup.triangles[prim];
                        expected.extend(last->bounds());
                    }
                    if (!last) {
                        ADD_FAILURE() << "a leaf lane whose first lane is padding, block " << b;
                        return all;
                    }
                    const Triangle t = bvh.blocks[b].triangle(lane);
                    EXPECT_TRUE(t.v0 == last->v0 && t.v1 == last->v1 && t.v2 == last->v2) << "block " << b;
                }
        } else {
            expected = checkWideNode(bvh, soup, child);
        }
        Bounds3 lane;
        for (int a = 0; a < 3; ++a) lane.lower[a] = node.lower[a][i], lane.upper[a] = node.upper[a][i];
        EXPECT_TRUE(lane.lower == expected.lower && lane.upper == expected.upper) << "node " << n << " lane " << i;
        all = unionOf(all, lane);
    }
    WideNode<N> reordered = node;
    orderChildren(reordered);
    for (int p = 0; p < N; ++p) EXPECT_EQ(node.order[p], reordered.order[p]) << "node " << n;
    return all;
}

// Both queries of `updated` against those of a fresh build over the same primitives: the same
// hits at the same t (bit for bit: one triangle test), the same occlusion.
void expectAnswersAsFresh(const Accelerator& updated, const Accelerator& fresh, float extent, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-0.3f * extent, 1.3f * extent);
    int mismatches = 0;
    for (int i = 0; i < 2000 && mismatches < 5; ++i) {
        const Vec3 org(pos(rng), pos(rng), pos(rng)), target(pos(rng), pos(rng), pos(rng));
        const Ray ray(org, target - org);
        Hit a, b;
        QueryCounters counters;
        const bool foundA = updated.findNearest(ray, a, counters), foundB = fresh.findNearest(ray, b, counters);
        const bool occludedA = updated.isOccluded(ray, counters), occludedB = fresh.isOccluded(ray, counters);
        if (foundA != foundB || a.t != b.t || !hitsAgree(a, b) || occludedA != occludedB) {
            ++mismatches;
            ADD_FAILURE() << updated.name() << " ray " << i << ": updated t=" << a.t << " prim " << a.primitive
                          << ", fresh t=" << b.t << " prim " << b.primitive;
        }
    }
}

TEST(Refit, BinaryBoxesHoldExactlyTheMovedTriangles) {
    const Soup soup = randomSoup(3000, 5), after = moved(soup, 2.0f, 0.5f);
    for (const BuilderRecord& kind : allBuilders()) {
        SCOPED_TRACE(kind.name);
        BvhAccelerator<BinaryBvh> updated(kind, BvhBuildConfig{}), fresh(kind, BvhBuildConfig{});
        updated.build(soup.prims());
        ASSERT_TRUE(updated.update(after.prims()));
        test::checkTree(updated.bvh(), after);  // boxes exactly the union of what they hold
        fresh.build(after.prims());
        expectAnswersAsFresh(updated, fresh, 12.0f, 7);
        test::expectAgreesWithNaive(updated, after, 500, 12.0f, 8);
    }
}

TEST(Refit, WideLanesHoldExactlyTheMovedTriangles) {
    const Soup soup = randomSoup(3000, 9), after = moved(soup, 3.0f, 0.8f);
    const BuilderRecord& kind = builderRecord("sahbvh");
    BvhAccelerator<WideBvh<4>> updated4(kind, BvhBuildConfig{}), fresh4(kind, BvhBuildConfig{});
    BvhAccelerator<WideBvh<8>> updated8(kind, BvhBuildConfig{}), fresh8(kind, BvhBuildConfig{});
    updated4.build(soup.prims());
    updated8.build(soup.prims());
    ASSERT_TRUE(updated4.update(after.prims()));
    ASSERT_TRUE(updated8.update(after.prims()));
    checkWideNode(updated4.bvh(), after, 0);
    checkWideNode(updated8.bvh(), after, 0);
    fresh4.build(after.prims());
    fresh8.build(after.prims());
    expectAnswersAsFresh(updated4, fresh4, 13.0f, 10);
    expectAnswersAsFresh(updated8, fresh8, 13.0f, 11);
}

TEST(Refit, OverTheBuiltPrimitivesTheBoxesAreTheBuilds) {
    // A refit changes nothing the build made, order of the children included: the refit's boxes
    // are the builder's, computed the same way.
    const Soup soup = randomSoup(2000, 12);
    const BuilderRecord& kind = builderRecord("sahbvh");
    BvhAccelerator<BinaryBvh> binary(kind, BvhBuildConfig{});
    BvhAccelerator<WideBvh<8>> wide(kind, BvhBuildConfig{});
    binary.build(soup.prims());
    wide.build(soup.prims());
    const BinaryBvh binaryBefore = binary.bvh();
    const WideBvh<8> wideBefore = wide.bvh();
    ASSERT_TRUE(binary.update(soup.prims()));
    ASSERT_TRUE(wide.update(soup.prims()));
    ASSERT_EQ(binary.bvh().nodes.size(), binaryBefore.nodes.size());
    for (size_t n = 0; n < binaryBefore.nodes.size(); ++n) {
        if (n == 1) continue;  // the padding slot
        EXPECT_TRUE(binary.bvh().nodes[n].box().lower == binaryBefore.nodes[n].box().lower &&
                    binary.bvh().nodes[n].box().upper == binaryBefore.nodes[n].box().upper)
            << "node " << n;
    }
    ASSERT_EQ(wide.bvh().nodes.size(), wideBefore.nodes.size());
    for (size_t n = 0; n < wideBefore.nodes.size(); ++n)
        for (int i = 0; i < 8; ++i) {
            const Bounds3 a = laneBox(wide.bvh().nodes[n].lower, wide.bvh().nodes[n].upper, i);
            const Bounds3 b = laneBox(wideBefore.nodes[n].lower, wideBefore.nodes[n].upper, i);
            EXPECT_TRUE(a.lower == b.lower && a.upper == b.upper) << "node " << n << " lane " << i;
            EXPECT_EQ(wide.bvh().nodes[n].order[i], wideBefore.nodes[n].order[i]);
        }
}

TEST(Refit, StatisticsDescribeTheRefittedTree) {
    // The wide layouts report their binary tree's figures, refitted as the wide tree was: those
    // of the binary accelerator refitted over the same moves, with leaves charged by blocks.
    const Soup soup = randomSoup(4000, 14), after = moved(soup, 4.0f, 1.0f);
    const BuilderRecord& kind = builderRecord("sahbvh");
    BvhBuildConfig blocks;
    blocks.shared.sahBlockShift = 3;
    BvhAccelerator<BinaryBvh> binary(kind, blocks);
    BvhAccelerator<WideBvh<8>> wide(kind, BvhBuildConfig{});
    binary.build(soup.prims());
    wide.build(soup.prims());
    const BuildStats built = wide.buildStats();
    ASSERT_TRUE(binary.update(after.prims()));
    ASSERT_TRUE(wide.update(after.prims()));
    const BuildStats refitted = wide.buildStats(), expected = binary.buildStats();
    ASSERT_TRUE(refitted.sah && expected.sah && built.sah);
    EXPECT_EQ(refitted.sah->cost, expected.sah->cost);
    EXPECT_EQ(refitted.epo, expected.epo);
    EXPECT_EQ(refitted.nodes, built.nodes);
    EXPECT_GT(refitted.sah->cost, built.sah->cost);  // half the triangles moved apart from the rest
    // A second update is refitted again from the first's.
    ASSERT_TRUE(binary.update(soup.prims()));
    ASSERT_TRUE(wide.update(soup.prims()));
    EXPECT_EQ(wide.buildStats().sah->cost, built.sah->cost);
}

TEST(Refit, InsertionAfterTheRefitLowersTheSahAndAnswersAlike) {
    const Soup soup = randomSoup(3000, 21), after = moved(soup, 5.0f, 1.0f);
    const BuilderRecord& kind = builderRecord("sahbvh");
    NaiveAccelerator naive;
    naive.build(after.prims());
    BvhAccelerator<BinaryBvh> refit(kind, BvhBuildConfig{});
    refit.build(soup.prims());
    ASSERT_TRUE(refit.update(after.prims()));
    const double refitSah = refit.buildStats().sah->cost;
    for (int width : {2, 8}) {
        SCOPED_TRACE(width);
        std::unique_ptr<Accelerator> accel;
        if (width == 2)
            accel = std::make_unique<BvhAccelerator<BinaryBvh>>(
                kind, BvhBuildConfig{}, TraversalConfig{}, BvhStatsConfig{}, BvhUpdateConfig{BvhUpdate::Insertion});
        else
            accel = std::make_unique<BvhAccelerator<WideBvh<8>>>(
                kind, BvhBuildConfig{}, TraversalConfig{}, BvhStatsConfig{}, BvhUpdateConfig{BvhUpdate::Insertion});
        accel->build(soup.prims());
        ASSERT_TRUE(accel->update(after.prims()));
        if (width == 2) {
            test::checkTree(static_cast<BvhAccelerator<BinaryBvh>&>(*accel).bvh(), after);
            EXPECT_LT(statisticsOf(*accel).sah->cost, refitSah);
        }
        expectAnswersAsFresh(*accel, naive, 16.0f, 22);
    }
}

TEST(Refit, QuadricTreeFollowsTheSpheresAndCones) {
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> pos(0.0f, 10.0f), size(0.1f, 0.6f);
    std::vector<Sphere> spheres, movedSpheres;
    std::vector<Cone> cones, movedCones;
    for (int i = 0; i < 300; ++i) {
        const Vec3 c(pos(rng), pos(rng), pos(rng));
        spheres.push_back({c, size(rng)});
        cones.push_back({c + Vec3(0.5f), size(rng), c + Vec3(0.5f, 1.5f, 0.5f), size(rng)});
        const Vec3 shift = i % 2 ? Vec3(3.0f, -1.0f, 2.0f) : Vec3(0.0f);
        movedSpheres.push_back({spheres.back().centre + shift, spheres.back().radius * 1.5f});
        movedCones.push_back(
            {cones.back().base - shift, cones.back().baseRadius, cones.back().apex - shift, cones.back().apexRadius});
    }
    const Soup soup = randomSoup(200, 32), after = moved(soup, 1.0f, 0.5f);
    std::vector<uint32_t> valid = soup.valid;
    for (uint32_t p = 0; p < spheres.size() + cones.size(); ++p) valid.push_back(uint32_t(soup.triangles.size()) + p);
    const PrimitiveSet before{soup.triangles, valid, spheres, cones},
        now{after.triangles, valid, movedSpheres, movedCones};
    NaiveAccelerator naive;
    naive.build(now);
    BvhAccelerator<WideBvh<8>> updated(builderRecord("sahbvh"), BvhBuildConfig{});
    updated.build(before);
    ASSERT_TRUE(updated.update(now));
    expectAnswersAsFresh(updated, naive, 12.0f, 33);
}

TEST(Refit, RebuildMeansNoUpdateAndOtherCountsAreRefused) {
    const Soup soup = randomSoup(500, 41), fewer = randomSoup(400, 41);
    BvhAccelerator<BinaryBvh> rebuild(builderRecord("sahbvh"), BvhBuildConfig{}, TraversalConfig{}, BvhStatsConfig{},
                                      BvhUpdateConfig{BvhUpdate::Rebuild});
    rebuild.build(soup.prims());
    EXPECT_FALSE(rebuild.update(soup.prims()));
    BvhAccelerator<WideBvh<4>> refit(builderRecord("sahbvh"), BvhBuildConfig{});
    refit.build(soup.prims());
    EXPECT_THROW(refit.update(fewer.prims()), std::invalid_argument);
}

}  // namespace
}  // namespace bvhlab
