#include "tests/support/bvh_checks.h"

#include "accel/naive/naive_accelerator.h"
#include "framework/core/timed_build.h"
#include "framework/scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

namespace bvhlab::test {

void addLatticeSquares(Soup& soup, int planes, int cells) {
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int i = 0; i <= planes; ++i)
            for (int j = 0; j < cells; ++j)
                for (int k = 0; k < cells; ++k) {
                    Vec3 p0(0.0f), p1(0.0f), p2(0.0f), p3(0.0f);
                    p0[axis] = p1[axis] = p2[axis] = p3[axis] = float(i);
                    p0[u] = p3[u] = float(j), p1[u] = p2[u] = float(j + 1);
                    p0[v] = p1[v] = float(k), p2[v] = p3[v] = float(k + 1);
                    soup.add({p0, p1, p2});
                    soup.add({p0, p2, p3});
                }
    }
}

std::vector<Ray> axisRaysThroughLattice(int planes) {
    std::vector<Ray> rays;
    const float last = float(planes);
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (float a : {0.0f, 0.5f, 1.0f, last})
            for (float b : {0.0f, 0.25f, 2.0f, last})
                for (float sign : {1.0f, -1.0f}) {
                    Ray ray;
                    ray.org[axis] = sign > 0 ? -1.0f : last + 2.0f;
                    ray.org[u] = a, ray.org[v] = b;
                    ray.dir = Vec3(sign < 0 ? -0.0f : 0.0f);
                    ray.dir[axis] = sign;
                    rays.push_back(ray);
                }
    }
    return rays;
}

Soup randomSoup(size_t n, uint32_t seed, float extent, float size) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(0.0f, extent), offset(-size, size);
    Soup soup;
    while (soup.triangles.size() < n) {
        const Vec3 p(pos(rng), pos(rng), pos(rng));
        const Triangle t{p, p + Vec3(offset(rng), offset(rng), offset(rng)),
                         p + Vec3(offset(rng), offset(rng), offset(rng))};
        if (!isDegenerate(t)) soup.add(t);
    }
    return soup;
}

Soup mixedScaleSoup(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-500.0f, 500.0f), unit(-1.0f, 1.0f), exponent(-6.0f, 3.0f);
    Soup soup;
    while (soup.triangles.size() < n) {
        const float size = std::pow(10.0f, exponent(rng));
        const Vec3 p(pos(rng), pos(rng), pos(rng));
        const Triangle t{p, p + size * Vec3(unit(rng), unit(rng), unit(rng)),
                         p + size * Vec3(unit(rng), unit(rng), unit(rng))};
        if (!isDegenerate(t)) soup.add(t);
    }
    return soup;
}

