// Perfect splits (Havran 2001; Wald and Havran 2006, section 4.2): the box of the part of a
// primitive inside a node's box. A triangle is clipped to the box (Sutherland-Hodgman, in
// double); a sphere or cone is represented by its bounding box, which is intersected with it.
// Conservative: the triangle is clipped to the box enlarged by `margin`, so that rounding never
// drops a triangle that touches the box, and the result is rounded outward to float and kept
// inside `box` (flat against a face where the part lies only in the margin). No part: an empty
// Bounds3.
#pragma once

#include <bvhlab/primitive_set.h>

namespace bvhlab::kdtree {

Bounds3 clippedTriangleBounds(const Triangle& tri, const Bounds3& box, double margin);
Bounds3 clippedBounds(const PrimitiveSet& prims, uint32_t prim, const Bounds3& box, double margin);

}  // namespace bvhlab::kdtree
