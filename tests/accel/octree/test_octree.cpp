// The octree plugin's parts (accel/octree/): Havran's structure counts on a scene derived by hand,
// the adaptive split's cost on a case worked by hand, the traversals' steps on rays counted by
// hand, both traversals against brute force on random, axis-parallel and in-plane rays, and the
// plugin end to end (found by name, its figures in the JSON). `bvhlab check --accel octree`
// (ctest CheckOctreePlugin, CheckOctreePluginAdaptive93) holds it to the conformance suite.
#include "accel/octree/octree_accelerator.h"
#include "accel/octree/octree_nodes.h"
#include "accel/octree/octree_objects.h"
#include "tests/support/cli_run.h"
#include "tests/support/json_figures.h"
#include "tests/support/scratch_dir.h"

#include <bvhlab/reference_tests.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <random>

namespace bvhlab::test {
namespace {

using octree::OctreeAccelerator;
using octree::OctreeParameters;
using octree::Subdivision;
using octree::Traversal;

std::vector<uint32_t> allOf(size_t count) {
    std::vector<uint32_t> valid(count);
    for (uint32_t i = 0; i < valid.size(); ++i) valid[i] = i;
    return valid;
}

// Three triangles in [0,4]^3: T0 flat in the corner [0,1]^2 at z = 0, T1 flat in [3,4]^2 at
// z = 4, T2 over [1,3]^2 rising from z = 1.5 to 2.5, across the middle of the box. No vertex lies
// on a plane of the octree: the padded root moves the planes off the integers.
const std::vector<Triangle> kThree = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                                      {Vec3(4, 4, 4), Vec3(3, 4, 4), Vec3(4, 3, 4)},
                                      {Vec3(1, 1, 1.5f), Vec3(3, 1, 2.5f), Vec3(1, 3, 2)}};
const std::vector<uint32_t> kThreeValid = allOf(3);

octree::Octree threeTriangles(int maxDepth) {
    return octree::buildOctree(PrimitiveSet{kThree, kThreeValid}, {Subdivision::Centre, maxDepth, 1});
}

TEST(OctreeNodes, HavransCountsOnAScenePlannedByHand) {
    // The root is [0,4]^3 padded by 1e-6 * 4 on every side, its planes through (2,2,2). T2's box
    // [1,3]^2 x [1.5,2.5] is across all three: it is in all eight octants. T0 is in octant 0 only,
    // T1 in octant 7 only. Depth 1 is the limit: 8 leaves, none empty, and 2 + 2 + 6 references.
    const octree::Octree depth1 = threeTriangles(1);
    EXPECT_EQ(depth1.innerNodes(), 1u);
    EXPECT_EQ(depth1.leaves(), 8u);
    EXPECT_EQ(depth1.emptyLeaves(), 0u);
    EXPECT_EQ(depth1.references(), 10u);
    // At depth 2, octants 0 (T0, T2) and 7 (T1, T2) are split; the other six stay leaves of T2.
    // Octant 0 is [-4e-6, 2]^3: its planes lie at 0.999998, just below T0's far edges (x, y = 1)
    // and below T2's near ones, so T0 goes to the four octants below z = 0.999998 and T2 to the
    // one above all three planes: 4 + 1 references, three empty octants. Octant 7 is
    // [2, 4 + 4e-6]^3, planes at 3.000002: T1 (z = 4, x and y across 3..4) to the four above
    // z = 3.000002, T2 (x, y up to 3, z up to 2.5) to the one below all three: again 4 + 1, three
    // empty.
    const octree::Octree depth2 = threeTriangles(2);
    EXPECT_EQ(depth2.innerNodes(), 3u);
    EXPECT_EQ(depth2.leaves(), 22u);  // 6 at depth 1, 16 at depth 2: N_V = 7 N_IN + 1
    EXPECT_EQ(depth2.emptyLeaves(), 6u);
    EXPECT_EQ(depth2.references(), 16u);
    EXPECT_EQ(depth2.deepestLeaf, 2);
    // MO = 3: the root holds three objects and is a leaf.
    const octree::Octree mo3 = octree::buildOctree(PrimitiveSet{kThree, kThreeValid}, {Subdivision::Centre, 7, 3});
    EXPECT_EQ(mo3.innerNodes(), 0u);
    EXPECT_EQ(mo3.leaves(), 1u);
    EXPECT_EQ(mo3.references(), 3u);
}

TEST(OctreeObjects, APolygonsFanIsOneObject) {
    // A square cut as the loader cuts it, (c0, c1, c2) and (c0, c2, c3); then a triangle that
    // continues the fan but leaves its plane; a triangle apart; a sphere.
    const std::vector<Triangle> tris = {{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 2, 0)},
                                        {Vec3(0, 0, 0), Vec3(2, 2, 0), Vec3(0, 2, 0)},
                                        {Vec3(0, 0, 0), Vec3(0, 2, 0), Vec3(0, 1, 3)},
                                        {Vec3(5, 5, 5), Vec3(6, 5, 5), Vec3(5, 6, 5)}};
    const std::vector<Sphere> spheres = {{Vec3(3, 3, 3), 0.5f}};
    const std::vector<uint32_t> valid = allOf(5);
    const PrimitiveSet prims{tris, valid, spheres};
    EXPECT_TRUE(octree::continuesFan(tris[0], tris[1]));
    EXPECT_FALSE(octree::continuesFan(tris[1], tris[2]));
    EXPECT_FALSE(octree::continuesFan(tris[2], tris[3]));
    const octree::OctreeObjects objects = octree::octreeObjects(prims, true);
    EXPECT_EQ(objects.first, (std::vector<uint32_t>{0, 2, 3, 4, 5}));
    EXPECT_EQ(objects.boxes[0].upper, Vec3(2, 2, 0));  // the square's box
    EXPECT_EQ(octree::octreeObjects(prims, false).size(), 5u);
    // A root that is a leaf: four objects referred to (N_OIV), five primitives tested.
    const octree::Octree leaf = octree::buildOctree(prims, {Subdivision::Centre, 0, 1, true});
    EXPECT_EQ(leaf.references(), 4u);
    EXPECT_EQ(leaf.refs.size(), 5u);
}

