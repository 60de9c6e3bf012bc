// How the wide layouts' group paths (packets: packet_traversal.h, streams: stream_traversal.h)
// split a batch: its valid rays with tmin >= 0 in groups of up to K rays of one direction
// octant, so that every ray of a group enters a box through the same bounds, in the order
// they come (a wavefront's camera rays, the shadow rays of one light: the rays of a group are
// neighbours where the batch is coherent), one group filling per octant. The other rays go
// alone through runQuery: a miss for an invalid ray, the sign-aware box test for tmin < 0.
#pragma once

#include "accel/bvh/layout/wide_bvh.h"
#include "accel/bvh/simd/kernel_namespace.h"
#include "accel/bvh/traverse/traversal.h"

#include <cstddef>
#include <span>

namespace bvhlab {
inline namespace BVHLAB_KERNEL_NS {

// Calls trace(groupRays, count, octant, answerInGroup) per group (0 < count <= K; the tree not
// empty), which must call answerInGroup(k, query, work) once per ray k of the group; calls
// answer(i, query, work) once per ray i of the batch, not in order, with its query and its
// work (queries = 1).
template <bool Counting, typename Query, bool Robust, int K, int N, typename Trace, typename Answer>
void traceInOctantGroups(const WideBvh<N>& bvh, std::span<const Ray> rays, Trace&& trace, Answer&& answer) {
    struct Group {
        Ray rays[K];
        size_t index[K];
        int count = 0;
    };
    Group groups[8];  // one filling per octant
    const auto flush = [&](int octant) {
        Group& g = groups[octant];
        trace(g.rays, g.count, octant,
              [&](int k, const Query& query, const QueryCounters& work) { answer(g.index[k], query, work); });
        g.count = 0;
    };
    for (size_t i = 0; i < rays.size(); ++i) {
        const Ray& ray = rays[i];
        if (bvh.empty() || !ray.isValid() || ray.tmin < 0.0f) {
            QueryCounters work;
            const Query query = runQuery<Query, Robust, Counting>(bvh, ray, work);
            answer(i, query, work);
            continue;
        }
        const int octant = directionOctant(ray.dir);
        Group& g = groups[octant];
        g.rays[g.count] = ray;
        g.index[g.count++] = i;
        if (g.count == K) flush(octant);
    }
    for (int octant = 0; octant < 8; ++octant)
        if (groups[octant].count != 0) flush(octant);
}

}  // namespace BVHLAB_KERNEL_NS
}  // namespace bvhlab
