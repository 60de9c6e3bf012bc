// The leaves' triangle test of the wide layouts: the watertight test of framework/core/
// triangle.h on the eight triangles of a TriangleBlock at once, in lanes of simd::Floats<8>.
// Every lane performs the scalar test's operations in its order (the edge functions filtered
// in float and recomputed in double where their sign is in doubt, as edgeFunction does), so a
// lane's answer is the scalar test's bit for bit: the wide layouts are as watertight as the
// binary one, and agree with it hit for hit.
#pragma once

#include <bvhlab/triangle.h>
#include "accel/bvh/layout/triangle_blocks.h"
#include "accel/bvh/layout/wide_bvh.h"
#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/simd/simd.h"

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// The hits of a lane-wise test: a lane mask and each lane's t, u, v (meaningful where the mask
// is set), kept in registers: the leaf tests are inlined into the traversal loops.
template <typename F>
struct LaneHits {
    int mask = 0;
    F t, u, v;
};
// One block's: a lane per triangle.
using BlockHits = LaneHits<simd::Floats<TriangleBlock::kLanes>>;

// The triangle tests on lanes, written once for both uses: a block's eight triangles against one
// ray (BlockTriangleTest), and one triangle against a packet's rays (coherent_traversal.h).
// Every lane performs the scalar test's operations in its order, so both agree with it bit for
// bit. `lanes` are the lanes that count: the others may hold anything.
namespace lane_tests {

// The edge function e = fma(a, b, -c*d) with its doubtful lanes (not `certain`) recomputed in
// double, as edgeFunction does. Rare, so out of line: inlined, its registers weighed on the
// traversal loop around the leaf test, which then saved and restored the ray's vectors at every
// leaf.
template <typename F, typename Mask>
[[gnu::noinline, gnu::cold]] F recomputeDoubtfulLanes(Mask certain, F e, F a, F b, F c, F d) {
    return select(certain, e, differenceOfProducts(a, b, c, d));
}

// edgeFunction (triangle.h) as it forms it: fma(a, b, -c*d), its sign certain where it exceeds
// the error bound; the doubtful lanes (rare) in double.
template <typename F>
[[gnu::always_inline]] inline F edgeFunction(F a, F b, F c, F d, int lanes) {
    const F cd = c * d;
    const F e = fmsub(a, b, cd);
    const auto certain = abs(e) > fmadd(abs(cd), F::broadcast(kEdgeErrorScale), F::broadcast(kEdgeErrorFloor));
    if ((movemask(certain) & lanes) == lanes) [[likely]]
        return e;
    return recomputeDoubtfulLanes(certain, e, a, b, c, d);
}

// The watertight test after the shear: x, y, z are the vertices in the sheared frame (z not
// yet scaled by sz).
template <typename F>
[[gnu::always_inline]] inline LaneHits<F> watertight(const F* x, const F* y, const F* z, F sz, F tmin, F tmax,
                                                     int lanes) {
    const F e0 = edgeFunction(x[2], y[1], y[2], x[1], lanes);  // edge v1-v2: weight of v0
    const F e1 = edgeFunction(x[0], y[2], y[0], x[2], lanes);  // edge v2-v0: weight of v1
    const F e2 = edgeFunction(x[1], y[0], y[1], x[0], lanes);  // edge v0-v1: weight of v2
    const F zero = F::broadcast(0.0f);
    // Lanes with edge functions of both signs miss; so does a zero determinant. The division
    // only where a lane may hit (a lane's quotient does not depend on the others).
    const int mixedSigns =
        movemask((e0 < zero) | (e1 < zero) | (e2 < zero)) & movemask((e0 > zero) | (e1 > zero) | (e2 > zero));
    const F det = e0 + e1 + e2;
    LaneHits<F> hits;
    if ((~mixedSigns & movemask(det != zero) & lanes) == 0) return hits;
    const F invDet = F::broadcast(1.0f) / det;
    hits.t = (e0 * (sz * z[0]) + e1 * (sz * z[1]) + e2 * (sz * z[2])) * invDet;
    const auto inRange = (hits.t >= tmin) & (hits.t <= tmax) & (det != zero);
    hits.mask = movemask(inRange) & ~mixedSigns & lanes;
    hits.u = e1 * invDet;
    hits.v = e2 * invDet;
    return hits;
}

// Moeller-Trumbore with the scalar form's operations and tests (triangle_moller_trumbore.h;
// glm's cross and dot, summed x + y + z); v[k] is vertex k.
template <typename F>
[[gnu::always_inline]] inline LaneHits<F> mollerTrumbore(const F* org, const F* dir, const F (*v)[3], F tmin, F tmax,
                                                         int lanes) {
    const auto cross = [](const F* a, const F* b, F* out) {
        out[0] = a[1] * b[2] - b[1] * a[2];
        out[1] = a[2] * b[0] - b[2] * a[0];
        out[2] = a[0] * b[1] - b[0] * a[1];
    };
    const auto dot = [](const F* a, const F* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    F e1[3], e2[3], s[3];
    for (int a = 0; a < 3; ++a) {
        e1[a] = v[1][a] - v[0][a];
        e2[a] = v[2][a] - v[0][a];
        s[a] = org[a] - v[0][a];
    }
    F p[3], q[3];
    cross(dir, e2, p);
    cross(s, e1, q);
    const F det = dot(e1, p);
    const F invDet = F::broadcast(1.0f) / det;
    const F u = dot(s, p) * invDet, v1 = dot(dir, q) * invDet, t = dot(e2, q) * invDet;
    const F zero = F::broadcast(0.0f), one = F::broadcast(1.0f);
    const int outside = movemask((u < zero) | (u > one) | (v1 < zero) | (u + v1 > one));
    const int inRange = movemask((t >= tmin) & (t <= tmax) & (det != zero));
    return {inRange & ~outside & lanes, t, u, v1};
}

}  // namespace lane_tests

template <bool Robust>
struct BlockTriangleTest {
    using F = simd::Floats<TriangleBlock::kLanes>;
    // The sheared ray in lanes, with its axes resolved once per ray: the vertex rows to load
    // (kx, ky, kz) and the origin's coordinates along them. (Indexing the glm origin by a
    // runtime axis inside the test compiled to two branches per load.)
    int kx, ky, kz;
    F orgX, orgY, orgZ, sx, sy, sz;

