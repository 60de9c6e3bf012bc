// A native quadric primitive by value, sphere or cone, as leaves store them and the
// accelerators test them: one dispatch instead of one code path per kind. (A tagged union
// rather than std::variant, whose header is 11 k lines after the preprocessor.)
#pragma once

#include <bvhlab/cone.h>
#include <bvhlab/sphere.h>

namespace bvhlab {

class QuadricShape {
public:
    QuadricShape(const Sphere& sphere) : sphere_(sphere), isCone_(false) {}
    QuadricShape(const Cone& cone) : cone_(cone), isCone_(true) {}

    // 0 for a sphere, 1 for a cone (std::variant<Sphere, Cone>'s index).
    size_t index() const { return isCone_ ? 1 : 0; }
    // The sphere or the cone it holds, or nullptr.
    const Sphere* sphere() const { return isCone_ ? nullptr : &sphere_; }
    const Cone* cone() const { return isCone_ ? &cone_ : nullptr; }

private:
    union {
        Sphere sphere_;
        Cone cone_;
    };
    bool isCone_;
};

inline Bounds3 boundsOf(const QuadricShape& shape) {
    return shape.cone() ? shape.cone()->bounds() : shape.sphere()->bounds();
}

inline bool isDegenerate(const QuadricShape& shape) {
    return shape.cone() ? isDegenerate(*shape.cone()) : isDegenerate(*shape.sphere());
}

// The test of either kind (callers count it by shape.index(): 0 sphere, 1 cone).
template <typename Real>
inline bool intersectQuadric(const Ray& ray, const QuadricShape& shape, Real tmin, Real tmax, QuadricHitT<Real>& out) {
    if (const Sphere* sphere = shape.sphere()) return intersectSphere(ray, *sphere, tmin, tmax, out);
    return intersectCone(ray, *shape.cone(), tmin, tmax, out);
}

}  // namespace bvhlab
