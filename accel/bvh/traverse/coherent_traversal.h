// The node and leaf steps of the coherent packets (BVH::batchTraversal=coherent), after Embree 3's
// coherent hybrid traversal (bvh_intersector_hybrid.cpp, intersectCoherent): tracePacket
// (packet_traversal.h) with these two steps in place of its plain ones.
//
// Node: one N-lane test of the node's children against a frustum that bounds every ray of the
// packet (PacketFrustum), then the exact K-lane test of each ray (PacketBoxTest) only on the
// children the frustum keeps. The frustum keeps every child that one of its rays hits, so the
// rays' masks are those of the plain packets.
//
// Leaf: one triangle against all active rays at once (PacketTriangleTest), where the plain packets
// test the leaf ray by ray, eight triangles at a time. Each lane performs the single-ray block
// test's operations in its order (triangle_block_test.h, lane_tests), so a ray's hits are its
// single-ray hits bit for bit; taking a leaf's triangles one by one in leaf order keeps
// ClosestHitQuery's tie rule (least t, the first in leaf order) and an any-hit ray's count of
// triangles tested up to the one that occludes.
#pragma once

#include "accel/bvh/layout/wide_bvh.h"
#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/simd/simd.h"
#include "accel/bvh/traverse/triangle_block_test.h"

#include <bit>
#include <cmath>

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// The packet's bounds per axis: its origins' and its 1/dir's least and greatest values, and its
// interval [least tmin, greatest tmax]. Every ray's slab distance on an axis is
// fl(fl(bound - org) * inv); rounding is monotonic, so the same formula on the bounds' extreme
// corners gives a near distance no greater, and a far distance no smaller, than every ray's. A
// child the frustum misses is thus missed by every ray of the packet. That needs 1/dir finite and
// not 0 and the origins finite (no NaN slab distance, which the ray's test would drop): a packet
// without them tests every child exactly (`usable` false).
template <int N>
struct PacketFrustum {
    using F = simd::Floats<N>;
    bool usable = true;
    // Per axis: the origin that makes the near (far) difference least (greatest): the greatest
    // origin where 1/dir > 0.
    float orgNear[3], orgFar[3];
    float invLeast[3], invGreatest[3], invFarLeast[3], invFarGreatest[3];
    float tmin = kInfinity;
    int nearOffset[3], farOffset[3];  // as PacketBoxTest's

    template <int K>
    PacketFrustum(const float (&org)[3][K], const float (&inv)[3][K], const float (&invFar)[3][K],
                  const float (&tmins)[K], int count, const int* nearOffsets, const int* farOffsets) {
        for (int a = 0; a < 3; ++a) {
            nearOffset[a] = nearOffsets[a], farOffset[a] = farOffsets[a];
            float orgLeast = org[a][0], orgGreatest = org[a][0];
            invLeast[a] = invGreatest[a] = inv[a][0];
            invFarLeast[a] = invFarGreatest[a] = invFar[a][0];
            for (int k = 0; k < count; ++k) {  // simd::min and max: minss, maxss, no libm call
                usable = usable && std::isfinite(org[a][k]) && std::isfinite(invFar[a][k]) && inv[a][k] != 0.0f;
                orgLeast = simd::min(orgLeast, org[a][k]), orgGreatest = simd::max(orgGreatest, org[a][k]);
                invLeast[a] = simd::min(invLeast[a], inv[a][k]), invGreatest[a] = simd::max(invGreatest[a], inv[a][k]);
                invFarLeast[a] = simd::min(invFarLeast[a], invFar[a][k]);
                invFarGreatest[a] = simd::max(invFarGreatest[a], invFar[a][k]);
            }
            const bool positive = inv[a][0] > 0.0f;  // one octant: one sign per axis
            orgNear[a] = positive ? orgGreatest : orgLeast;
            orgFar[a] = positive ? orgLeast : orgGreatest;
        }
        for (int k = 0; k < count; ++k) tmin = simd::min(tmin, tmins[k]);
    }

