// The box of a set of PrimRefs and the box of their centres (<bvhlab/prim_ref.h>),
// accumulated in the hot loops of every builder.
//
// The hot loops are written once against the SIMD layer (simd.h) and run with its vector or
// its scalar backend (BVH::simd): the same IEEE operations, so the same tree either way.
#pragma once

#include "accel/bvh/simd/simd.h"

#include <bvhlab/prim_ref.h>

#include <cstdint>

namespace bvhlab {

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