TEST(OctreeNodes, TheAdaptiveSplitIsTheLeastOfWhangsCost) {
    // A node [0,10] x [0,1] x [0,1] and three boxes of one unit along x at 0, 1, 2: the spatial
    // median is 5, the median of the centres 1.5, the positions 5 - 3.5 i / 9. With b = c = 1,
    // C(t) = (left + cut)(4t + 1) + (right + cut)(4(10 - t) + 1). Positions at 3 or above have all
    // three on the left, C = 3(4t + 1): the least of them is i = 5 (t = 3.056, C = 39.7); below 3
    // the box [2,3] is cut and adds 4(10 - t) + 1 > 29, i = 6 (t = 2.667) gives 65.3. So i = 5.
    std::vector<Bounds3> boxes;
    for (float x : {0.0f, 1.0f, 2.0f}) boxes.push_back({Vec3(x, 0.0f, 0.0f), Vec3(x + 1.0f, 1.0f, 1.0f)});
    const std::vector<uint32_t> objects = allOf(3);
    const DVec3 lo(0.0), hi(10.0, 1.0, 1.0);
    EXPECT_DOUBLE_EQ(octree::adaptiveSplit(boxes, objects, lo, hi, 0), 5.0 - 3.5 * 5.0 / 9.0);
    // No object: the spatial median.
    EXPECT_DOUBLE_EQ(octree::adaptiveSplit(boxes, {}, lo, hi, 0), 5.0);
    EXPECT_EQ(octree::parseSubdivision("adaptive"), Subdivision::Adaptive);
    EXPECT_FALSE(octree::parseSubdivision("center"));
}

struct Counts {
    bool hit = false;
    float t = 0.0f;
    QueryCounters counters;
};

