// What the traversal skeletons of every layout share: the two queries (closest hit, any hit),
// the leaves' triangle test, and the entry that picks the skeleton's variant for a ray. Each
// layout has one skeleton, `traverse<Counting, Query, NegativeT, Robust, Step>(tree, ray,
// counters)` (binary_bvh_traversal.h, wide_bvh_traversal.h; Step: BVH::singleStep, which only
// the wide one reads), with a fixed-size stack and no allocation.
//
// What the counters count (QueryCounters, Havran's terms):
//   N_TR (traversalSteps): nodes visited. The root is visited by every valid query; any other
//     node is visited when the ray enters its box before the current closest hit. A node
//     pushed on the stack and dropped because a closer hit was found meanwhile is not counted. A binary tree's inner
//     visit tests two boxes, so its box tests = 1 + 2 * (inner nodes visited); a wide tree's steps are wide nodes and
//     leaves, not comparable with a binary tree's.
//   N_IT (intersectionTests): ray-primitive tests, i.e. the sizes of the leaves visited (an
//     any-hit query stops counting at the primitive that occludes); spheres and cones are
//     also counted apart (sphereTests, coneTests).
//   queries: +1 per call, valid ray or not.
//
// The skeletons' per-node and per-leaf helpers (box tests, leaf tests, child ordering, ray
// setup) are [[gnu::always_inline]]: GCC's inliner drops them once their translation unit grows
// past its budget, and a call per node cost 7-15 % per trace (measured when the quadric tree
// joined bvh_accelerator.cpp; the trees and the work counted were the same).
#pragma once

#include <bvhlab/triangle.h>
#include "accel/bvh/layout/leaf_arrays.h"
#include "accel/bvh/layout/quadric_leaves.h"
#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/traverse/traversal_config.h"
#include "framework/core/accelerator.h"
#include "framework/core/triangle_moller_trumbore.h"

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// The leaves' triangle test: the shared watertight one, or Moeller-Trumbore when robustness
// is switched off (BVH::robust=false).
template <bool Robust>
struct LeafTriangleTest {
    ShearedRay sheared;
    [[gnu::always_inline]] explicit LeafTriangleTest(const Ray& ray) : sheared(ray) {}
    bool operator()(const Triangle& tri, float tmin, float tmax, TriangleHitT<float>& h) const {
        return intersectTriangle(sheared, tri, tmin, tmax, h);
    }
};
template <>
struct LeafTriangleTest<false> {
    const Ray& ray;
    explicit LeafTriangleTest(const Ray& ray) : ray(ray) {}
    bool operator()(const Triangle& tri, float tmin, float tmax, TriangleHitT<float>& h) const {
        return intersectTriangleMollerTrumbore(ray, tri, tmin, tmax, h);
    }
};

// Closest hit in [ray.tmin, ray.tmax]: every hit shortens the interval, and the skeleton
// skips nodes the ray enters behind it. Of hits at equal t the one first in leaf order wins,
// whatever order they are found in (the leaf tests pass hits at t <= tmax): the single-ray
// skeletons and the packets (packet_traversal.h) visit leaves in different orders and must
// give the same answer bit for bit, e.g. on coplanar duplicate triangles. (Unless the tied
// leaf's box entry rounds above t and culls it: docs/architecture.md, Packets.)
struct ClosestHitQuery {
    static constexpr bool kStopsAtFirstHit = false;
    float tmax;
    uint32_t found = kInvalidPrimitive;  // position in leaf order of the closest hit so far
    TriangleHitT<float> best{};

    explicit ClosestHitQuery(const Ray& ray) : tmax(ray.tmax) {}
    void record(const TriangleHitT<float>& h, uint32_t position) {
        if (h.t < tmax || position < found) tmax = h.t, best = h, found = position;
    }
};

// Any hit in [ray.tmin, ray.tmax], stopping at the first one found.
struct AnyHitQuery {
    static constexpr bool kStopsAtFirstHit = true;
    float tmax;
    bool occluded = false;

    explicit AnyHitQuery(const Ray& ray) : tmax(ray.tmax) {}
    void record(const TriangleHitT<float>&, uint32_t) { occluded = true; }
};

// Adds a skeleton's tallies to the counters; without Counting they are dead code, and the
// compiler drops them.
template <bool Counting>
[[gnu::always_inline]] inline void addWork(QueryCounters& counters, uint64_t steps, uint64_t tests) {
    if constexpr (Counting) {
        counters.traversalSteps += steps;
        counters.intersectionTests += tests;
    }
}

