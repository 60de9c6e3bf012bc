// The ray-cone test of NFF's `c`: the lateral surface of a truncated cone between its base and
// apex discs, open at both ends (no caps) and hit from either side. A cylinder is the case of
// equal radii, a true cone that of an apex radius 0. The ray is moved into the cone's frame (axis
// along +z from the base), where the surface is x^2 + y^2 = R(z)^2 with R linear in z.
#pragma once

#include <bvhlab/quadric.h>
#include <bvhlab/ray.h>

namespace bvhlab {

// NFF gives negative values to both radii of a cone of which only the inside is visible: the
// surface is that of |radius|, and the sign is left to shading. NFF calls the smaller radius the
// apex's; the surface does not depend on which end is which.
struct Cone {
    Vec3 base;
    float baseRadius;
    Vec3 apex;
    float apexRadius;

    // The box of the two end discs: a disc of radius r around a unit axis w reaches
    // r sqrt(1 - w_i^2) from its centre along axis i.
    Bounds3 bounds() const {
        const DVec3 b(base), a(apex);
        const DVec3 w = math::normalize(a - b);
        const DVec3 reach = math::sqrt(math::max(DVec3(0.0), 1.0 - w * w));
        const DVec3 baseReach = math::abs(double(baseRadius)) * reach,
                    apexReach = math::abs(double(apexRadius)) * reach;
        const DVec3 lower = math::min(b - baseReach, a - apexReach), upper = math::max(b + baseReach, a + apexReach);
        const DVec3 extent = math::max(math::abs(lower), math::abs(upper));
        return boundsRoundedOutward(lower, upper, 0x1p-45 * math::max(math::max(extent.x, extent.y), extent.z));
    }
    // The middle of the axis: the builders need a representative point, not a centre of mass.
    Vec3 centroid() const { return 0.5f * (base + apex); }
    // The unit normal at a point p on the lateral surface, as intersectCone gives it: the
    // gradient of x^2 + y^2 - R(z)^2, with R read off p itself (its distance from the axis).
    Vec3 normalAt(const Vec3& p) const {
        const Vec3 axis = apex - base;
        const float height = math::length(axis);
        const Vec3 w = axis / height;
        const Vec3 fromBase = p - base;
        const Vec3 radial = fromBase - math::dot(fromBase, w) * w;
        const float slope = (math::abs(apexRadius) - math::abs(baseRadius)) / height;
        const Vec3 gradient = radial - (slope * math::length(radial)) * w;
        // At the tip of a true cone the gradient vanishes: the axis away from the cone stands in.
        if (gradient == Vec3(0.0f)) return slope > 0.0f ? -w : w;
        return math::normalize(gradient);
    }
};

// Non-finite data; radii of opposite signs (NFF defines only both negative); a coincident base
// and apex, or both radii 0; or a squared axis length or radius that is not a normal float
// (under- or overflows): no test in float could place such a surface.
inline bool isDegenerate(const Cone& cone) {
    if (!isFinite(cone.base) || !isFinite(cone.apex) || !math::isfinite(cone.baseRadius) ||
        !math::isfinite(cone.apexRadius))
        return true;
    if ((cone.baseRadius < 0.0f && cone.apexRadius > 0.0f) || (cone.baseRadius > 0.0f && cone.apexRadius < 0.0f))
        return true;
    const Vec3 axis = cone.apex - cone.base;
    const float largerRadius = math::max(math::abs(cone.baseRadius), math::abs(cone.apexRadius));
    return !math::isnormal(math::dot(axis, axis)) || !math::isnormal(largerRadius * largerRadius);
}

// An orthonormal frame with w along the cone's axis (Duff et al., "Building an Orthonormal
// Basis, Revisited", JCGT 2017): no normalisation and no branch but the sign of w.z.
template <typename Real>
struct ConeFrameT {
    using V = glm::vec<3, Real>;
    V u, v, w;