    [[gnu::always_inline]] explicit BlockTriangleTest(const Ray& ray) {
        const ShearedRay r(ray);
        kx = r.kx, ky = r.ky, kz = r.kz;
        const float org[3] = {ray.org.x, ray.org.y, ray.org.z};
        orgX = F::broadcast(org[kx]), orgY = F::broadcast(org[ky]), orgZ = F::broadcast(org[kz]);
        sx = F::broadcast(r.sx), sy = F::broadcast(r.sy), sz = F::broadcast(r.sz);
    }

    // The hits at t in [tmin, tmax] among the block's lanes.
    [[gnu::always_inline]] BlockHits intersect(const TriangleBlock& block, float tmin, float tmax) const {
        F x[3], y[3], z[3];  // the vertices in the sheared frame (z not yet scaled)
        for (int k = 0; k < 3; ++k) {
            const F ax = F::load(block.vertex[k][kx]) - orgX;
            const F ay = F::load(block.vertex[k][ky]) - orgY;
            z[k] = F::load(block.vertex[k][kz]) - orgZ;
            x[k] = ax - sx * z[k];
            y[k] = ay - sy * z[k];
        }
        constexpr int kAll = (1 << TriangleBlock::kLanes) - 1;
        return lane_tests::watertight(x, y, z, sz, F::broadcast(tmin), F::broadcast(tmax), kAll);
    }
};

// With robustness off (BVH::robust=false): Moeller-Trumbore, as the binary layout's leaves do
// then (only to measure what the watertight test costs), in lanes with the scalar form's
// operations and tests (triangle_moller_trumbore.h; glm's cross and dot, summed x + y + z).
template <>
struct BlockTriangleTest<false> {
    using F = simd::Floats<TriangleBlock::kLanes>;
    F org[3], dir[3];

    [[gnu::always_inline]] explicit BlockTriangleTest(const Ray& ray) {
        for (int a = 0; a < 3; ++a) org[a] = F::broadcast(ray.org[a]), dir[a] = F::broadcast(ray.dir[a]);
    }

    [[gnu::always_inline]] BlockHits intersect(const TriangleBlock& block, float tmin, float tmax) const {
        F v[3][3];
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) v[k][a] = F::load(block.vertex[k][a]);
        constexpr int kAll = (1 << TriangleBlock::kLanes) - 1;
        return lane_tests::mollerTrumbore(org, dir, v, F::broadcast(tmin), F::broadcast(tmax), kAll);
    }
};

// The lane of a block's closest hit (hits.mask not 0): the least t, the lowest lane of equal
// ones (the first in leaf order), so that ClosestHitQuery::record's tie rule holds across
// blocks and leaves.
[[gnu::always_inline]] inline int closestLane(const BlockHits& hits) {
    int lane = __builtin_ctz(unsigned(hits.mask));
    if ((hits.mask & (hits.mask - 1)) == 0) [[likely]]
        return lane;
    alignas(32) float t[TriangleBlock::kLanes];
    hits.t.store(t);
    for (int m = hits.mask & (hits.mask - 1); m != 0; m &= m - 1) {
        const int i = __builtin_ctz(unsigned(m));
        if (t[i] < t[lane]) lane = i;
    }
    return lane;
}

// Lane `lane` of a block's hits.
[[gnu::always_inline]] inline TriangleHitT<float> hitInLane(const BlockHits& hits, int lane) {
    alignas(32) float t[TriangleBlock::kLanes], u[TriangleBlock::kLanes], v[TriangleBlock::kLanes];
    hits.t.store(t), hits.u.store(u), hits.v.store(v);
    return {t[lane], u[lane], v[lane]};
}

// Tests the leaf `child` (a wide_child word) of `leaves`; true when the query is answered.
// Counting: N_IT counts triangles as the binary layout does, an any-hit query up to the one
// that occludes, padding never.
template <bool Counting, typename Query, bool Robust>
[[gnu::always_inline]] inline bool testLeafBlocks(Query& query, const BlockTriangleTest<Robust>& test,
                                                  const TriangleBlockLeaves& leaves, uint32_t child, float tmin,
                                                  uint64_t& tests) {
    constexpr int W = TriangleBlock::kLanes;
    const uint32_t first = wide_child::firstBlock(child), end = wide_child::blocks(child);
    const TriangleBlock* blocks = leaves.blocks.data() + first;
    for (uint32_t b = 0; b < end; ++b) {
        const BlockHits hits = test.intersect(blocks[b], tmin, query.tmax);
        if (hits.mask == 0) [[likely]]
            continue;
        if constexpr (Query::kStopsAtFirstHit) {
            const int lane = __builtin_ctz(unsigned(hits.mask));
            if constexpr (Counting) tests += uint64_t(b) * W + lane + 1;
            query.record(hitInLane(hits, lane), (first + b) * W + lane);
            return true;
        } else {
            const int lane = closestLane(hits);
            query.record(hitInLane(hits, lane), (first + b) * W + lane);
        }
    }
    if constexpr (Counting) tests += leaves.trianglesIn(first, end);
    return false;
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
