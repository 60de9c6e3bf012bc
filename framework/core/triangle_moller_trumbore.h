// The classic ray-triangle test of Moeller and Trumbore (1997), in float. It is not
// watertight: rays aimed at a shared edge can slip between its two triangles (tests/
// test_stress.cpp counts them). It is here as the baseline that shows what the watertight
// test (triangle.h) costs: `BVH::robust=false` traverses with it.
#pragma once

#include <bvhlab/triangle.h>
#include <glm/glm.hpp>

namespace bvhlab {

// Returns true and fills `out` when the ray hits the triangle at t in [tmin, tmax].
inline bool intersectTriangleMollerTrumbore(const Ray& ray, const Triangle& tri, float tmin, float tmax,
                                            TriangleHitT<float>& out) {
    const Vec3 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
    const Vec3 p = glm::cross(ray.dir, e2);
    const float det = glm::dot(e1, p);
    if (det == 0.0f) return false;
    const float invDet = 1.0f / det;
    const Vec3 s = ray.org - tri.v0;
    const float u = glm::dot(s, p) * invDet;
    if (u < 0.0f || u > 1.0f) return false;
    const Vec3 q = glm::cross(s, e1);
    const float v = glm::dot(ray.dir, q) * invDet;
    if (v < 0.0f || u + v > 1.0f) return false;
    const float t = glm::dot(e2, q) * invDet;
    if (!(t >= tmin && t <= tmax)) return false;
    out = {t, u, v};
    return true;
}

}  // namespace bvhlab
