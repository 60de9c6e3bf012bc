// What BVH builders see of a primitive: its bounding box and its index, nothing else (the
// builders never see triangles, so they would serve any primitive). The array of PrimRefs is
// prepared once per build and then partitioned in place; a centroid is the centre of the box,
// derived from it on the fly (one add and one multiply) rather than read from a second array.
//
// The SIMD paths (SSE2, always present on x86-64) and the scalar paths compute the same
// IEEE operations in the same order, so `BVH::simd` on or off builds the identical tree.
#pragma once

#include "accel/bvh/simd/bvh_simd.h"
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
};
static_assert(sizeof(PrimRef) == 32);

// Scalar min and max with the semantics of SSE's minps/maxps (the second operand when equal
// or unordered), so that scalar and SIMD paths agree even on the sign of a zero.
inline float minSse(float a, float b) { return a < b ? a : b; }
inline float maxSse(float a, float b) { return a > b ? a : b; }

// The box of a set of primitives and the box of their centres, accumulated one by one. The
// centre box accumulates lower + upper and halves once at the end: halving is monotone, so
// that equals the min/max of the individual centres bit for bit.
struct ScalarBoundsAccumulator {
    float lower[3] = {kInfinity, kInfinity, kInfinity}, upper[3] = {-kInfinity, -kInfinity, -kInfinity};
    float sumLower[3] = {kInfinity, kInfinity, kInfinity}, sumUpper[3] = {-kInfinity, -kInfinity, -kInfinity};

    void add(const PrimRef& r) {
        for (int a = 0; a < 3; ++a) {
            lower[a] = minSse(lower[a], r.lower[a]);
            upper[a] = maxSse(upper[a], r.upper[a]);
            const float sum = r.lower[a] + r.upper[a];
            sumLower[a] = minSse(sumLower[a], sum);
            sumUpper[a] = maxSse(sumUpper[a], sum);
        }
    }
    Bounds3 bounds() const { return {{lower[0], lower[1], lower[2]}, {upper[0], upper[1], upper[2]}}; }
    Bounds3 centroidBounds() const {
        return {0.5f * Vec3(sumLower[0], sumLower[1], sumLower[2]), 0.5f * Vec3(sumUpper[0], sumUpper[1], sumUpper[2])};
    }
};

#if BVHLAB_BVH_SSE
inline Vec3 toVec3(__m128 v) {
    alignas(16) float f[4];
    _mm_store_ps(f, v);
    return {f[0], f[1], f[2]};
}

struct SseBoundsAccumulator {
    __m128 lower = _mm_set1_ps(kInfinity), upper = _mm_set1_ps(-kInfinity);
    __m128 sumLower = _mm_set1_ps(kInfinity), sumUpper = _mm_set1_ps(-kInfinity);

    void add(const PrimRef& r) {
        const __m128 lo = _mm_load_ps(r.lower), hi = _mm_load_ps(r.upper);
        lower = _mm_min_ps(lower, lo);
        upper = _mm_max_ps(upper, hi);
        const __m128 sum = _mm_add_ps(lo, hi);
        sumLower = _mm_min_ps(sumLower, sum);
        sumUpper = _mm_max_ps(sumUpper, sum);
    }
    Bounds3 bounds() const { return {toVec3(lower), toVec3(upper)}; }
    Bounds3 centroidBounds() const { return {0.5f * toVec3(sumLower), 0.5f * toVec3(sumUpper)}; }
};
#else
using SseBoundsAccumulator = ScalarBoundsAccumulator;
#endif

}  // namespace bvhlab
