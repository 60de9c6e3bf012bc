// Moving a ray's origin off the surface it starts on, robustly at any scale
// (Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems, 2019): a few ulps along the normal, in integer steps of the float
// representation, so the offset grows with the magnitude of the position; and a little more
// for the magnitude of the triangle left (below).
#pragma once

#include <bvhlab/triangle.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>

namespace bvhlab {

// `p` lies on the surface left; `n` is its geometric normal on the side the new ray leaves to
// (it need not be unit length but should be roughly so).
//
// Wächter and Binder bound the rounding error of p, coordinate by coordinate. A ray that
// leaves a triangle also meets that triangle's own rounding in the ray-triangle test, which
// grows with the magnitude of its vertices: on a ground z = 0 at x = 800, p moves 2^-16 up in
// z while the test's t for the ground comes out with errors around 1e-4, and the ray finds
// the ground it leaves (shadow acne; Stress.NoShadowAcneOnAGroundFarFromTheOrigin). So the
// origin also moves along n by 2^-18 of the vertices' largest coordinate (32 to 64 of its
// ulps): 0.4 mm on a 1 km scene.
//
// `magnitude` is the largest coordinate of the surface left (its own rounding grows with it).
inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& n, float magnitude) {
    constexpr float kOrigin = 1.0f / 32.0f;
    constexpr float kFloatScale = 1.0f / 65536.0f;
    constexpr float kIntScale = 256.0f;
    constexpr float kVertexScale = 1.0f / 262144.0f;  // 2^-18
    Vec3 result;
    for (int i = 0; i < 3; ++i) {
        const int32_t offset = int32_t(kIntScale * n[i]);
        const int32_t bits = std::bit_cast<int32_t>(p[i]);
        const float moved = std::bit_cast<float>(bits + (p[i] < 0.0f ? -offset : offset));
        result[i] = std::abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : moved;
    }
    return result + n * (kVertexScale * magnitude);
}

inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& n, const Triangle& leaving) {
    const Vec3 largest = glm::max(glm::max(glm::abs(leaving.v0), glm::abs(leaving.v1)), glm::abs(leaving.v2));
    return offsetRayOrigin(p, n, std::max(std::max(largest.x, largest.y), largest.z));
}

}  // namespace bvhlab
