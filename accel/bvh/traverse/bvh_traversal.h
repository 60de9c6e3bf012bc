// The one traversal of every BVH builder's tree: closest hit and any hit, with a fixed-size
// stack and no allocation.
//
// What the counters count (QueryCounters, Havran's terms):
//   N_TR (traversalSteps): nodes visited. The root is visited by every valid query; any other
//     node is visited when the ray enters its box before the current closest hit. Visiting an
//     inner node tests the boxes of its two children; visiting a leaf tests its triangles.
//     A node pushed on the stack and dropped on pop because a closer hit was found meanwhile
//     is not counted (it costs one comparison). So box tests = 1 + 2 * (inner nodes visited).
//   N_IT (intersectionTests): ray-triangle tests, i.e. the sizes of the leaves visited (an
//     any-hit query stops counting at the triangle that occludes).
//   queries: +1 per call, valid ray or not.
#pragma once

#include "accel/bvh/layout/bvh.h"

namespace bvhlab {

// Closest hit in [ray.tmin, ray.tmax]; on a miss returns false and leaves `hit` unchanged.
// Visits the nearer child first (by the entry distances of the two child boxes) and skips
// nodes the ray enters behind the current closest hit.
// robust = false (BVH::robust) swaps the watertight triangle test for Moeller-Trumbore and
// drops the box test's far-plane margin: only to measure what robustness costs.
bool bvhFindNearest(const Bvh& bvh, const Ray& ray, Hit& hit, QueryCounters& counters, bool robust);

// Any hit in [ray.tmin, ray.tmax], stopping at the first one found.
bool bvhIsOccluded(const Bvh& bvh, const Ray& ray, QueryCounters& counters, bool robust);

}  // namespace bvhlab
