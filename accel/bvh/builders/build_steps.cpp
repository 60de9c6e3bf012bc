#include "accel/bvh/builders/build_steps.h"

#include "accel/bvh/builders/bounds_accumulator.h"
#include "accel/bvh/builders/build_threads.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace bvhlab {

namespace {

// Step one of buildBvh: one PrimRef per valid triangle, and their boxes, in lanes of F.
template <typename F>
BuildRange preparePrimRefsWith(const PrimitiveSet& prims, PrimRef* out) {
    const std::span<const uint32_t> validTriangles = prims.validTriangles();
    const uint32_t n = uint32_t(validTriangles.size());
    const Triangle* triangles = prims.triangles.data();
    const uint32_t* valid = validTriangles.data();
    BoundsAccumulator<F> acc;
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t prim = valid[i];
        const Triangle& t = triangles[prim];
        // Unaligned 4-float loads (lane 3 is ignored); none reads past the triangle, which may
        // end the array.
        const F v0 = F::loadu(&t.v0.x), v1 = F::loadu(&t.v1.x), v2 = F::loadLast3(&t.v2.x);
        PrimRef& ref = out[i];
        min(min(v0, v1), v2).store(ref.lower);
        max(max(v0, v1), v2).store(ref.upper);
        ref.prim = prim;
        ref.pad = 0;
        acc.add(ref);
    }
    return {0, n, acc.bounds(), acc.centroidBounds()};
}

}  // namespace

BuildRange preparePrimRefs(const PrimitiveSet& prims, PrimRef* out, bool simd) {
    return simd::withFloats4(simd, [&](auto f) { return preparePrimRefsWith<decltype(f)>(prims, out); });
}

void fillLeafArrays(BinaryBvh& bvh, const PrimRef* refs, const PrimitiveSet& prims, int threads) {
    const size_t n = prims.validTriangles().size();
    bvh.primIndices.resize(n);
    for (size_t i = 0; i < n; ++i) bvh.primIndices[i] = refs[i].prim;
    copyLeafTriangles(prims, threads, bvh);
}

void copyLeafTriangles(const PrimitiveSet& prims, int threads, BinaryBvh& bvh) {
    const size_t n = bvh.primIndices.size();
    bvh.leafTriangles.resize(n);
    onThreads(threads, [&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) bvh.leafTriangles[i] = prims.triangles[bvh.primIndices[i]];
        });
    });
}

}  // namespace bvhlab
