// What every BVH builder shares: the leaf rules, the SAH's constants, SIMD and threads. Each
// builder's own options are a Config of its own, next to it (madmann91/bvh v2's way), and so
// are the BVH:: env keys that fill them (field_key.h).
#pragma once

#include "framework/config/field_key.h"

#include <bvhlab/math.h>

#include <algorithm>
#include <cstdint>
#include <tuple>

namespace bvhlab {

struct BuildConfig {
    int maxLeaf = 2;             // ranges of this many primitives or fewer always become leaves
    int leafCap = 16;            // largest leaf made when splitting does not pay (SAH termination)
                                 // or cannot separate primitives (coincident centres); >= maxLeaf
    bool sahTermination = true;  // SAH builders: leaf when no split beats testing every primitive
    float cTraversal = 1.0f;     // SAH cost of visiting an inner node, in units of ...
    float cIntersect = 1.0f;     // ... the cost of one ray-triangle test
    int sahBlockShift = 0;       // the SAH builders count a leaf's tests in blocks of 2^shift
                                 // triangles (ceil(n / 2^shift), Embree's sahBlockSize): 2 for
                                 // the wide layouts, whose leaves test eight at once
    bool simd = true;            // SIMD in the hot loops (prep, binning, partition); false = the
                                 // scalar backend of the same code, the same tree
    int threads = 1;             // build threads (TBB; 0 = all hardware threads): the tree does
                                 // not depend on them

    uint32_t effectiveLeafCap() const { return uint32_t(std::max(maxLeaf, leafCap)); }
    // What the SAH charges for testing n primitives: n, or the blocks they fill.
    uint32_t sahTests(uint32_t n) const { return (n + (1u << sahBlockShift) - 1) >> sahBlockShift; }

    bool operator==(const BuildConfig&) const = default;
};

namespace keys::BVH {
inline constexpr FieldKey<&BuildConfig::maxLeaf> maxLeaf{
    "BVH::maxLeaf", 1, 64,
    "ranges of this many primitives or fewer become leaves; 1, with sahTermination off and leafCap 1, = the "
    "report's BVH"};
inline constexpr FieldKey<&BuildConfig::leafCap> leafCap{
    "BVH::leafCap", 1, 256,
    "largest leaf made when SAH termination stops or all centres coincide (raised to maxLeaf if below)"};
inline constexpr FieldKey<&BuildConfig::sahTermination> sahTermination{
    "BVH::sahTermination", "sahbvh/sweepbvh: leaf when C_trav + C_isect*(A_L*N_L + A_R*N_R)/A >= C_isect*N"};
inline constexpr FieldKey<&BuildConfig::cTraversal> cTraversal{
    "BVH::cTraversal", 0, 1e6, "SAH cost of an inner node: used by the SAH builders and by the reported SAH cost"};
inline constexpr FieldKey<&BuildConfig::cIntersect> cIntersect{
    "BVH::cIntersect", 1e-6, 1e6,
    "SAH cost of a ray-triangle test: used by the SAH builders and by the reported SAH cost"};
inline constexpr FieldKey<&BuildConfig::simd> simd{
    "BVH::simd", "SSE in the build's hot loops (bounds, centres, binning, partition); false = scalar, same tree"};
}  // namespace keys::BVH

// The keys every builder reads (the threads come from BvhSettings::threads, bvh_env.h), and the
// one only the SAH builders read.
inline constexpr std::tuple kBuildKeys{&keys::BVH::maxLeaf, &keys::BVH::leafCap, &keys::BVH::cTraversal,
                                       &keys::BVH::cIntersect, &keys::BVH::simd};
inline constexpr std::tuple kSahTerminationKeys{&keys::BVH::sahTermination};

// The SAH leaf test: a split of cost `splitCost` = A_L*N_L + A_R*N_R of n primitives in
// `bounds` pays off when C_trav + C_isect * splitCost / A < C_isect * N.
inline bool sahPrefersLeaf(const BuildConfig& config, const Bounds3& bounds, uint32_t n, float splitCost) {
    const float area = bounds.halfArea();
    if (!(area > 0.0f)) return false;  // no meaningful ratio: keep splitting
    const float tests = float(config.sahTests(n));
    return !(config.cTraversal + config.cIntersect * splitCost / area < config.cIntersect * tests);
}

}  // namespace bvhlab
