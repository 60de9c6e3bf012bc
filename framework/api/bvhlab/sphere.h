// The ray-sphere test of NFF's `s`, with the precision improvements of pbrt-v4 and Ray Tracing
// Gems ch. 7 (Haines et al.): the discriminant from the distance of the ray's line to the centre,
// and the two roots without cancellation (quadric.h).
#pragma once

#include <bvhlab/quadric.h>
#include <bvhlab/ray.h>

namespace bvhlab {

// NFF gives a negative radius to a sphere of which only the inside is visible: the surface is
// that of |radius|, and the sign is left to shading.
struct Sphere {
    Vec3 centre;
    float radius;

    Bounds3 bounds() const {
        const DVec3 c(centre);
        const double r = math::abs(double(radius));
        const double magnitude = math::max(math::max(math::abs(c.x), math::abs(c.y)), math::abs(c.z)) + r;
        return boundsRoundedOutward(c - r, c + r, 0x1p-45 * magnitude);
    }
    Vec3 centroid() const { return centre; }
    // The unit normal at a point p on the surface, away from the centre.
    Vec3 normalAt(const Vec3& p) const { return math::normalize(p - centre); }
};

// A non-finite centre or radius, or a radius whose square is not a normal float (0, or so
// small or large that it under- or overflows): no test in float could place such a surface.
inline bool isDegenerate(const Sphere& sphere) {
    return !isFinite(sphere.centre) || !math::isnormal(sphere.radius * sphere.radius);
}

// Returns true and fills `out` with the nearest hit at t in [tmin, tmax]; a ray starting
// inside hits the far side. Real = double gives the reference used by the tests.
template <typename Real>
inline bool intersectSphere(const Ray& ray, const Sphere& sphere, Real tmin, Real tmax, QuadricHitT<Real>& out) {
    using V = glm::vec<3, Real>;
    if (isDegenerate(sphere)) return false;
    const Real r = math::abs(Real(sphere.radius));
    const V d(ray.dir);
    const V f = V(ray.org) - V(sphere.centre);
    const Real a = math::dot(d, d);
    const Real halfB = math::dot(f, d);
    const Real c = math::dot(f, f) - r * r;
    // halfB^2 - a c = a (r^2 - l^2), l the distance of the ray's line from the centre: the plain
    // form subtracts two nearly equal large terms when the sphere is small and far away.
    const Real l = math::length(f - (halfB / a) * d);
    Real roots[2];
    if (!quadraticRoots(a, halfB, c, a * (r - l) * (r + l), roots[0], roots[1])) return false;
    for (const Real t : roots) {
        if (!(t >= tmin && t <= tmax)) continue;
        out = {t, math::normalize(f + t * d)};
        return true;
    }
    return false;
}

}  // namespace bvhlab
