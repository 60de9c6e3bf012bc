#include "framework/scene/surface_point.h"

namespace bvhlab {
namespace {

float largestCoordinate(const Vec3& v) {
    const Vec3 a = glm::abs(v);
    return std::max(std::max(a.x, a.y), a.z);
}

SurfacePoint triangleSurface(const Scene& scene, const Ray& ray, const Hit& hit) {
    const Triangle& tri = scene.triangles[hit.primitive];
    SurfacePoint s;
    // The point from barycentrics is more accurate than org + t*dir far from the origin.
    s.position = (1.0f - hit.u - hit.v) * tri.v0 + hit.u * tri.v1 + hit.v * tri.v2;
    const Vec3 n = glm::normalize(tri.geometricNormal());
    s.outside = glm::dot(n, ray.dir) <= 0.0f;
    s.geometricNormal = s.outside ? n : -n;
    s.shadingNormal = s.geometricNormal;
    if (!scene.normals.empty()) {
        const glm::uvec3 idx = scene.indices[hit.primitive];
        const Vec3 interpolated =
            (1.0f - hit.u - hit.v) * scene.normals[idx.x] + hit.u * scene.normals[idx.y] + hit.v * scene.normals[idx.z];
        if (glm::dot(interpolated, interpolated) > 0.0f)
            s.shadingNormal = glm::faceforward(glm::normalize(interpolated), -s.geometricNormal, s.geometricNormal);
    }
    s.magnitude = std::max({largestCoordinate(tri.v0), largestCoordinate(tri.v1), largestCoordinate(tri.v2)});
    return s;
}

}  // namespace

SurfacePoint surfaceAt(const Scene& scene, const Ray& ray, const Hit& hit) {
    const PrimitiveSet prims = scene.primitives();
    if (prims.kind(hit.primitive) == PrimitiveKind::Triangle) return triangleSurface(scene, ray, hit);

    SurfacePoint s;
    Vec3 outward;
    if (prims.kind(hit.primitive) == PrimitiveKind::Sphere) {
        const Sphere& sphere = prims.spheres[hit.primitive - prims.sphereBase()];
        outward = sphere.normalAt(ray.at(hit.t));
        // Back onto the sphere: org + t*dir carries the rounding of t times |dir|.
        s.position = sphere.centre + std::abs(sphere.radius) * outward;
        s.magnitude = largestCoordinate(sphere.centre) + std::abs(sphere.radius);
    } else {
        const Cone& cone = prims.cones[hit.primitive - prims.coneBase()];
        s.position = ray.at(hit.t);
        outward = cone.normalAt(s.position);
        s.magnitude = std::max(largestCoordinate(cone.base), largestCoordinate(cone.apex)) +
                      std::max(std::abs(cone.baseRadius), std::abs(cone.apexRadius));
    }
    // The point's own rounding (org + t*dir) grows with its magnitude too.
    s.magnitude = std::max(s.magnitude, largestCoordinate(s.position));
    s.outside = glm::dot(outward, ray.dir) <= 0.0f;
    s.geometricNormal = s.outside ? outward : -outward;
    s.shadingNormal = s.geometricNormal;
    return s;
}

}  // namespace bvhlab
