// How a BVH is traversed, apart from how it is built (BvhBuildConfig): the same tree serves
// either setting.
#pragma once

namespace bvhlab {

struct TraversalConfig {
    // BVH::robust. true: the watertight triangle test and the conservative box test (box_test.h);
    // false: Moeller-Trumbore and plain boxes (not watertight), only to measure what
    // robustness costs.
    bool robust = true;
    // BVH::packetFallback. Batches on the wide layouts trace packets (packet_traversal.h); a
    // node reached by at most this many active rays of a packet is finished ray by ray.
    // Measured best: docs/performance.md, "Issue #31 — packets".
    int packetFallback = 2;
};

}  // namespace bvhlab