// Tests the triangles [first, first + count) of leaf order; true when the query is answered.
template <typename Query, bool Robust>
[[gnu::always_inline]] inline bool testLeaf(Query& query, const LeafTriangleTest<Robust>& test,
                                            const Triangle* triangles, uint32_t first, uint32_t count, float tmin,
                                            uint64_t& tests) {
    for (uint32_t i = first, end = first + count; i < end; ++i) {
        ++tests;
        TriangleHitT<float> h;
        if (test(triangles[i], tmin, query.tmax, h)) {
            query.record(h, i);
            if constexpr (Query::kStopsAtFirstHit) return true;
        }
    }
    return false;
}

// How the leaves of a binary tree are tested (binary_bvh_traversal.h): its triangles, or its quadrics.
template <typename Leaves, bool Robust>
struct LeafTester;

template <bool Robust>
struct LeafTester<LeafArrays, Robust> {
    LeafTriangleTest<Robust> test;
    const Triangle* triangles;

    LeafTester(const LeafArrays& leaves, const Ray& ray, QueryCounters&)
        : test(ray), triangles(leaves.leafTriangles.data()) {}
    const void* address(uint32_t first) const { return triangles + first; }
    template <typename Query>
    bool operator()(Query& query, uint32_t first, uint32_t count, float tmin, uint64_t& tests) const {
        return testLeaf(query, test, triangles, first, count, tmin, tests);
    }
};

// Spheres and cones: one test each, counted by kind straight into the counters.
template <bool Robust>
struct LeafTester<QuadricLeaves, Robust> {
    const Ray& ray;
    const QuadricShape* shapes;
    QueryCounters& counters;

    LeafTester(const QuadricLeaves& leaves, const Ray& ray, QueryCounters& counters)
        : ray(ray), shapes(leaves.leafShapes.data()), counters(counters) {}
    const void* address(uint32_t first) const { return shapes + first; }
    template <typename Query>
    bool operator()(Query& query, uint32_t first, uint32_t count, float tmin, uint64_t&) const {
        for (uint32_t i = first, end = first + count; i < end; ++i) {
            counters.countQuadricTest(shapes[i]);
            QuadricHitT<float> h;
            if (intersectQuadric(ray, shapes[i], tmin, query.tmax, h)) {
                query.record({h.t, 0.0f, 0.0f}, i);
                if constexpr (Query::kStopsAtFirstHit) return true;
            }
        }
        return false;
    }
};

// The entry of every query for a fixed robustness setting (a batch fixes it once): it counts
// (Counting: the query's work too), answers invalid rays and empty trees with a miss, and runs
// the skeleton variant the ray needs: NegativeT when the interval reaches below t = 0 (the box
// test's far margin must then be sign-aware).
template <typename Query, bool Robust, bool Counting, SingleStep Step = SingleStep::Offsets, typename Tree>
[[gnu::always_inline]] inline Query runQuery(const Tree& tree, const Ray& ray, QueryCounters& counters) {
    ++counters.queries;
    if (tree.empty() || !ray.isValid()) return Query(ray);
    return ray.tmin < 0.0f ? traverse<Counting, Query, true, Robust, Step>(tree, ray, counters)
                           : traverse<Counting, Query, false, Robust, Step>(tree, ray, counters);
}

// Robust per BVH::robust, counting.
template <typename Query, typename Tree>
Query runQuery(const Tree& tree, const Ray& ray, const TraversalConfig& config, QueryCounters& counters) {
    return config.robust ? runQuery<Query, true, true>(tree, ray, counters)
                         : runQuery<Query, false, true>(tree, ray, counters);
}

// The answer of a closest-hit query, in the primitives' index space; false on a miss (`hit`
// unchanged).
template <typename Tree>
[[gnu::always_inline]] inline bool answerOf(const Tree& tree, const ClosestHitQuery& query, Hit& hit) {
    if (query.found == kInvalidPrimitive) return false;
    hit = {query.best.t, tree.primIndices[query.found], query.best.u, query.best.v};
    return true;
}

// Closest hit; on a miss returns false and leaves `hit` unchanged.
template <typename Tree>
bool findNearest(const Tree& tree, const Ray& ray, Hit& hit, QueryCounters& counters, const TraversalConfig& config) {
    return answerOf(tree, runQuery<ClosestHitQuery>(tree, ray, config, counters), hit);
}

template <typename Tree>
bool isOccluded(const Tree& tree, const Ray& ray, QueryCounters& counters, const TraversalConfig& config) {
    return runQuery<AnyHitQuery>(tree, ray, config, counters).occluded;
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
