// The traversal of the 4-wide BVH: per step one SSE test of a node's four child boxes (a
// scalar loop where SSE is missing), the children hit pushed far to near, so the nearest is
// visited first. The same box-test robustness (Ize's far-plane margin, NaN-free axis-parallel
// rays) and the same leaf triangle test as the binary traversal.
//
// Counters: N_TR counts the steps, i.e. wide nodes and leaves visited (the root always);
// N_IT the ray-triangle tests. N_TR is therefore not comparable with a binary tree's.
#pragma once

#include "accel/bvh/layout/wide_bvh.h"

namespace bvhlab {

bool wideBvhFindNearest(const WideBvh& bvh, const Ray& ray, Hit& hit, QueryCounters& counters, bool robust);
bool wideBvhIsOccluded(const WideBvh& bvh, const Ray& ray, QueryCounters& counters, bool robust);

}  // namespace bvhlab
