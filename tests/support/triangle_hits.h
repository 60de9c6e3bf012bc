// The ray-triangle test as the triangle tests call it: hit or miss in float or double, the hit's
// t/u/v, points by their barycentric coordinates, and a triangle whose hits are easy to work out.
#pragma once

#include <bvhlab/triangle.h>
#include "tests/support/quiet_nan.h"

#include <glm/glm.hpp>

namespace bvhlab::test {

template <typename Real>
bool hits(const Ray& ray, const Triangle& tri, TriangleHitT<Real>* out = nullptr) {
    TriangleHitT<Real> h{};
    const bool hit = intersectTriangle<Real>(ShearedRayT<Real>(ray), tri, Real(ray.tmin), Real(ray.tmax), h);
    if (hit && out) *out = h;
    return hit;
}

inline bool hitsF(const Ray& ray, const Triangle& tri) { return hits<float>(ray, tri); }
inline bool hitsD(const Ray& ray, const Triangle& tri) { return hits<double>(ray, tri); }

inline glm::dvec3 pointAt(const Triangle& tri, double u, double v) {
    return (1.0 - u - v) * glm::dvec3(tri.v0) + u * glm::dvec3(tri.v1) + v * glm::dvec3(tri.v2);
}

// v0 = (1,1,5), v1 = (3,1,5), v2 = (1,5,5): the hit point (x, y, 5) has u = (x-1)/2, v = (y-1)/4.
inline const Triangle kTri{{1, 1, 5}, {3, 1, 5}, {1, 5, 5}};

}  // namespace bvhlab::test
