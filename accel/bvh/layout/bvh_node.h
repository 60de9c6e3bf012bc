// The one node layout every BVH builder emits and the one traversal walks: a binary node in
// 32 bytes (pbrt's LinearBVHNode size). The two children of an inner node are stored next to
// each other (left at `index`, right at `index + 1`), so one index addresses both and a
// traversal step reads one contiguous 64-byte pair.
#pragma once

#include <bvhlab/math.h>

#include <cstdint>

namespace bvhlab {

struct alignas(32) BvhNode {
    // lower x y z, then upper x y z: a flat array so that the traversal can pick the near and
    // far slab of each axis by the ray's octant (bounds[axis + 3 * dirIsNegative]).
    float bounds[6];
    uint32_t index;  // inner: the left child (the right one is index + 1); leaf: first primitive
    uint32_t count;  // 0 for an inner node; the number of primitives of a leaf

    bool isLeaf() const { return count != 0; }

    Bounds3 box() const { return {{bounds[0], bounds[1], bounds[2]}, {bounds[3], bounds[4], bounds[5]}}; }
    void setBox(const Bounds3& b) {
        bounds[0] = b.lower.x, bounds[1] = b.lower.y, bounds[2] = b.lower.z;
        bounds[3] = b.upper.x, bounds[4] = b.upper.y, bounds[5] = b.upper.z;
    }
};
static_assert(sizeof(BvhNode) == 32, "a binary BVH node is meant to fill half a cache line");

// Builders keep the tree shallower than this, so a traversal stack of this many entries
// cannot overflow (a push happens at most once per level).
inline constexpr int kBvhMaxDepth = 64;

}  // namespace bvhlab