Counts trace(Traversal traversal, int maxDepth, const Ray& ray) {
    OctreeAccelerator accel({Subdivision::Centre, maxDepth, 1}, traversal);
    accel.build(PrimitiveSet{kThree, kThreeValid});
    Counts c;
    Hit hit;
    c.hit = accel.findNearest(ray, hit, c.counters);
    c.t = hit.t;
    return c;
}

TEST(OctreeTraversal, StepsAndTestsOnRaysCountedByHand) {
    // Along x below the middle (y = z = 0.5), at depth 1: octant 0 (T0, T2), then octant 1 (T2);
    // no hit. Glassner's walk descends twice from the root (2 + 2 nodes), the recursive one
    // visits the root and two leaves; both test 3 references.
    const Ray along{Vec3(-1.0f, 0.5f, 0.5f), Vec3(1.0f, 0.0f, 0.0f)};
    for (const auto& [traversal, steps] : {std::pair{Traversal::Octree84, 4u}, std::pair{Traversal::Octree93, 3u}}) {
        const Counts c = trace(traversal, 1, along);
        EXPECT_FALSE(c.hit);
        EXPECT_EQ(c.counters.traversalSteps, steps);
        EXPECT_EQ(c.counters.intersectionTests, 3u);
    }
    // Down through (1.5, 1.5): octant 4 (T2) finds T2 at z = 1.875 (t = 3.125), beyond the
    // octant's exit at z = 2 (t = 3); the walk goes on into octant 0 (T0, T2) before answering it:
    // 3 tests, and 2 + 2 nodes or the root and two leaves.
    const Ray down{Vec3(1.5f, 1.5f, 5.0f), Vec3(0.0f, 0.0f, -1.0f)};
    for (const auto& [traversal, steps] : {std::pair{Traversal::Octree84, 4u}, std::pair{Traversal::Octree93, 3u}}) {
        const Counts c = trace(traversal, 1, down);
        EXPECT_TRUE(c.hit);
        EXPECT_FLOAT_EQ(c.t, 3.125f);
        EXPECT_EQ(c.counters.traversalSteps, steps);
        EXPECT_EQ(c.counters.intersectionTests, 3u);
    }
}

// Both traversals and both subdivisions against brute force (every primitive tested): closest
// hits that agree and the same any-hit answers, on random rays, on rays along the axes lying in
// the root's planes, and on rays from inside with a finite tmax.
TEST(OctreeTraversal, AgreesWithBruteForce) {
    std::mt19937 rng(43);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<Triangle> tris;
    for (int i = 0; i < 400; ++i) {
        const Vec3 c(u(rng), u(rng), u(rng));
        tris.push_back({c, c + 0.2f * Vec3(u(rng), u(rng), u(rng)), c + 0.2f * Vec3(u(rng), u(rng), u(rng))});
    }
    // Triangles whose vertices lie on the planes of centre subdivision (the box is [-1,1]^3).
    tris.push_back({Vec3(0.0f, 0.0f, 0.0f), Vec3(0.5f, 0.0f, 0.0f), Vec3(0.0f, 0.5f, 0.0f)});
    tris.push_back({Vec3(-0.5f, -0.5f, 0.5f), Vec3(0.0f, -0.5f, 0.5f), Vec3(-0.5f, 0.0f, 0.5f)});
    const std::vector<Sphere> spheres = {{Vec3(0.3f, -0.2f, 0.1f), 0.15f}, {Vec3(-0.6f, 0.6f, 0.0f), 0.25f}};
    const std::vector<Cone> cones = {{Vec3(0.5f, 0.5f, -0.5f), 0.1f, Vec3(0.5f, 0.5f, 0.5f), 0.05f}};
    const std::vector<uint32_t> valid = allOf(tris.size() + spheres.size() + cones.size());
    const PrimitiveSet prims{tris, valid, spheres, cones};
    const auto everything = [&](auto&& visit) { visit(View<const uint32_t>(valid), double(kInfinity)); };

    std::vector<Ray> rays;
    for (int i = 0; i < 3000; ++i) {
        const Vec3 o(2.0f * u(rng), 2.0f * u(rng), 2.0f * u(rng));
        rays.push_back({o, math::normalize(Vec3(u(rng), u(rng), u(rng)) + Vec3(1e-3f))});
    }
    for (int i = 0; i < 600; ++i) {
        const int axis = i % 3;
        Vec3 o(u(rng), u(rng), u(rng)), d(0.0f);
        o[(axis + 1) % 3] = (i / 3) % 2 == 0 ? 0.0f : (i / 6) % 2 == 0 ? 0.5f : -0.5f;  // in a plane
        o[axis] = -2.0f;
        d[axis] = 1.0f;
        rays.push_back({(i / 3) % 4 == 3 ? -o : o, (i / 3) % 4 == 3 ? -d : d});
    }
    for (int i = 0; i < 600; ++i)
        rays.push_back(
            {0.9f * Vec3(u(rng), u(rng), u(rng)), math::normalize(Vec3(u(rng), u(rng), u(rng))), 0.0f, 0.5f});

    for (const Subdivision subdivision : {Subdivision::Centre, Subdivision::Adaptive})
        for (const Traversal traversal : {Traversal::Octree84, Traversal::Octree93})
            for (const int depth : {1, 3, 6}) {
                OctreeAccelerator accel({subdivision, depth, 1}, traversal);
                accel.build(prims);
                size_t hits = 0;
                for (const Ray& ray : rays) {
                    QueryCounters counters, reference;
                    Hit ours, brute;
                    const bool found = accel.findNearest(ray, ours, counters);
                    ASSERT_EQ(found, findNearestAlong(prims, ray, reference, everything, brute));
                    ASSERT_TRUE(hitsAgree(ours, brute)) << "t " << ours.t << " against " << brute.t;
                    ASSERT_EQ(accel.isOccluded(ray, counters), isOccludedAlong(prims, ray, reference, everything));
                    hits += found;
                }
                EXPECT_GT(hits, rays.size() / 10);
            }
}

