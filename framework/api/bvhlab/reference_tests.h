// A list of primitive references tested against a ray, as a cell or a leaf of a spatial
// subdivision tests its references: each with its primitive's watertight test, counted in N_IT
// by its kind; and the two queries along a walk over such cells in the ray's order. For the
// structures that refer to one primitive from many places (grid, octree, kd-tree).
#pragma once

#include <bvhlab/counters.h>
#include <bvhlab/primitive_set.h>
#include <bvhlab/triangle.h>

namespace bvhlab {

// Tests each primitive of `refs` in order within [ray.tmin, tmax]; a hit lowers tmax to its t
// and calls onHit(t, prim, u, v) (u, v are 0 for spheres and cones), which returns true to stop
// the tests. Returns whether onHit stopped them.
template <typename OnHit>
bool testReferences(const PrimitiveSet& prims, View<const uint32_t> refs, const Ray& ray, const ShearedRay& sheared,
                    float& tmax, QueryCounters& counters, OnHit&& onHit) {
    for (const uint32_t prim : refs) {
        if (prims.kind(prim) == PrimitiveKind::Triangle) {
            ++counters.intersectionTests;
            TriangleHitT<float> h;
            if (intersectTriangle(sheared, prims.triangles[prim], ray.tmin, tmax, h)) {
                tmax = h.t;
                if (onHit(h.t, prim, h.u, h.v)) return true;
            }
        } else {
            const QuadricShape shape = prims.quadric(prim);
            counters.countQuadricTest(shape);
            QuadricHitT<float> h;
            if (intersectQuadric(ray, shape, ray.tmin, tmax, h)) {
                tmax = h.t;
                if (onHit(h.t, prim, 0.0f, 0.0f)) return true;
            }
        }
    }
    return false;
}

// The closest hit along a walk: walk(visit) calls visit(refs, tExit) for the cells the ray
// crosses, in its order, while visit returns true; tExit is the t at which the ray leaves the
// cell. A hit beyond the cell's exit is kept (it bounds the later tests) but answered only once
// the walk reaches a cell whose exit lies at or beyond it: a closer one may lie in the cells
// between. Every point of a primitive must lie in a cell that refers to it.
template <typename Walk>
bool findNearestAlong(const PrimitiveSet& prims, const Ray& ray, QueryCounters& counters, Walk&& walk, Hit& hit) {
    const ShearedRay sheared(ray);
    float tmax = ray.tmax;
    Hit best;
    walk([&](View<const uint32_t> refs, double exit) {
        testReferences(prims, refs, ray, sheared, tmax, counters, [&](float t, uint32_t prim, float u, float v) {
            best = {t, prim, u, v};
            return false;
        });
        return !(best.found() && double(best.t) <= exit);
    });
    if (!best.found()) return false;
    hit = best;
    return true;
}

// Any hit along a walk (as findNearestAlong's), stopping at the first.
template <typename Walk>
bool isOccludedAlong(const PrimitiveSet& prims, const Ray& ray, QueryCounters& counters, Walk&& walk) {
    const ShearedRay sheared(ray);
    float tmax = ray.tmax;
    bool occluded = false;
    walk([&](View<const uint32_t> refs, double) {
        occluded = testReferences(prims, refs, ray, sheared, tmax, counters,
                                  [](float, uint32_t, float, float) { return true; });
        return !occluded;
    });
    return occluded;
}

}  // namespace bvhlab
