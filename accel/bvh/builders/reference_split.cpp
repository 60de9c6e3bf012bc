#include "accel/bvh/builders/reference_split.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

namespace bvhlab {

namespace {

// The neighbours of a float towards -inf and +inf (std::nextafter is a libm call, and this is
// the split's hottest line); finite arguments only.
inline float nextDown(float f) {
    if (f == 0.0f) return -std::numeric_limits<float>::denorm_min();
    const uint32_t bits = std::bit_cast<uint32_t>(f);
    return std::bit_cast<float>(f > 0.0f ? bits - 1 : bits + 1);
}
inline float nextUp(float f) { return -nextDown(-f); }

// The float box around a point computed in double.
Bounds3 outwardBox(const double (&p)[3]) {
    Vec3 lo, hi;
    for (int a = 0; a < 3; ++a) {
        const float f = float(p[a]);
        lo[a] = double(f) > p[a] ? nextDown(f) : f;
        hi[a] = double(f) < p[a] ? nextUp(f) : f;
    }
    return {lo, hi};
}

}  // namespace

std::pair<Bounds3, Bounds3> splitReference(const Triangle& triangle, const Bounds3& box, int axis, float position) {
    const Vec3* v[3] = {&triangle.v0, &triangle.v1, &triangle.v2};
    Bounds3 left, right;
    for (int i = 0; i < 3; ++i) {
        const Vec3& a = *v[i];
        const Vec3& b = *v[(i + 1) % 3];
        if (a[axis] <= position) left.extend(a);
        if (a[axis] >= position) right.extend(a);
        // The edge crosses the plane strictly between its ends: its crossing is in both parts.
        if ((a[axis] < position && position < b[axis]) || (b[axis] < position && position < a[axis])) {
            const double t = (double(position) - a[axis]) / (double(b[axis]) - a[axis]);
            double p[3];
            for (int c = 0; c < 3; ++c) p[c] = double(a[c]) + t * (double(b[c]) - a[c]);
            p[axis] = position;
            const Bounds3 crossing = outwardBox(p);
            left.extend(crossing);
            right.extend(crossing);
        }
    }
    left = intersectionOf(left, box);
    right = intersectionOf(right, box);
    left.upper[axis] = std::min(left.upper[axis], position);
    right.lower[axis] = std::max(right.lower[axis], position);
    return {left, right};
}

}  // namespace bvhlab
