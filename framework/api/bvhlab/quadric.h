// What the sphere and cone tests share: their hit record, the two roots of the ray's quadratic
// computed without cancellation, and bounds rounded outward to float.
#pragma once

#include <bvhlab/math.h>

namespace bvhlab {

// Result of one ray-quadric test: t and the unit geometric normal, pointing away from the
// inside of the surface (whichever side the ray came from).
template <typename Real>
struct QuadricHitT {
    Real t;
    glm::vec<3, Real> normal;
};

// The roots t0 <= t1 of a t^2 + 2 halfB t + c = 0, given its reduced discriminant halfB^2 - a c,
// which the caller computes in a form that does not cancel. q = -(halfB + sign(halfB) sqrt(disc))
// adds two terms of one sign, and q/a, c/q then avoid the cancellation of -halfB +- sqrt(disc).
// A root at infinity (a = 0: the equation is linear) or at 0/0 (a tangent at t = 0) is dropped
// in favour of the other; false when there is no finite real root.
template <typename Real>
inline bool quadraticRoots(Real a, Real halfB, Real c, Real reducedDiscriminant, Real& t0, Real& t1) {
    if (!(reducedDiscriminant >= Real(0))) return false;  // also NaN
    const Real q = -(halfB + math::copysign(math::sqrt(reducedDiscriminant), halfB));
    t0 = q / a;
    t1 = c / q;
    if (!math::isfinite(t0)) t0 = t1;
    if (!math::isfinite(t1)) t1 = t0;
    if (!math::isfinite(t0)) return false;
    if (t0 > t1) {
        const Real larger = t0;
        t0 = t1;
        t1 = larger;
    }
    return true;
}

// The float box around [lower, upper] computed in double, widened by `pad` (a bound on the
// double's own rounding) and rounded outward, so the exact surface lies inside it.
inline Bounds3 boundsRoundedOutward(const DVec3& lower, const DVec3& upper, double pad) {
    Bounds3 b;
    for (int i = 0; i < 3; ++i) {
        b.lower[i] = math::nextafter(float(lower[i] - pad), -kInfinity);
        b.upper[i] = math::nextafter(float(upper[i] + pad), kInfinity);
    }
    return b;
}

}  // namespace bvhlab
