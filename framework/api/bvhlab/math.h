// The vector and box types of the plugin API, and the functions of <cmath> and of GLM's geometry
// that the primitive tests need. Those are written here on the compiler's builtins, computed as
// <cmath> and GLM compute them: <cmath> alone is 24 k lines after the preprocessor and GLM's
// geometry 31 k, while everything a plugin includes is to stay within 15 k (docs/plugins.md).
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>

namespace bvhlab {

using Vec3 = glm::vec3;
using DVec3 = glm::dvec3;

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

namespace math {

// std::abs, std::sqrt, std::copysign, std::nextafter, std::fma, std::isfinite, std::isnan and
// std::isnormal of float and double.
inline float abs(float x) { return __builtin_fabsf(x); }
inline double abs(double x) { return __builtin_fabs(x); }
inline float sqrt(float x) { return __builtin_sqrtf(x); }
inline double sqrt(double x) { return __builtin_sqrt(x); }
inline float copysign(float x, float sign) { return __builtin_copysignf(x, sign); }
inline double copysign(double x, double sign) { return __builtin_copysign(x, sign); }
inline float nextafter(float x, float toward) { return __builtin_nextafterf(x, toward); }
inline float fma(float a, float b, float c) { return __builtin_fmaf(a, b, c); }
template <typename Real>
bool isfinite(Real x) {
    return __builtin_isfinite(x);
}
template <typename Real>
bool isnan(Real x) {
    return __builtin_isnan(x);
}
template <typename Real>
bool isnormal(Real x) {
    return __builtin_isnormal(x);
}

// std::min and std::max (the first argument on a tie or a NaN).
template <typename T>
constexpr T min(T a, T b) {
    return b < a ? b : a;
}
template <typename T>
constexpr T max(T a, T b) {
    return a < b ? b : a;
}

// GLM's component-wise min, max, abs and sqrt.
template <typename Real>
glm::vec<3, Real> min(const glm::vec<3, Real>& a, const glm::vec<3, Real>& b) {
    return {b.x < a.x ? b.x : a.x, b.y < a.y ? b.y : a.y, b.z < a.z ? b.z : a.z};
}
template <typename Real>
glm::vec<3, Real> max(const glm::vec<3, Real>& a, const glm::vec<3, Real>& b) {
    return {a.x < b.x ? b.x : a.x, a.y < b.y ? b.y : a.y, a.z < b.z ? b.z : a.z};
}
template <typename Real>
glm::vec<3, Real> abs(const glm::vec<3, Real>& v) {
    return {abs(v.x), abs(v.y), abs(v.z)};
}
template <typename Real>
glm::vec<3, Real> sqrt(const glm::vec<3, Real>& v) {
    return {sqrt(v.x), sqrt(v.y), sqrt(v.z)};
}

// GLM's dot, cross, length and normalize, in GLM's order of operations.
template <typename Real>
Real dot(const glm::vec<3, Real>& a, const glm::vec<3, Real>& b) {
    const glm::vec<3, Real> products = a * b;
    return products.x + products.y + products.z;
}
template <typename Real>
glm::vec<3, Real> cross(const glm::vec<3, Real>& a, const glm::vec<3, Real>& b) {
    return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}
template <typename Real>
Real length(const glm::vec<3, Real>& v) {
    return sqrt(dot(v, v));
}
template <typename Real>
glm::vec<3, Real> normalize(const glm::vec<3, Real>& v) {
    return v * (Real(1) / sqrt(dot(v, v)));
}

}  // namespace math

inline int maxDimension(const Vec3& v) { return (v.x >= v.y && v.x >= v.z) ? 0 : (v.y >= v.z ? 1 : 2); }

inline bool isFinite(const Vec3& v) { return math::isfinite(v.x) && math::isfinite(v.y) && math::isfinite(v.z); }

// Axis-aligned bounding box; the empty box has lower = +inf and upper = -inf so that
// extending it by any point or box needs no special case.
struct Bounds3 {
    Vec3 lower{kInfinity};
    Vec3 upper{-kInfinity};

    Bounds3() = default;
    Bounds3(const Vec3& lo, const Vec3& hi) : lower(lo), upper(hi) {}
    explicit Bounds3(const Vec3& p) : lower(p), upper(p) {}

    bool isEmpty() const { return lower.x > upper.x || lower.y > upper.y || lower.z > upper.z; }
    void extend(const Vec3& p) {
        lower = math::min(lower, p);
        upper = math::max(upper, p);
    }
    void extend(const Bounds3& b) {
        lower = math::min(lower, b.lower);
        upper = math::max(upper, b.upper);
    }
    Vec3 diagonal() const { return upper - lower; }
    Vec3 center() const { return 0.5f * (lower + upper); }
    int largestAxis() const { return maxDimension(diagonal()); }

    // Half the surface area: the SAH only ever uses ratios of areas.
    float halfArea() const {
        if (isEmpty()) return 0.0f;
        const Vec3 d = diagonal();
        return d.x * d.y + d.y * d.z + d.z * d.x;
    }
};

inline Bounds3 unionOf(const Bounds3& a, const Bounds3& b) {
    return {math::min(a.lower, b.lower), math::max(a.upper, b.upper)};
}

// Empty (isEmpty()) when the boxes do not overlap.
inline Bounds3 intersectionOf(const Bounds3& a, const Bounds3& b) {
    return {math::max(a.lower, b.lower), math::min(a.upper, b.upper)};
}

}  // namespace bvhlab
