// A native quadric primitive by value, sphere or cone, as leaves store them and the
// accelerators test them: one dispatch instead of one code path per kind.
#pragma once

#include "framework/core/cone.h"
#include "framework/core/sphere.h"

#include <variant>

namespace bvhlab {

using QuadricShape = std::variant<Sphere, Cone>;

inline Bounds3 boundsOf(const QuadricShape& shape) {
    return std::visit([](const auto& s) { return s.bounds(); }, shape);
}

inline bool isDegenerate(const QuadricShape& shape) {
    return std::visit([](const auto& s) { return isDegenerate(s); }, shape);
}

// The test of either kind (callers count it by shape.index(): 0 sphere, 1 cone).
template <typename Real>
inline bool intersectQuadric(const Ray& ray, const QuadricShape& shape, Real tmin, Real tmax, QuadricHitT<Real>& out) {
    if (const Sphere* sphere = std::get_if<Sphere>(&shape)) return intersectSphere(ray, *sphere, tmin, tmax, out);
    return intersectCone(ray, std::get<Cone>(shape), tmin, tmax, out);
}

}  // namespace bvhlab
