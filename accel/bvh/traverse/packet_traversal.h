// Packets of coherent rays over the N-wide layout (Benthin, Wald, Woop, Ernst and Mark 2012,
// "Combining single and packet-ray tracing for arbitrary ray distributions on the Intel MIC
// architecture"): up to kPacketWidth rays of one direction octant walk the tree together, one
// SIMD lane per ray. At a node, each child box is tested against all active rays at once; a
// child is visited when any of them hits it, with the mask of those that do, in the node's
// order for the octant (WideNode::order), nearest first. Leaves are tested ray by ray with the
// single-ray block test. A node reached by at most `fallback` active rays no longer pays for a
// packet step (a packet tests one box per SIMD test, a single ray all N): each of its rays
// finishes that subtree alone, by the single-ray skeleton (traverseFrom, wide_bvh_traversal.h).
// PacketKind::Coherent (BVH::batchTraversal=coherent) adds a frustum test of each node's
// children before the rays' own tests and tests leaves one triangle against all active rays
// (coherent_traversal.h); the walk and the answers are the same.
//
// Answers equal the single-ray traversal's bit for bit: a ray's box test here performs
// WideBoxTest's operations in its order on the same RaySlabs values (lane by lane instead of
// child by child), its leaves use BlockTriangleTest itself, and the closest hit's tie rule
// does not depend on the visit order (ClosestHitQuery::record). Rays whose interval reaches
// below t = 0 (the sign-aware far margin) are not packed: traceAsPackets traces them alone.
//
// Counters per ray (docs/architecture.md): a ray counts a node step (N_TR) at each node where
// it is active, i.e. its own box test hit the node and, when the node is popped, it enters it
// before its closest hit so far (the root: every ray). N_IT counts the triangles of the leaves
// where it is active, as testLeafBlocks does. The visit order is the packet's, not the ray's,
// so hits shorten a ray's interval at other times: totals differ from single-ray totals.
#pragma once

#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/traverse/coherent_traversal.h"
#include "accel/bvh/traverse/octant_groups.h"
#include "accel/bvh/traverse/wide_bvh_traversal.h"

#include <algorithm>
#include <array>
#include <bit>
#include <span>
#include <type_traits>
#include <utility>

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// Rays per packet: 16 where the SIMD layer has 16-lane floats (AVX-512), else 8.
inline constexpr int kPacketWidth = std::is_same_v<simd::Floats<16>, simd::Scalar<16>> ? 8 : 16;

// The packets' node and leaf steps: Plain (Benthin et al.), or Coherent (coherent_traversal.h).
enum class PacketKind { Plain, Coherent };

namespace packet_traversal {

// The K rays' RaySlabs in SoA, one lane per ray, for rays of one direction octant (so that all
// enter a box through the same bounds); lanes past the packet's rays hold zeros (1/dir: inf)
// and are never active.
template <int K, int N, bool Robust>
struct PacketBoxTest {
    using F = simd::Floats<K>;
    alignas(64) float org[3][K]{};
    alignas(64) float inv[3][K]{};
    alignas(64) float invFar[3][K]{};
    alignas(64) float tmin[K]{};
    int nearOffset[3], farOffset[3];  // into a node's floats: its lower or upper bounds of each axis

    // RaySlabs' values in lanes: one IEEE operation per lane, the same values.
    PacketBoxTest(const Ray* rays, int count, int octant) {
        alignas(64) float dir[3][K]{};
        for (int k = 0; k < count; ++k) {
            for (int a = 0; a < 3; ++a) org[a][k] = rays[k].org[a], dir[a][k] = rays[k].dir[a];
            tmin[k] = rays[k].tmin;
        }
        for (int a = 0; a < 3; ++a) {
            const F lanes = F::broadcast(1.0f) / F::load(dir[a]);
            lanes.store(inv[a]);
            (lanes * F::broadcast(1.0f + kFarMargin<Robust>)).store(invFar[a]);
        }
        for (int a = 0; a < 3; ++a) {
            const int lower = a * N, upper = (3 + a) * N;  // WideNode: lower[3][N], then upper[3][N]
            const bool upperFirst = (octant >> a & 1) != 0;
            nearOffset[a] = upperFirst ? upper : lower;
            farOffset[a] = upperFirst ? lower : upper;
        }
    }

