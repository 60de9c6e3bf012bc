#include "framework/scene/kochanek_bartels.h"

#include <algorithm>
#include <cmath>

namespace bvhlab {
namespace {

constexpr double kEpsilon = 1e-6;

// 2 (t2 - t1) / (tb - ta), the tangents' adjustment to uneven key spacing; 0 where keys share
// a time (BART's kitchen has such pairs), which makes the segment between them empty anyway.
double spacing(double t1, double t2, double ta, double tb) { return tb > ta ? 2.0 * (t2 - t1) / (tb - ta) : 0.0; }

// The outgoing tangent's weights at key k (of the step into k, then of the step out of k) and
// the incoming tangent's at key k (of the step out of k, then of the step into k).
struct TangentWeights {
    double previous, next;
};
TangentWeights outgoing(const SplineKey& k, double adjust) {
    const double scale = 0.5 * adjust * (1.0 - k.tension);
    return {scale * (1.0 + k.continuity) * (1.0 + k.bias), scale * (1.0 - k.continuity) * (1.0 - k.bias)};
}
TangentWeights incoming(const SplineKey& k, double adjust) {
    const double scale = 0.5 * adjust * (1.0 - k.tension);
    return {scale * (1.0 - k.continuity) * (1.0 + k.bias), scale * (1.0 + k.continuity) * (1.0 - k.bias)};
}

// The segment holding `time` and the parameter u in [0, 1] within it, clamped at both ends.
template <typename Segment>
std::pair<size_t, double> locate(const std::vector<Segment>& segments, double time) {
    if (!(segments.front().tmin < time)) return {0, 0.0};
    if (!(time < segments.back().tmax)) return {segments.size() - 1, 1.0};
    size_t i = 0;
    while (!(time < segments[i].tmax)) ++i;
    return {i, (time - segments[i].tmin) / (segments[i].tmax - segments[i].tmin)};
}

glm::dquat logOf(const glm::dquat& q) {
    const double angle = std::acos(std::clamp(q.w, -1.0, 1.0));
    const double s = std::sin(angle);
    const double coeff = std::abs(s) >= kEpsilon ? angle / s : 1.0;
    return {0.0, coeff * q.x, coeff * q.y, coeff * q.z};
}

glm::dquat expOf(const glm::dquat& q) {
    const double angle = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
    const double s = std::sin(angle);
    const double coeff = std::abs(s) >= kEpsilon ? s / angle : 1.0;
    return {std::cos(angle), coeff * q.x, coeff * q.y, coeff * q.z};
}

// Eberly's slerp: no shortest-path flip (the spline arranged its keys for that).
glm::dquat slerpOf(double u, const glm::dquat& p, const glm::dquat& q) {
    const double angle = std::acos(std::clamp(glm::dot(p, q), -1.0, 1.0));
    if (std::abs(angle) < kEpsilon) return p;
    const double s = std::sin(angle);
    return (std::sin((1.0 - u) * angle) / s) * p + (std::sin(u * angle) / s) * q;
}

}  // namespace

glm::dquat quaternionFromAxisAngle(const glm::dvec3& axis, double angle) {
    const double length = glm::length(axis);
    if (!(length > 0.0)) return {1.0, 0.0, 0.0, 0.0};
    const glm::dvec3 v = std::sin(0.5 * angle) / length * axis;
    return {std::cos(0.5 * angle), v.x, v.y, v.z};
}

PositionSpline::PositionSpline(std::span<const PositionKey> keys) {
    for (size_t i1 = 1; i1 + 2 < keys.size(); ++i1) {
        const PositionKey &k0 = keys[i1 - 1], &k1 = keys[i1], &k2 = keys[i1 + 1], &k3 = keys[i1 + 2];
        const glm::dvec3 step = k2.value - k1.value;
        const TangentWeights out = outgoing(k1, spacing(k1.time, k2.time, k0.time, k2.time));
        const TangentWeights in = incoming(k2, spacing(k1.time, k2.time, k1.time, k3.time));
        const glm::dvec3 tOut = out.next * step + out.previous * (k1.value - k0.value);
        const glm::dvec3 tIn = in.next * (k3.value - k2.value) + in.previous * step;
        segments_.push_back(
            {k1.value, tOut, 3.0 * step - 2.0 * tOut - tIn, -2.0 * step + tOut + tIn, k1.time, k2.time});
    }
}

glm::dvec3 PositionSpline::at(double time) const {
    const auto [i, u] = locate(segments_, time);
    const Segment& s = segments_[i];
    return s.c0 + u * (s.c1 + u * (s.c2 + u * s.c3));
}

RotationSpline::RotationSpline(std::span<const RotationKey> keys) {
    std::vector<glm::dquat> read(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) read[i] = quaternionFromAxisAngle(keys[i].axis, keys[i].angle);
    // Consecutive inner keys at an acute angle: BART walks the segments once and negates the
    // later key of a pair where needed, which the next segment then sees as its first; the key
    // after a segment enters that segment's tangent as read, unflipped, as BART's does.
    std::vector<glm::dquat> q = read;
    for (size_t i = 2; i + 1 < keys.size(); ++i) {
        if (glm::dot(q[i - 1], q[i]) < 0.0) q[i] = -q[i];
    }
    for (size_t i1 = 1; i1 + 2 < keys.size(); ++i1) {
        const RotationKey &k0 = keys[i1 - 1], &k1 = keys[i1], &k2 = keys[i1 + 1], &k3 = keys[i1 + 2];
        const glm::dquat &q0 = q[i1 - 1], &q1 = q[i1], &q2 = q[i1 + 1], &q3 = read[i1 + 2];
        const glm::dquat logStep = logOf(glm::conjugate(q1) * q2);
        const TangentWeights out = outgoing(k1, spacing(k1.time, k2.time, k0.time, k2.time));
        const TangentWeights in = incoming(k2, spacing(k1.time, k2.time, k1.time, k3.time));
        const glm::dquat tOut = out.next * logStep + out.previous * logOf(glm::conjugate(q0) * q1);
        const glm::dquat tIn = in.previous * logStep + in.next * logOf(glm::conjugate(q2) * q3);
        const glm::dquat a = q1 * expOf(0.5 * (tOut - logStep));
        const glm::dquat b = q2 * expOf(0.5 * (logStep - tIn));
        segments_.push_back({q1, a, b, q2, k1.time, k2.time});
    }
}

glm::dquat RotationSpline::at(double time) const {
    const auto [i, u] = locate(segments_, time);
    const Segment& s = segments_[i];
    return slerpOf(2.0 * u * (1.0 - u), slerpOf(u, s.p, s.q), slerpOf(u, s.a, s.b));
}

}  // namespace bvhlab
