// Moving a ray's origin off the surface it starts on, robustly at any scale
// (Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems, 2019): a few ulps along the normal, in integer steps of the float
// representation, so the offset grows with the magnitude of the position.
#pragma once

#include "framework/math.h"

#include <bit>
#include <cstdint>

namespace bvhlab {

// `n` is the geometric normal on the side the new ray leaves to (it need not be unit length
// but should be roughly so).
inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& n) {
    constexpr float kOrigin = 1.0f / 32.0f;
    constexpr float kFloatScale = 1.0f / 65536.0f;
    constexpr float kIntScale = 256.0f;
    Vec3 result;
    for (int i = 0; i < 3; ++i) {
        const int32_t offset = int32_t(kIntScale * n[i]);
        const int32_t bits = std::bit_cast<int32_t>(p[i]);
        const float moved = std::bit_cast<float>(bits + (p[i] < 0.0f ? -offset : offset));
        result[i] = std::abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : moved;
    }
    return result;
}

}  // namespace bvhlab
