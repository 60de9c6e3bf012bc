// Vector types and the axis-aligned box every accelerator and reader shares.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>

namespace bvhlab {

using Vec3 = glm::vec3;
using DVec3 = glm::dvec3;

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

inline int maxDimension(const Vec3& v) {
    return (v.x >= v.y && v.x >= v.z) ? 0 : (v.y >= v.z ? 1 : 2);
}

inline bool isFinite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Axis-aligned bounding box; the empty box has lower = +inf and upper = -inf so that
// extending it by any point or box needs no special case.
struct Bounds3 {
    Vec3 lower{kInfinity};
    Vec3 upper{-kInfinity};

    Bounds3() = default;
    Bounds3(const Vec3& lo, const Vec3& hi) : lower(lo), upper(hi) {}
    explicit Bounds3(const Vec3& p) : lower(p), upper(p) {}

    bool isEmpty() const { return lower.x > upper.x || lower.y > upper.y || lower.z > upper.z; }
    void extend(const Vec3& p) { lower = glm::min(lower, p); upper = glm::max(upper, p); }
    void extend(const Bounds3& b) { lower = glm::min(lower, b.lower); upper = glm::max(upper, b.upper); }
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
    return {glm::min(a.lower, b.lower), glm::max(a.upper, b.upper)};
}

// Empty (isEmpty()) when the boxes do not overlap.
inline Bounds3 intersectionOf(const Bounds3& a, const Bounds3& b) {
    return {glm::max(a.lower, b.lower), glm::min(a.upper, b.upper)};
}

}  // namespace bvhlab
