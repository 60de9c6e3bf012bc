#include "accel/naive/naive_accelerator.h"

namespace bvhlab {

void NaiveAccelerator::build(const PrimitiveSet& prims) { prims_ = prims; }

BuildStats NaiveAccelerator::buildStats() const {
    const size_t n = prims_.valid.size();
    BuildStats stats;
    stats.primitives = n;
    // One leaf holding everything: the SAH cost of brute force is C_isect * N.
    stats.nodes = 1;
    stats.leaves = 1;
    stats.avgLeafPrimitives = double(n);
    stats.maxLeafPrimitives = n;
    stats.maxDepth = 0;
    stats.sah = SahCost{double(n), 1.0, 1.0};
    stats.bytes = 0;
    return stats;
}

bool NaiveAccelerator::findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const {
    ++counters.queries;
    if (!ray.isValid()) return false;
    counters.traversalSteps += 1;
    const ShearedRay sheared(ray);
    float tmax = ray.tmax;
    bool found = false;
    const View<const uint32_t> triangles = prims_.validTriangles();
    for (uint32_t prim : triangles) {
        TriangleHitT<float> h;
        if (intersectTriangle(sheared, prims_.triangles[prim], ray.tmin, tmax, h)) {
            tmax = h.t;
            hit = {h.t, prim, h.u, h.v};
            found = true;
        }
    }
    counters.intersectionTests += triangles.size();
    for (uint32_t prim : prims_.validQuadrics()) {
        const QuadricShape shape = prims_.quadric(prim);
        counters.countQuadricTest(shape);
        QuadricHitT<float> h;
        if (intersectQuadric(ray, shape, ray.tmin, tmax, h)) {
            tmax = h.t;
            hit = {h.t, prim, 0.0f, 0.0f};
            found = true;
        }
    }
    return found;
}

bool NaiveAccelerator::isOccluded(const Ray& ray, QueryCounters& counters) const {
    ++counters.queries;
    if (!ray.isValid()) return false;  // like findNearest: a rejected ray does no work
    counters.traversalSteps += 1;
    const ShearedRay sheared(ray);
    TriangleHitT<float> h;
    for (uint32_t prim : prims_.validTriangles()) {
        ++counters.intersectionTests;
        if (intersectTriangle(sheared, prims_.triangles[prim], ray.tmin, ray.tmax, h)) return true;
    }
    QuadricHitT<float> q;
    for (uint32_t prim : prims_.validQuadrics()) {
        const QuadricShape shape = prims_.quadric(prim);
        counters.countQuadricTest(shape);
        if (intersectQuadric(ray, shape, ray.tmin, ray.tmax, q)) return true;
    }
    return false;
}

}  // namespace bvhlab