    // The rays (lanes) whose interval [tmin, tmax] overlaps child c's box, as a bit mask; where
    // each enters it goes to entryOut. Per lane WideBoxTest<N, false, Robust>'s operations in
    // its order, so a ray's answer is its single-ray answer bit for bit.
    [[gnu::always_inline]] int intersect(const WideNode<N>& node, int c, const float* tmax, float* entryOut) const {
        static_assert(offsetof(WideNode<N>, lower) == 0 && offsetof(WideNode<N>, upper) == 3 * N * sizeof(float));
        const float* bounds = &node.lower[0][0];
        F nearT[3], farT[3];
        for (int a = 0; a < 3; ++a) {
            const F nearBound = F::broadcast(bounds[nearOffset[a] + c]),
                    farBound = F::broadcast(bounds[farOffset[a] + c]);
            const F o = F::load(org[a]);
            nearT[a] = (nearBound - o) * F::load(inv[a]);
            farT[a] = (farBound - o) * F::load(invFar[a]);
        }
        const F entry = max(max(nearT[0], nearT[1]), max(nearT[2], F::load(tmin)));
        const F exit = min(min(farT[0], farT[1]), min(farT[2], F::load(tmax)));
        entry.store(entryOut);
        return movemask(entry <= exit);
    }
};

// A child to visit (a wide_child word) with the rays (a lane mask) that hit it; their entries
// are kept beside the stack (closest hit).
struct PacketEntry {
    uint32_t child;
    int rays;
};

// {make(0), ..., make(K - 1)}: per-ray objects without a default constructor.
template <int K, typename Make>
auto arrayOf(Make&& make) {
    return [&]<size_t... I>(std::index_sequence<I...>) { return std::array{make(I)...}; }
    (std::make_index_sequence<K>());
}

}  // namespace packet_traversal

// Traces rays[0, count) (0 < count <= K; every ray valid with tmin >= 0 and of direction
// octant `octant`; the tree not empty) as one packet, then calls answer(k, query, work) for each
// ray k with its query and its work (queries = 1; its steps and tests when Counting).
template <bool Counting, typename Query, bool Robust, int K, PacketKind Kind = PacketKind::Plain, int N,
          typename Answer>