    // The children (a lane mask) that some ray of the packet with tmax <= `tmax` may hit; all
    // non-empty ones when the frustum is not usable. d * inv over inv in [least, greatest] is
    // least at `least` where d >= 0, at `greatest` where d < 0 (greatest the other way round).
    [[gnu::always_inline]] int intersect(const WideNode<N>& node, float tmax) const {
        const float* bounds = &node.lower[0][0];
        if (!usable) [[unlikely]]
            return movemask(F::load(node.lower[0]) <= F::load(node.upper[0]));
        const F zero = F::broadcast(0.0f);
        F nearT[3], farT[3];
        for (int a = 0; a < 3; ++a) {
            const F dNear = F::load(bounds + nearOffset[a]) - F::broadcast(orgNear[a]);
            nearT[a] = dNear * select(dNear >= zero, F::broadcast(invLeast[a]), F::broadcast(invGreatest[a]));
            const F dFar = F::load(bounds + farOffset[a]) - F::broadcast(orgFar[a]);
            farT[a] = dFar * select(dFar >= zero, F::broadcast(invFarGreatest[a]), F::broadcast(invFarLeast[a]));
        }
        const F entry = max(max(nearT[0], nearT[1]), max(nearT[2], F::broadcast(tmin)));
        const F exit = min(min(farT[0], farT[1]), min(farT[2], F::broadcast(tmax)));
        return ~movemask(entry > exit) & ((1 << N) - 1);  // empty lanes: entry +inf, exit -inf
    }
};

// One triangle against up to K rays, one lane per ray: the watertight test (Robust) on each
// ray's sheared frame, or Moeller-Trumbore. The sheared frame's axes (kx, ky, kz) differ between
// rays whose dominant axis differs; within one octant kz fixes kx and ky, so the rays fall into
// at most three groups that each load the triangle's coordinates along the same axes.
template <int K, bool Robust>
struct PacketTriangleTest {
    using F = simd::Floats<K>;
    static constexpr int kGroups = 3;
    // Per lane, ShearedRay's values: the origin along kx, ky, kz and sx, sy, sz.
    alignas(64) float org[3][K];
    alignas(64) float shear[3][K];
    int groupLanes[kGroups] = {};  // the lanes of each kz
    int axes[kGroups][3] = {};     // kx, ky, kz of each group

    // Lanes past `count` repeat ray 0 (never active).
    PacketTriangleTest(const Ray* rays, int count) {
        for (int k = 0; k < K; ++k) {
            const Ray& ray = rays[k < count ? k : 0];
            const ShearedRay r(ray);
            const float o[3] = {ray.org.x, ray.org.y, ray.org.z};
            org[0][k] = o[r.kx], org[1][k] = o[r.ky], org[2][k] = o[r.kz];
            shear[0][k] = r.sx, shear[1][k] = r.sy, shear[2][k] = r.sz;
            if (k < count) groupLanes[r.kz] |= 1 << k, axes[r.kz][0] = r.kx, axes[r.kz][1] = r.ky, axes[r.kz][2] = r.kz;
        }
    }

    // How many groups the rays in `lanes` fall into: the tests a triangle takes.
    [[gnu::always_inline]] int groupsOf(int lanes) const {
        return int((groupLanes[0] & lanes) != 0) + int((groupLanes[1] & lanes) != 0) +
               int((groupLanes[2] & lanes) != 0);
    }

    // The hits of the triangle in lane `lane` of `block` among `lanes` of group `group`, at t in
    // each lane's [tmin, tmax].
    [[gnu::always_inline]] LaneHits<F> intersect(const TriangleBlock& block, int lane, int group, F tmin, F tmax,
                                                 int lanes) const {
        const int kx = axes[group][0], ky = axes[group][1], kz = axes[group][2];
        const F orgX = F::load(org[0]), orgY = F::load(org[1]), orgZ = F::load(org[2]);
        const F sx = F::load(shear[0]), sy = F::load(shear[1]);
        F x[3], y[3], z[3];  // the vertices in the sheared frame (z not yet scaled)
        for (int v = 0; v < 3; ++v) {
            const F ax = F::broadcast(block.vertex[v][kx][lane]) - orgX;
            const F ay = F::broadcast(block.vertex[v][ky][lane]) - orgY;
            z[v] = F::broadcast(block.vertex[v][kz][lane]) - orgZ;
            x[v] = ax - sx * z[v];
            y[v] = ay - sy * z[v];
        }
        return lane_tests::watertight(x, y, z, F::load(shear[2]), tmin, tmax, lanes);
    }
};

template <int K>
struct PacketTriangleTest<K, false> {
    using F = simd::Floats<K>;
    static constexpr int kGroups = 1;
    alignas(64) float org[3][K];
    alignas(64) float dir[3][K];
    int groupLanes[kGroups];

    PacketTriangleTest(const Ray* rays, int count) : groupLanes{int((1u << count) - 1)} {
        for (int k = 0; k < K; ++k)
            for (int a = 0; a < 3; ++a)
                org[a][k] = rays[k < count ? k : 0].org[a], dir[a][k] = rays[k < count ? k : 0].dir[a];
    }

