// The leaves' triangle test of the wide layouts: the watertight test of framework/core/
// triangle.h on the eight triangles of a TriangleBlock at once, in lanes of simd::Floats<8>.
// Every lane performs the scalar test's operations in its order (the edge functions filtered
// in float and recomputed in double where their sign is in doubt, as edgeFunction does), so a
// lane's answer is the scalar test's bit for bit: the wide layouts are as watertight as the
// binary one, and agree with it hit for hit.
#pragma once

#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/layout/triangle_blocks.h"
#include "accel/bvh/simd/simd.h"
#include "framework/core/triangle.h"

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// The hits of one block: a lane mask and each lane's t, u, v.
struct BlockHits {
    int mask = 0;
    alignas(32) float t[TriangleBlock::kLanes], u[TriangleBlock::kLanes], v[TriangleBlock::kLanes];
};

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
        orgX = F::broadcast(r.org[kx]), orgY = F::broadcast(r.org[ky]), orgZ = F::broadcast(r.org[kz]);
        sx = F::broadcast(r.sx), sy = F::broadcast(r.sy), sz = F::broadcast(r.sz);
    }

    // The hits at t in [tmin, tmax] among the block's lanes in `lanes` (a mask: the padding
    // lanes of a leaf's last block are left out, and never hit).
    BlockHits intersect(const TriangleBlock& block, int lanes, float tmin, float tmax) const {
        F x[3], y[3], z[3];  // the vertices in the sheared frame (z not yet scaled)
        for (int k = 0; k < 3; ++k) {
            const F ax = F::load(block.vertex[k][kx]) - orgX;
            const F ay = F::load(block.vertex[k][ky]) - orgY;
            z[k] = F::load(block.vertex[k][kz]) - orgZ;
            x[k] = ax - sx * z[k];
            y[k] = ay - sy * z[k];
        }
        // Edge functions as edgeFunction (triangle.h) forms them: fma(a, b, -c*d), its sign
        // certain where it exceeds the error bound; the doubtful lanes (rare) in double.
        const F scale = F::broadcast(kEdgeErrorScale), floor = F::broadcast(kEdgeErrorFloor);
        const auto edge = [&](F a, F b, F c, F d) {
            const F cd = c * d;
            const F e = fmsub(a, b, cd);
            const auto certain = abs(e) > fmadd(abs(cd), scale, floor);
            if ((~movemask(certain) & lanes) == 0) return e;
            return select(certain, e, differenceOfProducts(a, b, c, d));
        };
        const F e0 = edge(x[2], y[1], y[2], x[1]);  // edge v1-v2: weight of v0
        const F e1 = edge(x[0], y[2], y[0], x[2]);  // edge v2-v0: weight of v1
        const F e2 = edge(x[1], y[0], y[1], x[0]);  // edge v0-v1: weight of v2
        const F zero = F::broadcast(0.0f);
        // Lanes with edge functions of both signs miss; so does a zero determinant.
        const int mixedSigns = movemask((e0 < zero) | (e1 < zero) | (e2 < zero)) &
                               movemask((e0 > zero) | (e1 > zero) | (e2 > zero));
        const F det = e0 + e1 + e2;
        BlockHits hits;
        if ((~mixedSigns & lanes) == 0 || movemask(det != zero) == 0) return hits;
        const F invDet = F::broadcast(1.0f) / det;
        const F t = (e0 * (sz * z[0]) + e1 * (sz * z[1]) + e2 * (sz * z[2])) * invDet;
        const auto inRange = (t >= F::broadcast(tmin)) & (t <= F::broadcast(tmax)) & (det != zero);
        hits.mask = movemask(inRange) & ~mixedSigns & lanes;
        if (hits.mask == 0) return hits;
        t.store(hits.t);
        (e1 * invDet).store(hits.u);
        (e2 * invDet).store(hits.v);
        return hits;
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

    BlockHits intersect(const TriangleBlock& block, int lanes, float tmin, float tmax) const {
        const auto cross = [](const F* a, const F* b, F* out) {
            out[0] = a[1] * b[2] - b[1] * a[2];
            out[1] = a[2] * b[0] - b[2] * a[0];
            out[2] = a[0] * b[1] - b[0] * a[1];
        };
        const auto dot = [](const F* a, const F* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
        F v0[3], e1[3], e2[3], s[3];
        for (int a = 0; a < 3; ++a) {
            v0[a] = F::load(block.vertex[0][a]);
            e1[a] = F::load(block.vertex[1][a]) - v0[a];
            e2[a] = F::load(block.vertex[2][a]) - v0[a];
            s[a] = org[a] - v0[a];
        }
        F p[3], q[3];
        cross(dir, e2, p);
        cross(s, e1, q);
        const F det = dot(e1, p);
        const F invDet = F::broadcast(1.0f) / det;
        const F u = dot(s, p) * invDet, v = dot(dir, q) * invDet, t = dot(e2, q) * invDet;
        const F zero = F::broadcast(0.0f), one = F::broadcast(1.0f);
        const int outside = movemask((u < zero) | (u > one) | (v < zero) | (u + v > one));
        const int inRange = movemask((t >= F::broadcast(tmin)) & (t <= F::broadcast(tmax)) & (det != zero));
        BlockHits hits;
        hits.mask = inRange & ~outside & lanes;
        if (hits.mask == 0) return hits;
        t.store(hits.t);
        u.store(hits.u);
        v.store(hits.v);
        return hits;
    }
};

// Tests the `count` triangles of the leaf whose blocks start at `first`; true when the query
// is answered. N_IT counts triangles as the binary layout does: an any-hit query up to the
// one that occludes, padding never. Of equal t in one block the lowest lane (the first in leaf
// order) goes to ClosestHitQuery::record, whose tie rule then holds across blocks and leaves.
template <typename Query, bool Robust>
[[gnu::always_inline]] inline bool testLeafBlocks(Query& query, const BlockTriangleTest<Robust>& test, const TriangleBlock* blocks,
                                                 uint32_t first, uint32_t count, float tmin, uint64_t& tests) {
    constexpr int W = TriangleBlock::kLanes;
    for (uint32_t b = 0, end = blocksFor(count); b < end; ++b) {
        const int lanes = b + 1 < end ? (1 << W) - 1 : (1 << (count - b * W)) - 1;
        const BlockHits hits = test.intersect(blocks[first + b], lanes, tmin, query.tmax);
        if (hits.mask == 0) continue;
        int lane = __builtin_ctz(unsigned(hits.mask));
        if constexpr (Query::kStopsAtFirstHit) {
            tests += uint64_t(b) * W + lane + 1;
            query.record({hits.t[lane], hits.u[lane], hits.v[lane]}, (first + b) * W + lane);
            return true;
        } else {
            for (int m = hits.mask & (hits.mask - 1); m != 0; m &= m - 1) {
                const int i = __builtin_ctz(unsigned(m));
                if (hits.t[i] < hits.t[lane]) lane = i;
            }
            query.record({hits.t[lane], hits.u[lane], hits.v[lane]}, (first + b) * W + lane);
        }
    }
    tests += count;
    return false;
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