void tracePacket(const WideBvh<N>& bvh, const Ray* rays, int count, int octant, int fallback, Answer&& answer) {
    constexpr bool kCoherent = Kind == PacketKind::Coherent;
    using namespace packet_traversal;
    using F = simd::Floats<K>;
    // Lanes past `count` repeat ray 0: never active, only so that every lane is constructed.
    const auto rayOf = [&](size_t k) -> const Ray& { return rays[int(k) < count ? k : 0]; };
    const PacketBoxTest<K, N, Robust> boxTest(rays, count, octant);
    const auto triangleTests = arrayOf<K>([&](size_t k) { return BlockTriangleTest<Robust>(rayOf(k)); });
    auto queries = arrayOf<K>([&](size_t k) { return Query(rayOf(k)); });
    alignas(64) float tmax[K]{};
    for (int k = 0; k < count; ++k) tmax[k] = queries[k].tmax;
    // Coherent: the frustum, its tmax the greatest of the rays' (kept up to date as hits shorten
    // them), and the packet's leaf test; nothing for the plain packets.
    const auto coherentOnly = [](auto make) {
        if constexpr (kCoherent) {
            return make();
        } else {
            return 0;
        }
    };
    const auto frustum = coherentOnly([&] {
        return PacketFrustum<N>(boxTest.org, boxTest.inv, boxTest.invFar, boxTest.tmin, count, boxTest.nearOffset,
                                boxTest.farOffset);
    });
    const auto packetTriangleTest = coherentOnly([&] { return PacketTriangleTest<K, Robust>(rays, count); });
    float frustumTmax = *std::max_element(tmax, tmax + count);
    const auto updateFrustumTmax = [&] {
        if constexpr (kCoherent && !Query::kStopsAtFirstHit) frustumTmax = *std::max_element(tmax, tmax + count);
    };
    uint64_t steps[K]{}, tests[K]{};
    const WideNode<N>* nodes = bvh.nodes.data();

    PacketEntry stack[kWideStackSize<N>];
    alignas(64) float stackEntries[kWideStackSize<N>][K];
    int size = 0;
    int live = int((1u << count) - 1);  // rays not yet answered (an any-hit ray leaves when occluded)
    const auto finished = [&](int k) {
        tmax[k] = queries[k].tmax;
        if constexpr (Query::kStopsAtFirstHit) {
            if (queries[k].occluded) live &= ~(1 << k);
        }
    };
    PacketEntry current{wide_child::inner(0), live};  // the root
    for (;;) {
        const int active = current.rays;
        if (wide_child::isLeaf(current.child)) {
            // Coherent: the packet's test where it takes fewer triangle tests than the rays'
            // blocks would (its lanes once per group of sheared frames, against the blocks once
            // per active ray).
            const int rayCount = std::popcount(unsigned(active));
            uint32_t packetTests = 0;
            uint32_t lanes = 0;
            if constexpr (kCoherent) {
                lanes = lanesToTest(bvh, current.child);
                packetTests = lanes * uint32_t(packetTriangleTest.groupsOf(active));
            }
            bool hit = false;
            if (kCoherent && packetTests <= uint32_t(rayCount) * wide_child::blocks(current.child)) {
                if constexpr (kCoherent) {
                    hit = testLeafPacket<Counting>(queries.data(), tmax, boxTest.tmin, packetTriangleTest, bvh,
                                                   current.child, lanes, active, tests);
                }
                for (int m = active; m != 0; m &= m - 1) {
                    const int k = std::countr_zero(unsigned(m));
                    if constexpr (Counting) ++steps[k];
                    finished(k);
                }
            } else {
                for (int m = active; m != 0; m &= m - 1) {
                    const int k = std::countr_zero(unsigned(m));
                    if constexpr (Counting) ++steps[k];
                    hit |= testLeafBlocks<Counting>(queries[k], triangleTests[k], bvh, current.child, rays[k].tmin,
                                                    tests[k]) ||
                           queries[k].tmax < tmax[k];
                    finished(k);
                }
            }
            if (hit) updateFrustumTmax();
        } else if (std::popcount(unsigned(active)) <= fallback) {
            for (int m = active; m != 0; m &= m - 1) {
                const int k = std::countr_zero(unsigned(m));
                const WideBoxTest<N, false, Robust> single(rays[k]);
                traverseFrom<Counting>(bvh, single, triangleTests[k], queries[k], current.child, steps[k], tests[k]);
                finished(k);
            }
            updateFrustumTmax();
        } else {
            if constexpr (Counting) {
                for (int m = active; m != 0; m &= m - 1) ++steps[std::countr_zero(unsigned(m))];
            }
            const WideNode<N>& node = nodes[current.child];
            alignas(64) float entries[N][K];
            int hitRays[N];
            int order[N];  // the children hit: closest hit far to near for the octant, any hit in lane order
            int hits = 0;
            // Coherent: the rays' own tests only on the children the frustum keeps.
            int candidates = 0;
            if constexpr (kCoherent) candidates = frustum.intersect(node, frustumTmax);
            for (int p = 0; p < N; ++p) {
                const int c = Query::kStopsAtFirstHit ? p : int(node.order[p] >> (3 * octant) & 7);
                if constexpr (kCoherent) {
                    if ((candidates >> c & 1) == 0) continue;
                } else if (!(node.lower[0][c] <= node.upper[0][c])) {
                    continue;  // an empty lane
                }
                const int mask = boxTest.intersect(node, c, tmax, entries[c]) & active;
                if (mask == 0) continue;
                hitRays[c] = mask;
                order[hits++] = c;
            }
            if (hits != 0) {
                // Closest hit: the nearest next, the others pushed far to near. Any hit: the
                // first in lane order next, as the single-ray skeleton does.
                const int next = Query::kStopsAtFirstHit ? 0 : hits - 1;
                assert(size + hits - 1 <= kWideStackSize<N>);
                for (int j = 0; j < hits; ++j) {
                    if (j == next) continue;
                    const int c = order[j];
                    stack[size] = {node.child[c], hitRays[c]};
                    if constexpr (!Query::kStopsAtFirstHit) F::load(entries[c]).store(stackEntries[size]);
                    ++size;
                }
                const int c = order[next];
                current = {node.child[c], hitRays[c]};
                continue;
            }
        }
        if (live == 0) break;
        // Pop the next child that one of its rays still enters before its closest hit.
        bool popped = false;
        while (!popped && size > 0) {
            --size;
            current = stack[size];
            if constexpr (Query::kStopsAtFirstHit) {
                current.rays &= live;
            } else {
                current.rays &= movemask(F::load(stackEntries[size]) <= F::load(tmax));
            }
            popped = current.rays != 0;
        }
        if (!popped) break;
    }
    for (int k = 0; k < count; ++k) {
        QueryCounters work;
        work.queries = 1;
        if constexpr (Counting) work.traversalSteps = steps[k], work.intersectionTests = tests[k];
        answer(k, queries[k], work);
    }
}

// A batch: its valid rays with tmin >= 0 in packets of up to kPacketWidth of one direction
// octant (a wavefront's camera rays, the shadow rays of one light: the rays of a packet are
// neighbours where the batch is coherent), the others alone (octant_groups.h). Calls answer(i, query, work) once per
// ray i, not in order, with its query and its work (queries = 1).
template <bool Counting, typename Query, bool Robust, PacketKind Kind, int N, typename Answer>
void traceAsPackets(const WideBvh<N>& bvh, std::span<const Ray> rays, int fallback, Answer&& answer) {
    constexpr int K = kPacketWidth;
    traceInOctantGroups<Counting, Query, Robust, K>(
        bvh, rays,
        [&](const Ray* group, int count, int octant, auto&& answerInGroup) {
            tracePacket<Counting, Query, Robust, K, Kind>(bvh, group, count, octant, fallback, answerInGroup);
        },
        answer);
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
