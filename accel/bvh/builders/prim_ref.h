// What BVH builders see of a primitive: its bounding box and its index, nothing else (the
// builders never see triangles, so they would serve any primitive). The array of PrimRefs is
// prepared once per build and then partitioned in place; a centroid is the centre of the box,
// derived from it on the fly (one add and one multiply) rather than read from a second array.
//
// The hot loops are written once against the SIMD layer (simd.h) and run with its vector or
// its scalar backend (BVH::simd): the same IEEE operations, so the same tree either way.
#pragma once

#include "accel/bvh/simd/simd.h"
#include "framework/core/math.h"

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

// The box of a set of primitives and the box of their centres, accumulated one by one, in
// lanes of F (simd::Floats<4> or simd::Scalar<4>). The centre box accumulates lower + upper and
// halves once at the end: halving is monotone, so that equals the min/max of the individual
// centres bit for bit.
template <typename F>
struct BoundsAccumulator {
    F lower = F::broadcast(kInfinity), upper = F::broadcast(-kInfinity);
    F sumLower = F::broadcast(kInfinity), sumUpper = F::broadcast(-kInfinity);

    void add(const PrimRef& r) {
        const F lo = F::load(r.lower), hi = F::load(r.upper);
        lower = min(lower, lo);
        upper = max(upper, hi);
        const F sum = lo + hi;
        sumLower = min(sumLower, sum);
        sumUpper = max(sumUpper, sum);
    }
    Bounds3 bounds() const { return {toVec3(lower), toVec3(upper)}; }
    Bounds3 centroidBounds() const { return {0.5f * toVec3(sumLower), 0.5f * toVec3(sumUpper)}; }

private:
    static Vec3 toVec3(const F& v) {
        alignas(16) float f[4];
        v.store(f);
        return {f[0], f[1], f[2]};
    }
};

}  // namespace bvhlab
