// What a BVH builder sees of a primitive: its bounding box and its index, nothing else (the
// builders never see triangles, so they serve any primitive). The array of PrimRefs is prepared
// once per build and then partitioned in place; a centroid is the centre of the box, derived
// on the fly (one add and one multiply) rather than read from a second array. Part of the
// plugin API: a builder plugin's split rule partitions these (<bvhlab/builder.h>).
#pragma once

#include <bvhlab/math.h>

#include <cstdint>

namespace bvhlab {

struct alignas(32) PrimRef {
    // lower and upper are loaded as 4-float SIMD registers: lane 3 then holds `prim` and
    // `pad`, which every computation ignores.
    float lower[3];
    uint32_t prim;
    float upper[3];
    uint32_t pad;

    float center(int axis) const { return 0.5f * (lower[axis] + upper[axis]); }
    Bounds3 box() const { return {{lower[0], lower[1], lower[2]}, {upper[0], upper[1], upper[2]}}; }
    static PrimRef of(const Bounds3& b, uint32_t prim) {
        return {{b.lower.x, b.lower.y, b.lower.z}, prim, {b.upper.x, b.upper.y, b.upper.z}, 0};
    }
};
static_assert(sizeof(PrimRef) == 32);

}  // namespace bvhlab
