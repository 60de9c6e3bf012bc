// The steps of a build that every builder shares, whether under the top-down recursion or with a
// tree of its own (sbvh, ploc, a plugin's merge tree): the PrimRefs of the triangles first, the
// leaf arrays last.
#pragma once

#include "accel/bvh/builders/split_rule.h"
#include "accel/bvh/layout/binary_bvh.h"

namespace bvhlab {

// One PrimRef per valid triangle into `out` (its size), and the range over them; SIMD or scalar,
// the same PrimRefs.
BuildRange preparePrimRefs(const PrimitiveSet& prims, PrimRef* out, bool simd);
// The leaf arrays from PrimRefs in leaf order.
void fillLeafArrays(BinaryBvh& bvh, const PrimRef* refs, const PrimitiveSet& prims, int threads);
// bvh.leafTriangles from the triangles bvh.primIndices name, in parallel.
void copyLeafTriangles(const PrimitiveSet& prims, int threads, BinaryBvh& bvh);

}  // namespace bvhlab