    static int groupsOf(int) { return 1; }

    [[gnu::always_inline]] LaneHits<F> intersect(const TriangleBlock& block, int lane, int, F tmin, F tmax,
                                                 int lanes) const {
        F o[3], d[3], v[3][3];
        for (int a = 0; a < 3; ++a) {
            o[a] = F::load(org[a]), d[a] = F::load(dir[a]);
            for (int k = 0; k < 3; ++k) v[k][a] = F::broadcast(block.vertex[k][a][lane]);
        }
        return lane_tests::mollerTrumbore(o, d, v, tmin, tmax, lanes);
    }
};

// How many of the leaf `child`'s lanes (a wide_child word) the packet's test takes, in leaf order:
// all but the run of repeats that ends its last block. Its padding lanes repeat its last triangle;
// leaving a repeat out changes no answer (it hits exactly where the lane before it does, later in
// leaf order), and counting this way reads the blocks the test reads anyway, not primIndices.
[[gnu::always_inline]] inline uint32_t lanesToTest(const TriangleBlockLeaves& leaves, uint32_t child) {
    constexpr int W = TriangleBlock::kLanes;
    const uint32_t blocks = wide_child::blocks(child);
    const TriangleBlock& last = leaves.blocks[wide_child::firstBlock(child) + blocks - 1];
    const auto repeats = [&](int lane) {  // lane holds the triangle of lane - 1, bit for bit
        for (int v = 0; v < 3; ++v)
            for (int a = 0; a < 3; ++a)
                if (std::bit_cast<uint32_t>(last.vertex[v][a][lane]) !=
                    std::bit_cast<uint32_t>(last.vertex[v][a][lane - 1]))
                    return false;
        return true;
    };
    int lanes = W;
    while (lanes > 1 && repeats(lanes - 1)) --lanes;
    return (blocks - 1) * W + uint32_t(lanes);
}

// Tests the first `lanes` lanes (lanesToTest) of the leaf `child` (a wide_child word) against
// the rays in `active`: each triangle against
// all of them, in leaf order. queries[k] and tmax[k] follow each ray's hits; an any-hit ray
// stops at the triangle that occludes it. Counting: N_IT per ray as testLeafBlocks counts it.
// Returns whether any ray hit.
template <bool Counting, typename Query, bool Robust, int K>
[[gnu::always_inline]] inline bool testLeafPacket(Query* queries, float* tmax, const float* tmin,
                                                  const PacketTriangleTest<K, Robust>& test,
                                                  const TriangleBlockLeaves& leaves, uint32_t child,
                                                  uint32_t lanesTested, int active, uint64_t* tests) {
    using F = simd::Floats<K>;
    constexpr int W = TriangleBlock::kLanes;
    const uint32_t first = wide_child::firstBlock(child);
    const TriangleBlock* block = leaves.blocks.data() + first;
    const F tmins = F::load(tmin);
    alignas(64) float t[K], u[K], v[K];
    bool hit = false;
    for (int group = 0; group < test.kGroups; ++group) {
        int lanes = test.groupLanes[group] & active;
        if (lanes == 0) continue;
        F tmaxes = F::load(tmax);
        for (uint32_t i = 0; i < lanesTested; ++i) {
            const LaneHits<F> hits = test.intersect(block[i / W], int(i % W), group, tmins, tmaxes, lanes);
            if (hits.mask == 0) [[likely]]
                continue;
            hit = true;
            hits.t.store(t), hits.u.store(u), hits.v.store(v);
            for (int m = hits.mask; m != 0; m &= m - 1) {
                const int k = std::countr_zero(unsigned(m));
                queries[k].record({t[k], u[k], v[k]}, first * W + i);
                tmax[k] = queries[k].tmax;
                if constexpr (Query::kStopsAtFirstHit) {
                    if constexpr (Counting) tests[k] += i + 1;
                    lanes &= ~(1 << k);
                }
            }
            if constexpr (Query::kStopsAtFirstHit) {
                if (lanes == 0) break;
            } else {
                tmaxes = F::load(tmax);
            }
        }
        if constexpr (Counting) {
            const uint32_t triangles = leaves.trianglesIn(first, wide_child::blocks(child));
            for (int m = lanes; m != 0; m &= m - 1) tests[std::countr_zero(unsigned(m))] += triangles;
        }
    }
    return hit;
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