    explicit ConeFrameT(const V& unitAxis) : w(unitAxis) {
        const Real sign = math::copysign(Real(1), w.z);
        const Real a = Real(-1) / (sign + w.z);
        const Real b = w.x * w.y * a;
        u = V(Real(1) + sign * w.x * w.x * a, sign * b, -sign * w.x);
        v = V(b, sign + w.y * w.y * a, -w.y);
    }
    V toLocal(const V& p) const { return V(math::dot(p, u), math::dot(p, v), math::dot(p, w)); }
    V toWorld(const V& p) const { return p.x * u + p.y * v + p.z * w; }
};

// The dot product of the (x, y) parts of two vectors, as GLM's of two 2D vectors.
template <typename Real>
Real dotXY(const glm::vec<3, Real>& a, const glm::vec<3, Real>& b) {
    const Real x = a.x * b.x, y = a.y * b.y;
    return x + y;
}

// Returns true and fills `out` with the nearest hit on the lateral surface at t in [tmin, tmax].
// The frame is rigid, so t is the same in it as in the world. Real = double gives the reference
// used by the tests.
template <typename Real>
inline bool intersectCone(const Ray& ray, const Cone& cone, Real tmin, Real tmax, QuadricHitT<Real>& out) {
    using V = glm::vec<3, Real>;
    if (isDegenerate(cone)) return false;
    const V axis = V(cone.apex) - V(cone.base);
    const Real height = math::length(axis);
    const ConeFrameT<Real> frame(axis / height);
    const V d = frame.toLocal(V(ray.dir));
    // The ray restarted at its point nearest the middle of the axis, t measured from there: the
    // quadratic's terms are then of the cone's size, as sphere.h's distance of the line from the
    // centre, not of the origin's distance, whose square would swamp the discriminant of hits near
    // the apex or at a shallow angle.
    const V fromBase = frame.toLocal(V(ray.org) - V(cone.base));
    const Real tShift = (Real(0.5) * height * d.z - math::dot(fromBase, d)) / math::dot(d, d);
    const V f = fromBase + tShift * d;
    const Real baseRadius = math::abs(Real(cone.baseRadius));
    const Real slope = (math::abs(Real(cone.apexRadius)) - baseRadius) / height;  // R(z) = baseRadius + slope z

    // fxy and dxy, the projections of f and d on the plane of the base, are f and d with z ignored.
    const V& fxy = f;
    const V& dxy = d;
    const Real radiusAtOrigin = baseRadius + slope * f.z;
    const Real a = dotXY(dxy, dxy) - (slope * d.z) * (slope * d.z);
    const Real halfB = dotXY(fxy, dxy) - slope * d.z * radiusAtOrigin;
    const Real c = dotXY(fxy, fxy) - radiusAtOrigin * radiusAtOrigin;
    // halfB^2 - a c = |m|^2 - cross^2, m = R(f.z) dxy - slope d.z fxy and cross = fxy x dxy (|cross|
    // / |dxy| is the distance of the projected ray from the axis): as for the sphere, no two large
    // nearly equal terms are subtracted unless the ray is nearly tangent.
    const V mxy = radiusAtOrigin * dxy - (slope * d.z) * fxy;
    const Real m = math::sqrt(dotXY(mxy, mxy));
    const Real cross = math::abs(fxy.x * dxy.y - fxy.y * dxy.x);
    Real roots[2];
    if (!quadraticRoots(a, halfB, c, (m - cross) * (m + cross), roots[0], roots[1])) return false;
    for (const Real tFromShift : roots) {
        const Real t = tShift + tFromShift;
        const V p = f + tFromShift * d;
        if (!(t >= tmin && t <= tmax && p.z >= Real(0) && p.z <= height)) continue;
        // The gradient of x^2 + y^2 - R(z)^2; at the tip of a true cone (R = 0) it vanishes, and
        // the axis away from the cone stands in for it.
        const V gradient(p.x, p.y, -slope * (baseRadius + slope * p.z));
        const V normal = gradient == V(Real(0)) ? V(Real(0), Real(0), -slope) : gradient;
        out = {t, math::normalize(frame.toWorld(normal))};
        return true;
    }
    return false;
}

}  // namespace bvhlab
