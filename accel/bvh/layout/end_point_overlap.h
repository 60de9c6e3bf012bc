// EPO, the end-point overlap of a BVH (Aila, Karras and Laine, "On quality metrics of bounding
// volume hierarchies", HPG 2013): the surface area of the scene's geometry that lies inside a
// node's box without belonging to the node's subtree, summed over the nodes with the node's
// cost and divided by the area of all geometry,
//   EPO = sum_n C_n * A((S \ S(n)) ∩ box(n)) / A(S),  C_n = C_trav (inner), C_isect (leaf).
// A ray ending on such geometry (a hit, or a shadow ray's light) must still visit the node,
// which the SAH, counting rays that pass through, does not see. Computed exactly: each triangle
// is clipped to the boxes of the nodes it overlaps, found by a walk from the root that stops
// where the clipped area is zero (children lie inside their parent). The cost is that walk per
// triangle: about the SAH traversal of a short ray, O(N log N) for a good tree, seconds for
// millions of triangles (BVH::epoMaxTriangles).
#pragma once

#include <bvhlab/triangle.h>
#include "accel/bvh/layout/bvh_node.h"

#include <optional>
#include <span>

namespace bvhlab {

// The node visits the walks may take, per triangle on average (measured 40-100 for sahbvh8 on
// five of our scenes, 166 for tdbvh on conference); beyond, boxes overlap so much (many coincident triangles) that the
// walks grow quadratic, and EPO is not computed.
inline constexpr int kEpoVisitsPerTriangle = 512;

// EPO of the tree `nodes` (the BinaryBvh layout) whose leaf slot i holds leafTriangles[i]; 0 for an
// empty tree or geometry of no area; nullopt past the visit budget. TBB-parallel on `threads`
// (0 = all) over fixed chunks of triangles, summed in a fixed order: the same value whatever
// the thread count (and whether the budget is exceeded depends only on the total visits).
std::optional<double> endPointOverlap(std::span<const BvhNode> nodes, std::span<const Triangle> leafTriangles,
                                      double cTraversal, double cIntersect, int threads);

// The area of the part of `t` inside `box` (exact up to rounding: the triangle clipped by the
// box's six planes in double precision).
double clippedArea(const Triangle& t, const Bounds3& box);

}  // namespace bvhlab
