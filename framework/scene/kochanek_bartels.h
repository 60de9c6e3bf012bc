// Kochanek-Bartels splines as BART's AFF animates with them: positions (and scales) as cubic
// Hermite segments, rotations as quaternion squad segments, both with the tangents of the
// keys' tension, continuity and bias. After the reference code of BART (Eberly's kbsplpos.c
// and kbsplrot.c): the first and the last key only shape the end tangents, so the curve runs
// from the second key's time to the last but one's and is clamped outside; a spline needs at
// least four keys and passes through every inner key exactly.
#pragma once

#include <bvhlab/math.h>
#include <glm/gtc/quaternion.hpp>

#include <span>
#include <vector>

namespace bvhlab {

struct SplineKey {
    double time = 0.0;
    double tension = 0.0, continuity = 0.0, bias = 0.0;
};

struct PositionKey : SplineKey {
    glm::dvec3 value{0.0};
};

// A rotation about an axis (need not be unit length) by an angle in radians.
struct RotationKey : SplineKey {
    glm::dvec3 axis{1.0, 0.0, 0.0};
    double angle = 0.0;
};

inline constexpr size_t kMinSplineKeys = 4;

class PositionSpline {
public:
    // keys: at least kMinSplineKeys, times not decreasing (the reader checks both).
    explicit PositionSpline(std::span<const PositionKey> keys);
    glm::dvec3 at(double time) const;
    double startTime() const { return segments_.front().tmin; }
    double endTime() const { return segments_.back().tmax; }

private:
    struct Segment {
        glm::dvec3 c0, c1, c2, c3;  // value(u) = c0 + u (c1 + u (c2 + u c3)), u in [0, 1]
        double tmin, tmax;
    };
    std::vector<Segment> segments_;
};

class RotationSpline {
public:
    explicit RotationSpline(std::span<const RotationKey> keys);
    glm::dquat at(double time) const;

private:
    struct Segment {
        glm::dquat p, a, b, q;  // squad(u) = slerp(2u(1-u), slerp(u, p, q), slerp(u, a, b))
        double tmin, tmax;
    };
    std::vector<Segment> segments_;
};

// The unit quaternion of a rotation by `angle` radians about `axis` (normalised; a zero axis
// gives the identity).
glm::dquat quaternionFromAxisAngle(const glm::dvec3& axis, double angle);

}  // namespace bvhlab