Soup triangleAndCopy(Vec3 shift) {
    const Triangle unit{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    Soup soup;
    soup.add(unit);
    soup.add({unit.v0 + shift, unit.v1 + shift, unit.v2 + shift});
    return soup;
}

std::vector<BuilderRecord> allBuilders() {
    return {builderRecord("tdbvh"), builderRecord("sahbvh"), builderRecord("sweepbvh"), builderRecord("ploc")};
}

namespace {

bool contains(const Bounds3& outer, const Bounds3& inner) {
    return outer.lower.x <= inner.lower.x && outer.lower.y <= inner.lower.y && outer.lower.z <= inner.lower.z &&
           outer.upper.x >= inner.upper.x && outer.upper.y >= inner.upper.y && outer.upper.z >= inner.upper.z;
}

bool sameBox(const Bounds3& a, const Bounds3& b) { return a.lower == b.lower && a.upper == b.upper; }

Ray randomRay(std::mt19937& rng, float extent) {
    std::uniform_real_distribution<float> pos(-0.2f * extent, 1.2f * extent), dir(-1.0f, 1.0f);
    Ray ray;
    ray.org = {pos(rng), pos(rng), pos(rng)};
    const Vec3 target(pos(rng), pos(rng), pos(rng));
    ray.dir = target - ray.org;
    // Every seventh ray runs along an axis, from a triangle's vertex coordinate: slab planes.
    if (rng() % 7 == 0) ray.dir = Vec3(0.0f), ray.dir[rng() % 3] = (rng() & 1) ? 1.0f : -1.0f;
    return ray;
}

}  // namespace

TreeFacts checkTree(const BinaryBvh& bvh, const Soup& soup) {
    TreeFacts facts;
    const size_t n = soup.valid.size();
    EXPECT_EQ(bvh.primIndices.size(), n);
    EXPECT_EQ(bvh.leafTriangles.size(), n);
    if (n == 0) {
        EXPECT_TRUE(bvh.empty());
        return facts;
    }
    EXPECT_EQ(reinterpret_cast<uintptr_t>(bvh.nodes.data()) % 64, 0u) << "sibling pairs must share a cache line";

    std::multiset<uint32_t> seen(bvh.primIndices.begin(), bvh.primIndices.end());
    EXPECT_EQ(seen, std::multiset<uint32_t>(soup.valid.begin(), soup.valid.end()));
    for (size_t i = 0; i < n; ++i) {
        const Triangle& a = bvh.leafTriangles[i];
        const Triangle& b = soup.triangles[bvh.primIndices[i]];
        EXPECT_TRUE(a.v0 == b.v0 && a.v1 == b.v1 && a.v2 == b.v2) << "leaf triangle " << i;
    }

    std::vector<int> covered(n, 0);
    struct Item {
        uint32_t node;
        int depth;
    };
    std::vector<Item> stack{{0, 0}};
    while (!stack.empty()) {
        const auto [index, depth] = stack.back();
        stack.pop_back();
        if (index >= bvh.nodes.size()) {
            ADD_FAILURE() << "node index " << index << " out of range";
            continue;
        }
        const BvhNode& node = bvh.nodes[index];
        ++facts.nodes;
        facts.maxDepth = std::max(facts.maxDepth, depth);
        const Bounds3 box = node.box();
        if (node.isLeaf()) {
            ++facts.leaves;
            facts.maxLeaf = std::max<size_t>(facts.maxLeaf, node.count);
            EXPECT_LE(size_t(node.index) + node.count, n);
            Bounds3 tight;
            for (uint32_t i = node.index; i < node.index + node.count && i < n; ++i) {
                ++covered[i];
                tight.extend(bvh.leafTriangles[i].bounds());
            }
            EXPECT_TRUE(sameBox(box, tight)) << "leaf " << index << " box is not its triangles' box";
        } else {
            EXPECT_TRUE(node.index >= 2 && node.index % 2 == 0) << "children of " << index << " at " << node.index;
            if (node.index + 1 >= bvh.nodes.size()) {
                ADD_FAILURE() << "children of " << index << " out of range";
                continue;
            }
            const Bounds3 left = bvh.nodes[node.index].box(), right = bvh.nodes[node.index + 1].box();
            EXPECT_TRUE(contains(box, left) && contains(box, right)) << "children outside node " << index;
            EXPECT_TRUE(sameBox(box, unionOf(left, right))) << "node " << index << " box is not its children's";
            stack.push_back({node.index, depth + 1});
            stack.push_back({node.index + 1, depth + 1});
        }
    }
    for (size_t i = 0; i < n; ++i)
        EXPECT_EQ(covered[i], 1) << "leaf slot " << i << " covered " << covered[i] << " times";
    EXPECT_EQ(facts.nodes, 2 * facts.leaves - 1);
    EXPECT_LT(facts.maxDepth, kBvhMaxDepth);
    return facts;
}

TreeFacts buildAndCheck(BvhAccelerator<BinaryBvh>& accel, const Soup& soup) {
    const BuildStats stats = timedBuild(accel, soup.prims());
    const TreeFacts facts = checkTree(accel.bvh(), soup);
    EXPECT_EQ(stats.primitives, soup.valid.size());
    EXPECT_EQ(stats.nodes.value_or(0), facts.nodes);
    EXPECT_EQ(stats.leaves.value_or(0), facts.leaves);
    EXPECT_EQ(stats.maxLeafPrimitives.value_or(0), facts.maxLeaf);
    EXPECT_EQ(stats.maxDepth.value_or(-1), facts.maxDepth);
    EXPECT_EQ(stats.bytes.value_or(0), accel.bvh().bytes());
    EXPECT_TRUE(stats.sah.has_value());
    return facts;
}

double sahOf(const BinaryBvh& bvh) {
    BuildStats stats;
    fillTreeStats(bvh, 1.0, 1.0, stats);
    return stats.sah->cost;
}

void expectAgreesWithNaive(const Accelerator& accel, const Soup& soup, int count, float extent, uint32_t seed) {
    NaiveAccelerator naive;
    naive.build(soup.prims());
    std::mt19937 rng(seed);
    int mismatches = 0;
    for (int i = 0; i < count && mismatches < 5; ++i) {
        Ray ray = randomRay(rng, extent);
        if (!soup.triangles.empty() && i % 3 == 0) {
            // Aim at a vertex-derived point on a triangle: many rays hit something.
            const Triangle& t = soup.triangles[soup.valid[rng() % soup.valid.size()]];
            ray.dir = (t.v0 + t.v1 + t.v2) * (1.0f / 3.0f) - ray.org;
        }
        if (i % 5 == 0) ray.tmax = std::uniform_real_distribution<float>(0.1f, 1.5f)(rng);
        // Intervals reaching behind the origin: far slab distances are then negative too.
        if (i % 4 == 1) ray.tmin = -std::uniform_real_distribution<float>(0.0f, 2.0f)(rng);
        Hit expected, actual;
        QueryCounters c1, c2;
        const bool e = naive.findNearest(ray, expected, c1);
        const bool a = accel.findNearest(ray, actual, c2);
        if (e != a || !hitsAgree(expected, actual)) {
            ++mismatches;
            ADD_FAILURE() << accel.name() << " ray " << i << ": naive t=" << expected.t << " prim "
                          << expected.primitive << ", bvh t=" << actual.t << " prim " << actual.primitive;
        }
        if (naive.isOccluded(ray, c1) != accel.isOccluded(ray, c2)) {
            ++mismatches;
            ADD_FAILURE() << accel.name() << " ray " << i << ": occlusion differs";
        }
        EXPECT_EQ(c2.queries, 2u);
    }
}

}  // namespace bvhlab::test