TEST(OctreeNodes, ABudgetBoundsTheReferencesOfHugeOverlappingTriangles) {
    std::vector<Triangle> tris;
    for (int i = 0; i < 20000; ++i) {
        const float z = float(i) / 20000.0f;
        tris.push_back({Vec3(-1.0f, -1.0f, z), Vec3(1.0f, -1.0f, 1.0f - z), Vec3(0.0f, 1.0f, z)});
    }
    const std::vector<uint32_t> valid = allOf(tris.size());
    const octree::Octree tree = octree::buildOctree(PrimitiveSet{tris, valid}, {Subdivision::Centre, 7, 1});
    EXPECT_TRUE(tree.budgetReached);
    EXPECT_LE(tree.references(), std::max<uint64_t>(octree::kMinReferenceBudget, 32 * tris.size()));
}

TEST(OctreePlugin, FoundByNameItsFiguresInTheJson) {
    const auto out = scratchDir("octree_plugin") / "image";
    const Result r =
        run("render -DCamera::width=16 -DCamera::height=12 -DASDS::type=octree -DOctree::maxDepth=4 "
            "--out " +
            out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("octree N_OIV:"), std::string::npos) << r.output;
    std::ifstream in(out.string() + ".json");
    const nlohmann::json json = nlohmann::json::parse(in);
    const std::vector<nlohmann::json> found = figuresWith(json, "N_IN");
    ASSERT_FALSE(found.empty()) << json.dump();
    const nlohmann::json& f = found.front();
    for (const char* name : {"N_IN", "N_V", "N_EV", "N_OIV"}) EXPECT_TRUE(f.contains(name)) << name;
    EXPECT_EQ(f["N_V"]["value"].get<double>(), 7.0 * f["N_IN"]["value"].get<double>() + 1.0);
    EXPECT_LE(f["N_EV"]["value"].get<double>(), f["N_V"]["value"].get<double>());
}

TEST(OctreePlugin, AnUnknownTraversalIsRefused) {
    const Result r =
        run("render -DCamera::width=8 -DCamera::height=8 -DASDS::type=octree -DOctree::traversal=octree89 "
            "--out " +
            (scratchDir("octree_plugin") / "bad").string());
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("Octree::traversal"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace bvhlab::test
