// The reference split of the SBVH (Stich et al. 2009): a triangle's reference
// (its box, possibly already chopped by earlier splits) cut by an axis-aligned plane into the
// boxes of the triangle's parts on either side, each intersected with the reference's box.
// The triangle is clipped, not only its box halved, so the parts' boxes are tight: that is
// where the SBVH gains on long, thin, diagonal triangles.
#pragma once

#include <bvhlab/triangle.h>

#include <utility>

namespace bvhlab {

// The boxes of the part of `triangle` inside `box` with x[axis] <= position and of the part
// with x[axis] >= position. Either may be empty (isEmpty()) when the plane misses the part.
// Conservative: every point of a part lies in its box (edge crossings are computed in double
// and rounded outward), so a ray that hits the triangle enters the box of a part it hits.
std::pair<Bounds3, Bounds3> splitReference(const Triangle& triangle, const Bounds3& box, int axis, float position);

}  // namespace bvhlab
